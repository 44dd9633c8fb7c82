#include "patching/curvature_sheet.hpp"

#include "core/io/xml_text.hpp"
#include "patching/plan_drawing.hpp"

#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace egg::patching {
namespace {

using plan::boundaryLoops;
using plan::centroidXY;
using plan::label;
using plan::Legend;
using plan::point;
using plan::pointList;
using plan::Projection;
using plan::wrap;

// Diverging ColorBrewer RdBu: blue for negative K, white at 0, red for positive; v in [-1, 1].
std::string divergingColour(double v) {
  static const std::array<std::array<double, 3>, 5> stops{
      {{33, 102, 172}, {146, 197, 222}, {247, 247, 247}, {244, 165, 130}, {178, 24, 43}}};
  const double s = (std::clamp(v, -1.0, 1.0) + 1.0) * 2.0;  // 0 .. 4
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  std::array<int, 3> c{};
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<int>(std::lround(stops[i][k] * (1 - f) + stops[i + 1][k] * f));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

constexpr int kHalfBins = 8;  // the K map uses 2 * 8 + 1 colours
double binValue(int bin) { return static_cast<double>(bin - kHalfBins) / kHalfBins; }

std::string number(double v) { return fmt::format("{:.3g}", v); }

// Throws InvalidInput when the drawing's parts do not fit together.
void validateDrawing(const CurvatureDrawing& drawing) {
  drawing.options.validate();
  if (drawing.surface == nullptr || drawing.surface->n_faces() == 0)
    throw InvalidInput("plan.svg: no surface to draw");
  const TriMesh& surface = *drawing.surface;
  const int nv = static_cast<int>(surface.n_vertices());
  if (drawing.gaussian.size() != 0 && drawing.gaussian.size() != nv)
    throw InvalidInput(fmt::format("plan.svg: {} curvature values for {} surface vertices",
                                   drawing.gaussian.size(), nv));
  if (drawing.coverage != nullptr && drawing.layout == nullptr)
    throw InvalidInput("plan.svg: cut-offs need the layout");
  const PatchLayout* layout = drawing.layout;
  const int patchCount = layout ? static_cast<int>(layout->patches.size()) : 0;
  if (!drawing.patchProblems.empty() &&
      static_cast<int>(drawing.patchProblems.size()) != patchCount)
    throw InvalidInput(fmt::format("plan.svg: {} patch problems for {} patches",
                                   drawing.patchProblems.size(), patchCount));
  if (layout && layout->patchSides.size() != layout->patches.size())
    throw InvalidInput("plan.svg: the layout is not finished (finishLayout)");
}

// The page's geometry.
struct Page {
  Projection proj;
  double margin = 0.0, titleHeight = 0.0, legendWidth = 0.0;
  double dx = 0.0;                         // the plan's width [m]
  double mapBottom = 0.0, mapRight = 0.0;  // [px]
};

// Page: the map on the left (width_px wide, at most 1.4 times as tall), the legend on the right.
Page pageOf(const CurvatureDrawing& drawing) {
  const BoundingBox box = boundingBox(*drawing.surface);
  Page page;
  page.margin = 30.0, page.titleHeight = drawing.title.empty() ? 0.0 : 34.0,
  page.legendWidth = 300.0;
  page.dx = std::max(box.size().x(), 1e-9);
  const double margin = page.margin, dx = page.dx, dy = std::max(box.size().y(), 1e-9);
  const double mapWidth = drawing.options.widthPx;
  Projection& proj = page.proj;
  proj.scale = std::min((mapWidth - 2 * margin) / dx, (1.4 * mapWidth - 2 * margin) / dy);
  proj.xmin = box.min.x(), proj.ymax = box.max.y();
  proj.left = margin, proj.top = margin + page.titleHeight;
  page.mapBottom = proj.py(box.min.y()), page.mapRight = proj.px(box.max.x());
  return page;
}

// The K colour map and the scale its colours were capped at.
struct CurvatureMap {
  std::string svg;
  double kScale = 1.0;            // |K| of the saturated colours
  double kMin = 0.0, kMax = 0.0;  // over the face means
};

// K colour map: faces binned into 17 colours, one path per colour (each face stroked in its own
// colour to hide the anti-aliasing seams between faces).
CurvatureMap curvatureMap(const CurvatureDrawing& drawing, const Projection& proj) {
  const TriMesh& surface = *drawing.surface;
  const int nv = static_cast<int>(surface.n_vertices());
  CurvatureMap out;
  const Eigen::VectorXd gaussian =
      drawing.gaussian.size() == nv ? drawing.gaussian : computeCurvature(surface).gaussian;
  std::vector<double> faceK(surface.n_faces());
  for (auto fh : surface.faces()) {
    const auto fv = faceVertices(surface, fh.idx());
    faceK[fh.idx()] = (gaussian(fv[0]) + gaussian(fv[1]) + gaussian(fv[2])) / 3.0;
  }
  std::vector<double> magnitudes(faceK.size());
  std::transform(faceK.begin(), faceK.end(), magnitudes.begin(),
                 [](double k) { return std::abs(k); });
  const size_t rank = std::min(magnitudes.size() - 1,
                               static_cast<size_t>(std::floor(drawing.options.curvaturePercentile /
                                                              100.0 * (magnitudes.size() - 1))));
  std::nth_element(magnitudes.begin(), magnitudes.begin() + rank, magnitudes.end());
  const double kScale = out.kScale = std::max(magnitudes[rank], 1e-9);
  const auto [kMinIt, kMaxIt] = std::minmax_element(faceK.begin(), faceK.end());
  out.kMin = *kMinIt, out.kMax = *kMaxIt;
  std::vector<plan::PathChunks> bins;
  for (int b = 0; b <= 2 * kHalfBins; ++b)
    bins.emplace_back(
        fmt::format("fill=\"{0}\" stroke=\"{0}\" stroke-width=\"0.6\" stroke-linejoin=\"round\"",
                    divergingColour(binValue(b))));
  std::string d;
  for (auto fh : surface.faces()) {
    const int bin =
        static_cast<int>(std::lround(std::clamp(faceK[fh.idx()] / kScale, -1.0, 1.0) * kHalfBins)) +
        kHalfBins;
    const auto fv = faceVertices(surface, fh.idx());
    d.clear();
    for (int k = 0; k < 3; ++k)
      d.append(k == 0 ? "M" : "L")
          .append(point(proj, toEigen(surface.point(TriMesh::VertexHandle(fv[k])))));
    d += "Z";
    bins[bin].add(d);
  }
  std::string& body = out.svg;
  body += "<g id=\"curvature-map\">\n";
  for (auto& bin : bins) body += bin.finish();
  body += "</g>\n";
  return out;
}

// Cut-offs: grey under a hatch (group opacity, so overlapping face strokes do not show).
std::string cutOffsSvg(const CurvatureDrawing& drawing, const Projection& proj) {
  std::string body;
  const TriMesh& lm = drawing.layout->mesh.mesh;
  for (size_t c = 0; c < drawing.coverage->cutOffs.size(); ++c) {
    const CutOff& cut = drawing.coverage->cutOffs[c];
    plan::PathChunks grey("fill=\"#808080\" stroke=\"#808080\" stroke-width=\"0.6\"");
    plan::PathChunks hatch("fill=\"url(#hatch-cutoff)\"");
    for (const auto& d :
         plan::facePaths(lm, cut.faces, proj, fmt::format("curvature.svg: cut-off {}", c))) {
      grey.add(d);
      hatch.add(d);
    }
    body += fmt::format("<g id=\"cutoff-{}\" class=\"cutoff\"><g opacity=\"0.45\">{}</g>{}</g>\n",
                        c, grey.finish(), hatch.finish());
    const Eigen::Vector3d at = plan::cutOffLabelPoint(lm, cut);
    body += label(proj.px(at.x()), proj.py(at.y()) + 4,
                  "cut-off " + plan::plainNumber(cut.areaM2, cut.areaM2 < 10.0 ? 1 : 0) + " m²", 11,
                  " fill=\"#333\"");
  }
  return body;
}

// Design outline and holes (the loop with the largest plan area is the outline).
std::string outlineSvg(const TriMesh& surface, const Projection& proj) {
  std::string body;
  auto loops = boundaryLoops(surface);
  const size_t outer = plan::outerLoop(loops);
  for (size_t i = 0; i < loops.size(); ++i)
    body += fmt::format(
        "<polygon id=\"{}\" fill=\"none\" stroke=\"#1a1a1a\" stroke-width=\"2.5\" "
        "stroke-linejoin=\"round\" points=\"{}\"/>\n",
        i == outer ? std::string("outline") : fmt::format("hole-{}", i < outer ? i : i - 1),
        pointList(proj, loops[i]));
  return body;
}

// Patch outlines with their ids; infeasible ones hatched, labelled with the index of their reason.
// The outlines go to `body`, the ids to `labels`, the distinct problems, in order of first
// appearance, to `reasons`.
void patchOutlinesSvg(const CurvatureDrawing& drawing, const Projection& proj, std::string& body,
                      std::string& labels, std::vector<std::string>& reasons) {
  const PatchLayout* layout = drawing.layout;
  const int patchCount = layout ? static_cast<int>(layout->patches.size()) : 0;
  for (int p = 0; p < patchCount; ++p) {
    const std::string problem = drawing.patchProblems.empty() ? "" : drawing.patchProblems[p];
    int reason = -1;
    if (!problem.empty()) {
      const auto it = std::find(reasons.begin(), reasons.end(), problem);
      reason = static_cast<int>(it - reasons.begin());
      if (it == reasons.end()) reasons.push_back(problem);
    }
    const auto outline = plan::patchOutline(*layout, p);
    body += fmt::format(
        "<polygon id=\"patch-{}\" class=\"patch{}\" fill=\"{}\" stroke=\"#000\" stroke-width=\"2\" "
        "stroke-linejoin=\"round\" points=\"{}\"/>\n",
        p, reason >= 0 ? " infeasible" : "", reason >= 0 ? "url(#hatch-infeasible)" : "none",
        pointList(proj, outline));
    const Eigen::Vector2d c = centroidXY(outline);
    labels += label(proj.px(c.x()), proj.py(c.y()) + 6,
                    reason >= 0 ? fmt::format("{} [{}]", p, reason + 1) : std::to_string(p), 17,
                    fmt::format(" id=\"patch-label-{}\" font-weight=\"bold\"", p));
  }
}

// Injectivity circles, then the p_max markers and their labels on top of everything. The circles
// go to `body` (a note for each that encloses the whole surface to `notes`), the markers to
// `labels`.
void circlesAndPeaksSvg(const CurvatureDrawing& drawing, const Page& page, std::string& body,
                        std::string& labels, std::vector<std::string>& notes) {
  const Projection& proj = page.proj;
  for (size_t i = 0; i < drawing.circles.size(); ++i) {
    const InjectivityCircle& circle = drawing.circles[i];
    body += fmt::format(
        "<g id=\"circle-{}\" class=\"circle\" fill=\"none\" stroke=\"#7b1fa2\" "
        "stroke-width=\"2.5\" "
        "stroke-dasharray=\"9 5\" stroke-linejoin=\"round\">\n",
        i);
    for (const auto& line : circle.polylines)
      body += fmt::format("<{} points=\"{}\"/>\n", line.closed ? "polygon" : "polyline",
                          pointList(proj, line.positions));
    body += "</g>\n";
    if (circle.coversSurface)
      notes.push_back(fmt::format("circle {} (r = {} m) encloses the whole surface", i,
                                  number(circle.radiusM)));
  }
  std::vector<std::pair<Eigen::Vector3d, std::string>> markers;
  std::set<int> peakVertices;
  for (const auto& peak : drawing.peaks) {
    markers.emplace_back(peak.position, fmt::format("K {} /m², r = {} m", number(peak.gaussianMax),
                                                    number(peak.radiusM)));
    peakVertices.insert(peak.vertex);
  }
  for (const auto& circle : drawing.circles)
    if (!peakVertices.count(circle.peakVertex))
      markers.emplace_back(circle.centre, fmt::format("r = {} m", number(circle.radiusM)));
  // Markers first, then their labels where they overlap no marker, no other label and stay on
  // the map; a label with no free place goes to the legend's notes.
  plan::LabelLayout layout(page.mapRight + 0.5 * page.margin, page.mapBottom + 18);
  for (const auto& [at, text] : markers)
    layout.reserve(plan::LabelLayout::boxAround(proj.px(at.x()), proj.py(at.y()), 1, 1, 10));
  for (size_t i = 0; i < markers.size(); ++i) {
    const double x = proj.px(markers[i].first.x()), y = proj.py(markers[i].first.y());
    labels += fmt::format(
        "<g id=\"pmax-{}\" class=\"pmax\"><circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"6\" "
        "fill=\"#7b1fa2\" stroke=\"#fff\" "
        "stroke-width=\"2\"/><path d=\"M{:.1f},{:.1f}h8M{:.1f},{:.1f}v8\" stroke=\"#fff\" "
        "stroke-width=\"1.5\"/></g>\n",
        i, x, y, x - 4, y, x, y - 4);
    const std::string text = fmt::format("p{}  {}", i, markers[i].second);
    const size_t chars = text.size();
    const double half = 0.5 * (0.62 * 12 * static_cast<double>(chars) + 4.0);
    std::vector<Eigen::Vector2d> candidates;
    for (int ring = 0; ring < 4; ++ring) {
      const double dy = 16.0 * ring;
      for (const Eigen::Vector2d& c :
           {Eigen::Vector2d(x + 10 + half, y - 8 - dy), Eigen::Vector2d(x - 10 - half, y - 8 - dy),
            Eigen::Vector2d(x + 10 + half, y + 14 + dy),
            Eigen::Vector2d(x - 10 - half, y + 14 + dy)})
        candidates.push_back(c);
    }
    Eigen::Vector2d at;
    if (layout.place(candidates, chars, 1, 12, at))
      labels += label(at.x(), at.y() + 4, text, 12, " fill=\"#4a0072\"");
    else
      notes.push_back(text + " (label left out on the map: no free place)");
  }
}

// The scale bar's top edge [px].
double scaleBarY(const Page& page) { return page.mapBottom + 24; }

// Scale bar (a round length near a fifth of the plan's width) and north arrow, under the map.
std::string scaleBarSvg(const Page& page) {
  return plan::scaleBarSvg(page.proj, page.dx, page.margin, scaleBarY(page), page.mapRight - 10);
}

// Legend.
Legend legendOf(const CurvatureDrawing& drawing, const Page& page, const CurvatureMap& kMap,
                const std::vector<std::string>& reasons, const std::vector<std::string>& notes) {
  const double kScale = kMap.kScale;
  Legend legend;
  legend.x = page.mapRight + page.margin, legend.y = page.proj.top;
  legend.text("Gaussian curvature K [1/m²]", 13, " font-weight=\"bold\"");
  const double barWidth = 240.0, cell = barWidth / (2 * kHalfBins + 1);
  for (int b = 0; b <= 2 * kHalfBins; ++b)
    legend.svg += fmt::format(
        "<rect x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"14\" fill=\"{}\"/>\n",
        legend.x + b * cell, legend.y, cell + 0.3, divergingColour(binValue(b)));
  legend.svg += fmt::format(
      "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"14\" fill=\"none\" "
      "stroke=\"#555\"/>\n",
      legend.x, legend.y, barWidth);
  legend.y += 16;
  for (auto [frac, text, anchor] : {std::tuple{0.0, fmt::format("−{}", number(kScale)), "start"},
                                    std::tuple{0.5, std::string("0"), "middle"},
                                    std::tuple{1.0, fmt::format("+{}", number(kScale)), "end"}})
    legend.svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" text-anchor=\"{}\">{}</text>\n",
        legend.x + frac * barWidth, legend.y + 11, anchor, escapeXml(text));
  legend.y += 16;
  legend.text(fmt::format("colours capped at the {:g}th percentile of |K|",
                          drawing.options.curvaturePercentile),
              10);
  legend.text(fmt::format("K from {} to {} /m² (face means)", number(kMap.kMin), number(kMap.kMax)),
              10);
  legend.gap(10);
  legend.item("<path d=\"M0,7h30\" stroke=\"#1a1a1a\" stroke-width=\"2.5\"/>",
              "design outline and holes");
  legend.item(
      "<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"none\" stroke=\"#000\" "
      "stroke-width=\"2\"/>",
      "patch outline and id");
  legend.item(
      "<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"url(#hatch-infeasible)\" "
      "stroke=\"#000\" stroke-width=\"2\"/>",
      "infeasible patch  [reason]");
  legend.item(
      "<path d=\"M0,7h30\" stroke=\"#7b1fa2\" stroke-width=\"2.5\" stroke-dasharray=\"9 5\"/>",
      "injectivity circle r = π/√K_max");
  legend.item(
      "<circle cx=\"15\" cy=\"7\" r=\"6\" fill=\"#7b1fa2\" stroke=\"#fff\" stroke-width=\"2\"/>",
      "p_max, peak of K");
  legend.item(
      "<rect x=\"1\" y=\"1\" width=\"28\" height=\"12\" fill=\"#b8b8b8\"/><rect x=\"1\" y=\"1\" "
      "width=\"28\" height=\"12\" "
      "fill=\"url(#hatch-cutoff)\"/>",
      "cut-off (not covered by a patch)");
  if (!reasons.empty()) {
    legend.gap(8);
    legend.text("Infeasible patches", 13, " font-weight=\"bold\"");
    for (size_t r = 0; r < reasons.size(); ++r) {
      const auto lines = wrap(fmt::format("[{}] {}", r + 1, reasons[r]), 44);
      for (const auto& line : lines) legend.text(line, 11);
    }
  }
  if (drawing.coverage != nullptr || !notes.empty()) {
    legend.gap(8);
    if (drawing.coverage != nullptr)
      legend.text(fmt::format("coverage {:.1f} % of {} m²", 100.0 * drawing.coverage->fraction,
                              plan::plainNumber(drawing.coverage->surfaceAreaM2)),
                  11);
    for (const auto& note : notes)
      for (const auto& line : wrap(note, 44)) legend.text(line, 11);
  }
  legend.gap(8);
  legend.text("plan view: xy projection, z up, metres", 10, " fill=\"#555\"");
  return legend;
}

// The SVG document round the map's body and the legend.
std::string documentSvg(const CurvatureDrawing& drawing, const Page& page, const std::string& body,
                        const Legend& legend) {
  const double margin = page.margin;
  const double width = legend.x + page.legendWidth;
  const double height = std::max(scaleBarY(page) + 40, legend.y + margin);
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 "
      "0 {0:.0f} {1:.0f}\" "
      "data-px-per-m=\"{2:.9g}\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n",
      width, height, page.proj.scale);
  svg +=
      "<defs>\n"
      "<pattern id=\"hatch-cutoff\" width=\"8\" height=\"8\" patternUnits=\"userSpaceOnUse\" "
      "patternTransform=\"rotate(45)\">"
      "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"8\" stroke=\"#444\" stroke-width=\"1.1\"/></pattern>\n"
      "<pattern id=\"hatch-infeasible\" width=\"10\" height=\"10\" patternUnits=\"userSpaceOnUse\" "
      "patternTransform=\"rotate(-45)\">"
      "<rect width=\"10\" height=\"10\" fill=\"#9e9e9e\" fill-opacity=\"0.45\"/>"
      "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"10\" stroke=\"#424242\" "
      "stroke-width=\"2\"/></pattern>\n"
      "</defs>\n";
  svg += fmt::format("<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n");
  if (!drawing.title.empty())
    svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"20\" font-weight=\"bold\">{}</text>\n", margin,
        margin + 10, escapeXml(drawing.title));
  svg += body + legend.svg + "</svg>\n";
  return svg;
}

}  // namespace

