#include "patching/site_plan.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"
#include "patching/plan_drawing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg::patching {
namespace {
namespace site {

using plan::LabelLayout;
using plan::Projection;

// Colours shared with planar.svg (U blue, V orange) so a member reads the same on every sheet.
constexpr const char* kColourU = "#1f6fb4";
constexpr const char* kColourV = "#d9822b";
constexpr const char* kInfeasible = "#c62828";

void validate(const SitePlanDrawing& d) {
  if (d.surface == nullptr || d.surface->n_faces() == 0)
    throw InvalidInput("plan.svg: no surface to draw");
  if (!(d.widthPx >= 200.0 && d.widthPx <= 20000.0))
    throw InvalidInput(
        fmt::format("plan.svg: width_px must be in [200, 20000], got {}", d.widthPx));
  if (!d.generalised.empty() && d.layout == nullptr)
    throw InvalidInput("plan.svg: generalised patches need the layout");
  const int patches = d.layout ? static_cast<int>(d.layout->patches.size()) : 0;
  if (d.layout && d.layout->patchSides.size() != d.layout->patches.size())
    throw InvalidInput("plan.svg: the layout is not finished (finishLayout)");
  if (!d.patchProblems.empty() && static_cast<int>(d.patchProblems.size()) != patches)
    throw InvalidInput(
        fmt::format("plan.svg: {} patch problems for {} patches", d.patchProblems.size(), patches));
  if (!d.patchAreasM2.empty() && static_cast<int>(d.patchAreasM2.size()) != patches)
    throw InvalidInput(
        fmt::format("plan.svg: {} patch areas for {} patches", d.patchAreasM2.size(), patches));
  if (d.coverage != nullptr && d.layout == nullptr)
    throw InvalidInput("plan.svg: cut-offs need the layout");
  for (size_t m = 0; m < d.members.size(); ++m)
    for (const auto& p : d.members[m].points)
      if (!p.allFinite()) throw InvalidInput(fmt::format("plan.svg: member {} has a NaN point", m));
  for (const auto& s : d.supports)
    if (!s.position.allFinite())
      throw InvalidInput(fmt::format("plan.svg: support {} has a NaN position", s.id));
}

// The page: room for the y dimension left of the map, the x dimensions and the scale bar under it,
// the legend column right of it.
struct Page {
  Projection proj;
  BoundingBox box;
  double margin = 30.0, title = 0.0, legendWidth = 320.0;
  double mapLeft = 0.0, mapTop = 0.0, mapRight = 0.0, mapBottom = 0.0;
  double width = 0.0;
};

Page pageOf(const SitePlanDrawing& d) {
  Page page;
  page.box = boundingBox(*d.surface);
  page.title = d.title.empty() ? 0.0 : 34.0;
  const double dx = std::max(page.box.size().x(), 1e-9), dy = std::max(page.box.size().y(), 1e-9);
  const double dimRoom = 70.0;
  Projection& proj = page.proj;
  proj.scale = std::min((d.widthPx - 2 * page.margin - dimRoom) / dx,
                        (1.4 * d.widthPx - 2 * page.margin) / dy);
  proj.xmin = page.box.min.x(), proj.ymax = page.box.max.y();
  proj.left = page.margin + dimRoom, proj.top = page.margin + page.title + 10.0;
  page.mapLeft = proj.left, page.mapTop = proj.top;
  page.mapRight = proj.px(page.box.max.x()), page.mapBottom = proj.py(page.box.min.y());
  page.width = page.mapRight + page.margin + page.legendWidth;
  return page;
}

// The surface in plan: filled, holes left white (even-odd), outline and holes stroked.
std::string surfaceSvg(const TriMesh& surface, const Projection& proj, int& holes) {
  const auto loops = plan::boundaryLoops(surface);
  const size_t outer = plan::outerLoop(loops);
  std::string d;
  for (const auto& loop : loops) d += "M" + plan::pointList(proj, loop) + "Z";
  std::string out = fmt::format(
      "<path id=\"surface\" fill=\"#f4f0e6\" fill-rule=\"evenodd\" stroke=\"none\" d=\"{}\"/>\n",
      d);
  holes = 0;
  for (size_t i = 0; i < loops.size(); ++i) {
    const std::string id = i == outer ? std::string("outline") : fmt::format("hole-{}", holes++);
    out += fmt::format(
        "<polygon id=\"{}\" fill=\"none\" stroke=\"#1a1a1a\" stroke-width=\"2.5\" "
        "stroke-linejoin=\"round\" points=\"{}\"/>\n",
        id, plan::pointList(proj, loops[i]));
  }
  return out;
}

// Members: one path per family and weight, so the Yas's thousands of members stay small.
std::string membersSvg(const SitePlanDrawing& d, const Projection& proj) {
  std::vector<plan::PathChunks> paths;  // [2 * (family U?) + (boundary?)]
  for (int u = 0; u < 2; ++u)
    for (int b = 0; b < 2; ++b)
      paths.emplace_back(fmt::format("class=\"members-{}{}\" stroke=\"{}\" stroke-width=\"{}\"",
                                     u ? "u" : "v", b ? " boundary" : "", u ? kColourU : kColourV,
                                     b ? "1.6" : "0.7"));
  std::string path;
  for (const auto& m : d.members) {
    if (m.points.size() < 2) continue;
    path.clear();
    for (size_t i = 0; i < m.points.size(); ++i)
      path.append(i == 0 ? "M" : "L").append(plan::point(proj, m.points[i]));
    paths[2 * (m.familyU ? 1 : 0) + (m.boundary ? 1 : 0)].add(path);
  }
  std::string out = "<g id=\"members\" fill=\"none\" stroke-linejoin=\"round\">\n";
  for (auto& p : paths) out += p.finish();
  return out + "</g>\n";
}

// Cut-offs: grey under a single hatch (group opacity, so the faces' strokes do not show seams).
std::string cutOffsSvg(const SitePlanDrawing& d, const Projection& proj) {
  std::string out;
  const TriMesh& lm = d.layout->mesh.mesh;
  for (size_t c = 0; c < d.coverage->cutOffs.size(); ++c) {
    plan::PathChunks grey("fill=\"#cfcfcf\" stroke=\"#cfcfcf\" stroke-width=\"0.6\"");
    plan::PathChunks hatch("fill=\"url(#sp-hatch-cutoff)\"");
    for (const auto& path : plan::facePaths(lm, d.coverage->cutOffs[c].faces, proj,
                                            fmt::format("plan.svg: cut-off {}", c))) {
      grey.add(path);
      hatch.add(path);
    }
    out += fmt::format("<g id=\"cutoff-{}\" class=\"cutoff\"><g opacity=\"0.6\">{}</g>{}</g>\n", c,
                       grey.finish(), hatch.finish());
  }
  return out;
}

// Generalised patches: their faces tinted green, under the members.
std::string generalisedSvg(const SitePlanDrawing& d, const Projection& proj) {
  std::string out;
  if (d.generalised.empty()) return out;  // then there may be no layout (validate)
  const TriMesh& lm = d.layout->mesh.mesh;
  for (const auto& g : d.generalised) {
    plan::PathChunks tint("fill=\"#dcebd3\" stroke=\"#dcebd3\" stroke-width=\"0.6\"");
    for (const auto& path :
         plan::facePaths(lm, g.faces, proj, fmt::format("plan.svg: generalised patch {}", g.id)))
      tint.add(path);
    out +=
        fmt::format("<g id=\"generalised-{}\" class=\"generalised\">{}</g>\n", g.id, tint.finish());
  }
  return out;
}

// Characters of a label as the layout counts them: UTF-8 continuation bytes do not count.
size_t glyphs(const std::string& s) {
  return static_cast<size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// A label of one or two lines, at `at` (its box's centre), with its box as data.
std::string placedLabel(const std::string& id, const Eigen::Vector2d& at, const std::string& first,
                        const std::string& second, double size, const std::string& style) {
  const int lines = second.empty() ? 1 : 2;
  const size_t chars = std::max(glyphs(first), glyphs(second));
  const auto box = LabelLayout::boxAround(at.x(), at.y(), chars, lines, size);
  const double baseline = at.y() - 0.5 * 1.2 * size * (lines - 1) + 0.35 * size;
  std::string out = fmt::format(
      "<text id=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{:.0f}\" text-anchor=\"middle\" "
      "paint-order=\"stroke\" stroke=\"#fff\" stroke-width=\"3\" stroke-linejoin=\"round\" "
      "data-box=\"{:.1f} {:.1f} {:.1f} {:.1f}\"{}>",
      id, at.x(), baseline, size, box.x0, box.y0, box.x1, box.y1, style);
  out += "<tspan font-weight=\"bold\">" + escapeXml(first) + "</tspan>";
  if (!second.empty())
    out += fmt::format("<tspan x=\"{:.1f}\" dy=\"{:.1f}\" font-size=\"{:.0f}\">{}</tspan>", at.x(),
                       1.2 * size, 0.85 * size, escapeXml(second));
  return out + "</text>\n";
}

// One dimension line from a to b (page px, horizontal or vertical) with 45° ticks at its ends and
// at `stops` between, each stretch labelled with its length in metres where its text fits.
std::string dimensionSvg(const std::string& id, bool horizontal, double at,
                         const std::vector<double>& stopsPx, double scale, LabelLayout& labels,
                         int& leftOut) {
  std::string out = fmt::format("<g id=\"{}\" class=\"dimension\" stroke=\"#333\">\n", id);
  const auto xy = [&](double along, double across) {
    return horizontal ? Eigen::Vector2d(along, across) : Eigen::Vector2d(across, along);
  };
  const Eigen::Vector2d a = xy(stopsPx.front(), at), b = xy(stopsPx.back(), at);
  out += fmt::format("<path stroke-width=\"0.8\" d=\"M{:.1f},{:.1f}L{:.1f},{:.1f}\"/>\n", a.x(),
                     a.y(), b.x(), b.y());
  for (double s : stopsPx) {
    const Eigen::Vector2d p = xy(s, at);
    out += fmt::format("<path stroke-width=\"1.6\" d=\"M{:.1f},{:.1f}l-5,5m10,-10l-5,5\"/>\n",
                       p.x(), p.y());
  }
  for (size_t k = 0; k + 1 < stopsPx.size(); ++k) {
    const double lengthM = std::abs(stopsPx[k + 1] - stopsPx[k]) / scale;
    const std::string text = plan::plainNumber(lengthM, lengthM < 10.0 ? 2 : 1) + " m";
    const double mid = 0.5 * (stopsPx[k] + stopsPx[k + 1]);
    const double spanPx = std::abs(stopsPx[k + 1] - stopsPx[k]);
    // Horizontal text over a horizontal line; beside a vertical one (rotated text would need a
    // rotated box).
    const double textPx = 0.62 * 11 * static_cast<double>(glyphs(text)) + 4.0;
    if (textPx > spanPx) {
      ++leftOut;
      continue;
    }
    // Over a horizontal line; along a vertical one, reading upwards, on its left. The middle of
    // the stretch first, then towards its ends (a section mark may sit in the middle).
    Eigen::Vector2d where;
    LabelLayout::Box box;
    bool placed = false;
    for (double shift : {0.0, 0.3, -0.3, 0.45, -0.45}) {
      if (std::abs(shift) * spanPx * 2 + textPx > spanPx) continue;
      where = xy(mid + shift * spanPx, at - 9);
      box = horizontal ? LabelLayout::boxAround(where.x(), where.y(), glyphs(text), 1, 11)
                       : LabelLayout::Box{where.x() - 7.5, where.y() - 0.5 * textPx,
                                          where.x() + 7.5, where.y() + 0.5 * textPx};
      if ((placed = labels.placeBox(box))) break;
    }
    if (!placed) {
      ++leftOut;
      continue;
    }
    out += fmt::format(
        "<text id=\"{}-label{}\" x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" stroke=\"none\" "
        "fill=\"#222\" text-anchor=\"middle\"{} data-box=\"{:.1f} {:.1f} {:.1f} "
        "{:.1f}\">{}</text>\n",
        id, stopsPx.size() == 2 ? std::string() : fmt::format("-{}", k),
        horizontal ? where.x() : where.x() + 4, horizontal ? where.y() + 4 : where.y(),
        horizontal
            ? std::string()
            : fmt::format(" transform=\"rotate(-90 {:.1f} {:.1f})\"", where.x() + 4, where.y()),
        box.x0, box.y0, box.x1, box.y1, escapeXml(text));
  }
  return out + "</g>\n";
}

// Overall dimensions (and, with up to three holes, a chain giving their positions) under the map
// and left of it.
std::string dimensionsSvg(const SitePlanDrawing& d, const Page& page, LabelLayout& labels,
                          int& leftOut) {
  const Projection& proj = page.proj;
  std::vector<double> xs{page.mapLeft, page.mapRight}, ys{page.mapTop, page.mapBottom};
  const auto loops = plan::boundaryLoops(*d.surface);
  const size_t outer = plan::outerLoop(loops);
  std::vector<double> chainX = xs, chainY = ys;
  if (loops.size() >= 2 && loops.size() <= 4)
    for (size_t i = 0; i < loops.size(); ++i) {
      if (i == outer) continue;
      double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
      for (const auto& p : loops[i])
        x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()),
        y1 = std::max(y1, p.y());
      chainX.insert(chainX.end(), {proj.px(x0), proj.px(x1)});
      chainY.insert(chainY.end(), {proj.py(y1), proj.py(y0)});
    }
  std::sort(chainX.begin(), chainX.end());
  std::sort(chainY.begin(), chainY.end());
  std::string out;
  // Extension lines from the plan's extremes to the dimension lines.
  out += fmt::format(
      "<g stroke=\"#999\" stroke-width=\"0.5\"><path d=\"M{0:.1f},{2:.1f}V{3:.1f}M{1:.1f},{2:.1f}"
      "V{3:.1f}M{4:.1f},{5:.1f}H{6:.1f}M{4:.1f},{7:.1f}H{6:.1f}\"/></g>\n",
      page.mapLeft, page.mapRight, page.mapBottom + 4, page.mapBottom + 50, page.mapLeft - 4,
      page.mapTop, page.mapLeft - 50, page.mapBottom);
  if (chainX.size() > 2)
    out +=
        dimensionSvg("dim-x-chain", true, page.mapBottom + 22, chainX, proj.scale, labels, leftOut);
  out += dimensionSvg("dim-x", true, page.mapBottom + 46, xs, proj.scale, labels, leftOut);
  if (chainY.size() > 2)
    out +=
        dimensionSvg("dim-y-chain", false, page.mapLeft - 22, chainY, proj.scale, labels, leftOut);
  out += dimensionSvg("dim-y", false, page.mapLeft - 46, ys, proj.scale, labels, leftOut);
  return out;
}

// Section lines: dash-dot across the plan, a bubble with the name at each end and an arrow the way
// the section looks. The bubbles sit just outside the map, so they are reserved before any label.
std::string sectionsSvg(const SitePlanDrawing& d, const Page& page, LabelLayout& labels) {
  std::string out;
  for (const auto& s : d.sections) {
    const double at = s.alongX ? page.proj.py(s.atM) : page.proj.px(s.atM);
    const double a = s.alongX ? page.mapLeft - 12 : page.mapTop - 12;
    const double b = s.alongX ? page.mapRight + 12 : page.mapBottom + 12;
    const auto xy = [&](double u) {
      return s.alongX ? Eigen::Vector2d(u, at) : Eigen::Vector2d(at, u);
    };
    const Eigen::Vector2d p = xy(a), q = xy(b);
    out += fmt::format(
        "<g id=\"section-{0}\" class=\"section\"><path d=\"M{1:.1f},{2:.1f}L{3:.1f},{4:.1f}\" "
        "stroke=\"#111\" stroke-width=\"1\" stroke-dasharray=\"14 3 2 3\"/>\n",
        escapeXml(s.name), p.x(), p.y(), q.x(), q.y());
    for (const Eigen::Vector2d& end : {p, q}) {
      // Looking north (constant y): the arrow points up the page; looking west: left.
      const Eigen::Vector2d look = s.alongX ? Eigen::Vector2d(0, -1) : Eigen::Vector2d(-1, 0);
      const Eigen::Vector2d tip = end + 16 * look, side(-look.y(), look.x());
      out += fmt::format(
          "<path d=\"M{:.1f},{:.1f}L{:.1f},{:.1f}L{:.1f},{:.1f}z\" fill=\"#111\"/>"
          "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"8\" fill=\"#fff\" stroke=\"#111\" "
          "stroke-width=\"1.2\"/><text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" "
          "font-weight=\"bold\" text-anchor=\"middle\">{}</text>\n",
          tip.x(), tip.y(), end.x() + 6 * side.x(), end.y() + 6 * side.y(), end.x() - 6 * side.x(),
          end.y() - 6 * side.y(), end.x(), end.y(), end.x(), end.y() + 3.5, escapeXml(s.name));
      labels.reserve(
          LabelLayout::Box{std::min(end.x(), tip.x()) - 9, std::min(end.y(), tip.y()) - 9,
                           std::max(end.x(), tip.x()) + 9, std::max(end.y(), tip.y()) + 9});
    }
    out += "</g>\n";
  }
  return out;
}

struct Drawn {
  std::string body, labels;
  std::vector<std::string> reasons;  // distinct infeasibility reasons, in order
  int leftOut = 0;                   // labels with no free place
  int supportLabels = 0;
};

void patchesSvg(const SitePlanDrawing& d, const Projection& proj, LabelLayout& layout,
                Drawn& drawn) {
  const int patches = d.layout ? static_cast<int>(d.layout->patches.size()) : 0;
  for (int p = 0; p < patches; ++p) {
    const std::string problem = d.patchProblems.empty() ? "" : d.patchProblems[p];
    int reason = -1;
    if (!problem.empty()) {
      const auto it = std::find(drawn.reasons.begin(), drawn.reasons.end(), problem);
      reason = static_cast<int>(it - drawn.reasons.begin());
      if (it == drawn.reasons.end()) drawn.reasons.push_back(problem);
    }
    const auto outline = plan::patchOutline(*d.layout, p);
    if (reason >= 0)
      drawn.body += fmt::format(
          "<polygon id=\"infeasible-{}\" class=\"infeasible\" fill=\"url(#sp-hatch-infeasible)\" "
          "stroke=\"none\" points=\"{}\"/>\n",
          p, plan::pointList(proj, outline));
    drawn.body += fmt::format(
        "<polygon id=\"patch-{}\" class=\"patch{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\" "
        "stroke-linejoin=\"round\"{} points=\"{}\"/>\n",
        p, reason >= 0 ? " infeasible" : "", reason >= 0 ? kInfeasible : "#000",
        reason >= 0 ? " stroke-dasharray=\"10 4\"" : "", plan::pointList(proj, outline));
    const Eigen::Vector2d c = plan::centroidXY(outline);
    const std::string first =
        reason >= 0 ? fmt::format("P{} [{}]", p, reason + 1) : fmt::format("P{}", p);
    const double area = d.patchAreasM2.empty() ? 0.0 : d.patchAreasM2[p];
    const std::string second =
        area > 0.0 ? plan::plainNumber(area, area < 10.0 ? 1 : 0) + " m²" : "";
    Eigen::Vector2d at;
    if (layout.place(plan::candidatesAround(proj.px(c.x()), proj.py(c.y()), 14.0, 5),
                     std::max(glyphs(first), glyphs(second)), second.empty() ? 1 : 2, 15, at))
      drawn.labels += placedLabel(fmt::format("patch-label-{}", p), at, first, second, 15,
                                  reason >= 0 ? fmt::format(" fill=\"{}\"", kInfeasible) : "");
    else
      ++drawn.leftOut;
  }
}

void cutOffLabels(const SitePlanDrawing& d, const Projection& proj, LabelLayout& layout,
                  Drawn& drawn) {
  for (size_t c = 0; c < d.coverage->cutOffs.size(); ++c) {
    const CutOff& cut = d.coverage->cutOffs[c];
    const Eigen::Vector3d p = plan::cutOffLabelPoint(d.layout->mesh.mesh, cut);
    const std::string second = plan::plainNumber(cut.areaM2, cut.areaM2 < 10.0 ? 1 : 0) + " m²";
    Eigen::Vector2d at;
    if (layout.place(plan::candidatesAround(proj.px(p.x()), proj.py(p.y()), 10.0, 3),
                     std::max<size_t>(7, glyphs(second)), 2, 11, at))
      drawn.labels += placedLabel(fmt::format("cutoff-label-{}", c), at, "cut-off", second, 11,
                                  " fill=\"#444\"");
    else
      ++drawn.leftOut;
  }
}

void generalisedLabels(const SitePlanDrawing& d, const Projection& proj, LabelLayout& layout,
                       Drawn& drawn) {
  for (const auto& g : d.generalised) {
    CutOff region;
    region.faces = g.faces;
    const Eigen::Vector3d p = plan::cutOffLabelPoint(d.layout->mesh.mesh, region);
    const std::string second = (g.patchId >= 0 ? fmt::format("P{}, ", g.patchId) : std::string()) +
                               plan::plainNumber(g.areaM2, g.areaM2 < 10.0 ? 1 : 0) + " m²";
    Eigen::Vector2d at;
    if (layout.place(plan::candidatesAround(proj.px(p.x()), proj.py(p.y()), 10.0, 3),
                     std::max(glyphs(g.id), glyphs(second)), 2, 13, at))
      drawn.labels += placedLabel(fmt::format("generalised-label-{}", g.id), at, g.id, second, 13,
                                  " fill=\"#2f5d1e\"");
    else
      ++drawn.leftOut;
  }
}

void supportsSvg(const SitePlanDrawing& d, const Projection& proj, LabelLayout& layout,
                 Drawn& drawn) {
  drawn.body += "<g id=\"supports\">\n";
  for (const auto& s : d.supports) {
    const double x = proj.px(s.position.x()), y = proj.py(s.position.y());
    drawn.body +=
        s.bracket
            ? fmt::format(
                  "<rect id=\"support-{}\" class=\"bracket\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"8\" "
                  "height=\"8\" fill=\"#fff\" stroke=\"#111\" stroke-width=\"1.6\"/>\n",
                  escapeXml(s.id), x - 4, y - 4)
            : fmt::format(
                  "<path id=\"support-{}\" class=\"block\" d=\"M{:.1f},{:.1f}l5,8.5h-10z\" "
                  "fill=\"#111\" stroke=\"#fff\" stroke-width=\"0.8\"/>\n",
                  escapeXml(s.id), x, y - 5.5);
    layout.reserve(LabelLayout::boxAround(x, y, 1, 1, 8));
  }
  drawn.body += "</g>\n";
  // Ids after every marker is reserved, so no id covers another support.
  for (const auto& s : d.supports) {
    const double x = proj.px(s.position.x()), y = proj.py(s.position.y());
    std::vector<Eigen::Vector2d> candidates;
    for (const auto& c : plan::candidatesAround(x, y, 13.0, 2))
      if ((c - Eigen::Vector2d(x, y)).norm() > 1.0) candidates.push_back(c);
    Eigen::Vector2d at;
    if (layout.place(candidates, glyphs(s.id), 1, 9, at)) {
      const auto box = LabelLayout::boxAround(at.x(), at.y(), glyphs(s.id), 1, 9);
      drawn.labels += fmt::format(
          "<text id=\"support-label-{}\" x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"9\" "
          "text-anchor=\"middle\" fill=\"#111\" paint-order=\"stroke\" stroke=\"#fff\" "
          "stroke-width=\"2.5\" data-box=\"{:.1f} {:.1f} {:.1f} {:.1f}\">{}</text>\n",
          escapeXml(s.id), at.x(), at.y() + 3, box.x0, box.y0, box.x1, box.y1, escapeXml(s.id));
      ++drawn.supportLabels;
    } else {
      ++drawn.leftOut;
    }
  }
}

// The crown: the surface's highest point, with its level.
void crownSvg(const SitePlanDrawing& d, const Projection& proj, LabelLayout& layout, Drawn& drawn,
              double& crownZ) {
  const TriMesh& s = *d.surface;
  Eigen::Vector3d top(0, 0, -std::numeric_limits<double>::infinity());
  for (auto v : s.vertices())
    if (toEigen(s.point(v)).z() > top.z()) top = toEigen(s.point(v));
  crownZ = top.z();
  const double x = proj.px(top.x()), y = proj.py(top.y());
  drawn.body += fmt::format(
      "<g id=\"crown\"><circle cx=\"{0:.1f}\" cy=\"{1:.1f}\" r=\"5\" fill=\"#fff\" stroke=\"#111\" "
      "stroke-width=\"1.4\"/><path d=\"M{0:.1f},{2:.1f}v10M{3:.1f},{1:.1f}h10\" stroke=\"#111\" "
      "stroke-width=\"1.2\"/></g>\n",
      x, y, y - 5, x - 5);
  layout.reserve(LabelLayout::boxAround(x, y, 1, 1, 10));
  const std::string text = fmt::format("+{} m", plan::plainNumber(top.z(), 2));
  std::vector<Eigen::Vector2d> candidates;
  for (const auto& c : plan::candidatesAround(x, y, 16.0, 3))
    if ((c - Eigen::Vector2d(x, y)).norm() > 1.0) candidates.push_back(c);
  Eigen::Vector2d at;
  if (layout.place(candidates, glyphs(text), 1, 11, at))
    drawn.labels += placedLabel("crown-label", at, text, "", 11, "");
  else
    ++drawn.leftOut;
}

std::string legendSvg(const SitePlanDrawing& d, const Page& page, const Drawn& drawn, double crownZ,
                      double& bottom) {
  plan::Legend legend;
  legend.x = page.mapRight + page.margin, legend.y = page.mapTop;
  legend.text("Plan", 14, " font-weight=\"bold\"");
  legend.item("<path d=\"M0,7h30\" stroke=\"#1a1a1a\" stroke-width=\"2.5\"/>",
              "design outline and holes");
  legend.item(
      "<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"#f4f0e6\" stroke=\"#000\" "
      "stroke-width=\"2\"/>",
      "patch outline, id and surface area");
  legend.item(fmt::format("<path d=\"M0,7h30\" stroke=\"{}\" stroke-width=\"1.4\"/>", kColourU),
              "member, family U (thick: patch side)");
  legend.item(fmt::format("<path d=\"M0,7h30\" stroke=\"{}\" stroke-width=\"1.4\"/>", kColourV),
              "member, family V");
  legend.item("<path d=\"M15,1.5l5,8.5h-10z\" fill=\"#111\"/>", "support block, with its id");
  legend.item(
      "<rect x=\"11\" y=\"3\" width=\"8\" height=\"8\" fill=\"#fff\" stroke=\"#111\" "
      "stroke-width=\"1.6\"/>",
      "support bracket (wall steeper than 80°)");
  legend.item(fmt::format("<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" "
                          "fill=\"url(#sp-hatch-infeasible)\" stroke=\"{}\" stroke-width=\"2\" "
                          "stroke-dasharray=\"6 3\"/>",
                          kInfeasible),
              "infeasible patch [reason]: no grid");
  legend.item(
      "<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"#cfcfcf\"/><rect x=\"1\" y=\"1\" "
      "width=\"28\" height=\"12\" fill=\"url(#sp-hatch-cutoff)\"/>",
      "cut-off: surface no patch covers");
  if (!d.generalised.empty())
    legend.item("<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"#dcebd3\"/>",
                "generalised patch (Ch. 4), id, cut-file P, area");
  if (!d.sections.empty())
    legend.item(
        "<path d=\"M0,7h30\" stroke=\"#111\" stroke-dasharray=\"8 2 2 2\"/><circle cx=\"24\" "
        "cy=\"7\" r=\"6\" fill=\"#fff\" stroke=\"#111\"/>",
        "section line (elevations.svg)");
  legend.item(
      "<circle cx=\"15\" cy=\"7\" r=\"5\" fill=\"#fff\" stroke=\"#111\" stroke-width=\"1.4\"/>",
      fmt::format("crown, level +{} m (design z)", plan::plainNumber(crownZ, 2)));
  if (!drawn.reasons.empty()) {
    legend.gap(8);
    legend.text("Infeasible patches", 13, " font-weight=\"bold\"");
    for (size_t r = 0; r < drawn.reasons.size(); ++r)
      for (const auto& line : plan::wrap(fmt::format("[{}] {}", r + 1, drawn.reasons[r]), 46))
        legend.text(line, 11);
  }
  legend.gap(8);
  if (d.coverage != nullptr) {
    double cutM2 = 0.0;
    for (const auto& c : d.coverage->cutOffs) cutM2 += c.areaM2;
    legend.text(fmt::format("patches cover {:.1f} % of {} m²", 100.0 * d.coverage->fraction,
                            plan::plainNumber(d.coverage->surfaceAreaM2)),
                11);
    if (cutM2 > 0.0)
      legend.text(fmt::format("cut-offs {} m² in all", plan::plainNumber(cutM2)), 11);
  }
  legend.text("areas are measured on the surface, not in plan", 11);
  if (!d.supports.empty())
    legend.text(fmt::format("{} supports; all in supports.csv", d.supports.size()), 11);
  if (drawn.leftOut > 0)
    for (const auto& line :
         plan::wrap(fmt::format("{} {} left out where {} would overlap (all ids are in "
                                "patches.json, supports.csv and bom.csv)",
                                drawn.leftOut, drawn.leftOut == 1 ? "label" : "labels",
                                drawn.leftOut == 1 ? "it" : "they"),
                    46))
      legend.text(line, 11);
  legend.gap(6);
  legend.text("plan: xy projection, y north, dimensions in metres", 10, " fill=\"#555\"");
  bottom = legend.y;
  return legend.svg;
}

}  // namespace site
}  // namespace