void CurvatureSheetOptions::validate() const {
  if (!(widthPx >= 200.0 && widthPx <= 20000.0))
    throw InvalidInput(
        fmt::format("CurvatureSheetOptions.width_px must be in [200, 20000], got {}", widthPx));
  if (!(curvaturePercentile > 0.0 && curvaturePercentile <= 100.0))
    throw InvalidInput(
        fmt::format("CurvatureSheetOptions.curvature_percentile must be in (0, 100], got {}",
                    curvaturePercentile));
}

std::string curvatureSheetSvg(const CurvatureDrawing& drawing) {
  validateDrawing(drawing);
  const Page page = pageOf(drawing);
  const CurvatureMap kMap = curvatureMap(drawing, page.proj);
  std::string body = kMap.svg;
  if (drawing.coverage != nullptr) body += cutOffsSvg(drawing, page.proj);
  body += outlineSvg(*drawing.surface, page.proj);
  std::vector<std::string> reasons;  // distinct problems, in order of first appearance
  std::string labels;
  patchOutlinesSvg(drawing, page.proj, body, labels, reasons);
  std::vector<std::string> notes;
  circlesAndPeaksSvg(drawing, page, body, labels, notes);
  body += labels;
  body += scaleBarSvg(page);
  const Legend legend = legendOf(drawing, page, kMap, reasons, notes);
  return documentSvg(drawing, page, body, legend);
}

void writeCurvatureSheet(const std::filesystem::path& path, const CurvatureDrawing& drawing) {
  writeFileAtomically(path, curvatureSheetSvg(drawing));
}

}  // namespace egg::patching