std::string sitePlanSvg(const SitePlanDrawing& d) {
  using namespace site;  // NOLINT(google-build-using-namespace): this file's own helpers
  validate(d);
  const site::Page page = pageOf(d);
  const double barY = page.mapBottom + 78;
  // Labels stay on the map's page area, clear of the dimension lines' texts and the scale bar.
  LabelLayout labels(page.mapRight + 0.5 * page.margin, barY - 4);
  Drawn drawn;
  int holes = 0;
  drawn.body += surfaceSvg(*d.surface, page.proj, holes);
  if (d.coverage != nullptr) drawn.body += cutOffsSvg(d, page.proj);
  drawn.body += generalisedSvg(d, page.proj);
  drawn.body += membersSvg(d, page.proj);
  drawn.body += sectionsSvg(d, page, labels);
  drawn.body += dimensionsSvg(d, page, labels, drawn.leftOut);
  patchesSvg(d, page.proj, labels, drawn);
  double crownZ = 0.0;
  crownSvg(d, page.proj, labels, drawn, crownZ);
  if (d.coverage != nullptr) cutOffLabels(d, page.proj, labels, drawn);
  generalisedLabels(d, page.proj, labels, drawn);
  supportsSvg(d, page.proj, labels, drawn);
  double legendBottom = 0.0;
  const std::string legend = legendSvg(d, page, drawn, crownZ, legendBottom);
  const double height = std::max(barY + 40, legendBottom + page.margin);
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" "
      "viewBox=\"0 0 {0:.0f} {1:.0f}\" data-px-per-m=\"{2:.9g}\" data-labels-left-out=\"{3}\" "
      "font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n",
      page.width, height, page.proj.scale, drawn.leftOut);
  svg += fmt::format(
      "<defs>\n"
      "<pattern id=\"sp-hatch-cutoff\" width=\"7\" height=\"7\" patternUnits=\"userSpaceOnUse\" "
      "patternTransform=\"rotate(45)\"><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"7\" stroke=\"#666\" "
      "stroke-width=\"0.9\"/></pattern>\n"
      "<pattern id=\"sp-hatch-infeasible\" width=\"12\" height=\"12\" "
      "patternUnits=\"userSpaceOnUse\" patternTransform=\"rotate(45)\"><rect width=\"12\" "
      "height=\"12\" fill=\"#fde3e0\"/><path d=\"M0,0V12M0,0H12\" stroke=\"{}\" "
      "stroke-width=\"1.6\"/></pattern>\n"
      "</defs>\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n",
      kInfeasible);
  if (!d.title.empty())
    svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"20\" font-weight=\"bold\">{} – plan</text>\n",
        page.margin, page.margin + 10, escapeXml(d.title));
  svg += drawn.body + drawn.labels;
  svg += plan::scaleBarSvg(page.proj, page.box.size().x(), page.mapLeft, barY, page.mapRight - 10);
  return svg + legend + "</svg>\n";
}

}  // namespace egg::patching
