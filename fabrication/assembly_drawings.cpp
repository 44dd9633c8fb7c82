#include "fabrication/assembly_drawings.hpp"

#include "fabrication/assembly_labels.hpp"
#include "fabrication/pdf_pages.hpp"

#include <cairo.h>
#include <fmt/format.h>
#include <fmt/printf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

namespace egg::fabrication {
namespace {

std::string memberId(int patch, bool isU, int index) {
  return "P" + std::to_string(patch) + (isU ? "-U" : "-V") + std::to_string(index);
}

// A model-to-page mapping: model coordinates (metres, y up) fitted into a page's drawing area at
// the standard scale 1:n (model millimetres per page millimetre), centred.
struct View {
  double n = 1.0, x0 = 0.0, y1 = 0.0, px = 0.0, py = 0.0;
  Eigen::Vector2d page(const Eigen::Vector2d& m) const {
    return {px + (m.x() - x0) * 1000.0 / n, py + (y1 - m.y()) * 1000.0 / n};
  }
};

View fit(const std::vector<Eigen::Vector2d>& points, const PageFrame& f) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (points.empty()) lo = hi = Eigen::Vector2d::Zero();
  const Eigen::Vector2d size = (hi - lo).cwiseMax(1e-3) * 1000.0;
  // Leave room for labels beyond the outermost members.
  View v;
  v.n = fittingScale({size.x(), size.y()}, {f.areaWidth - 20.0, f.areaHeight - 12.0});
  v.x0 = lo.x();
  v.y1 = hi.y();
  v.px = f.areaX + (f.areaWidth - size.x() / v.n) / 2.0;
  v.py = f.areaY + (f.areaHeight - size.y() / v.n) / 2.0;
  return v;
}

// Isometric axonometry (ISO 5456-3, unit axis factors): lengths along x, y and z are true to the
// page's scale.
Eigen::Vector2d axo(const Eigen::Vector3d& p) {
  const double c = std::cos(M_PI / 6.0), s = std::sin(M_PI / 6.0);
  return {(p.x() - p.y()) * c, p.z() + (p.x() + p.y()) * s};
}

void arrow(cairo_t* cr, const Eigen::Vector2d& from, const Eigen::Vector2d& direction,
           double length) {
  const Eigen::Vector2d d = direction.normalized(), n(-d.y(), d.x());
  const Eigen::Vector2d tip = from + length * d;
  cairo_move_to(cr, from.x(), from.y());
  cairo_line_to(cr, tip.x(), tip.y());
  cairo_move_to(cr, (tip - 0.35 * length * d + 0.2 * length * n).x(),
                (tip - 0.35 * length * d + 0.2 * length * n).y());
  cairo_line_to(cr, tip.x(), tip.y());
  cairo_line_to(cr, (tip - 0.35 * length * d - 0.2 * length * n).x(),
                (tip - 0.35 * length * d - 0.2 * length * n).y());
  cairo_stroke(cr);
}

// Pages of text lines (the order, the joins, the support table).
class TextPages {
 public:
  TextPages(PdfDocument& pdf, PaperSize paper, std::string title)
      : pdf_(pdf), frame_(pageFrame(paper, true)), title_(std::move(title)) {}
  void line(const std::string& text, double size = 3.0) {
    if (!cr_ || y_ + size * 1.5 > frame_.areaY + frame_.areaHeight) newPage();
    cairo_set_source_rgb(cr_, 0, 0, 0);
    cairo_set_font_size(cr_, size);
    cairo_move_to(cr_, frame_.areaX, y_ + size);
    cairo_show_text(cr_, text.c_str());
    y_ += size * 1.5;
  }
  void finish() {
    if (cr_) end();
  }

 private:
  void newPage() {
    if (cr_) end();
    cr_ = pdf_.beginPage(frame_);
    y_ = frame_.areaY;
    ++page_;
  }
  void end() {
    // Text pages are not to scale; the bar still lets a reader check the print's size.
    drawTitleBand(cr_, frame_, title_ + (page_ > 1 ? " (continued)" : ""),
                  "text page (not to scale): the bar is 1:1 to check the print", 1.0);
    pdf_.endPage();
    cr_ = nullptr;
  }
  PdfDocument& pdf_;
  PageFrame frame_;
  std::string title_;
  cairo_t* cr_ = nullptr;
  double y_ = 0.0;
  int page_ = 0;
};

// Where the segment a-b lies inside the box [lo, hi]: its parameters t0 < t1 (Liang-Barsky), or
// false when it misses the box.
bool clipSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                 const Eigen::Vector2d& hi, double& t0, double& t1) {
  t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int k = 0; k < 2; ++k) {
    for (const auto& [p, q] : {std::pair{-d[k], a[k] - lo[k]}, std::pair{d[k], hi[k] - a[k]}}) {
      if (p == 0.0) {
        if (q < 0.0) return false;
      } else if (p < 0.0) {
        t0 = std::max(t0, q / p);
      } else {
        t1 = std::min(t1, q / p);
      }
    }
  }
  return t0 < t1;
}

using Window = std::pair<Eigen::Vector2d, Eigen::Vector2d>;  // lower left, upper right (m)

// The windows of a patch's detail pages and their scale 1:n: the grid cut into equal windows
// drawn at least twice as large as the overview's 1:`overviewN` (the standard scale at or above
// 1:overviewN/2.5, enlarged until at most 8 windows are needed), empty windows skipped, top row
// first as the overview reads. None when no larger scale needs 8 or fewer.
std::vector<Window> detailWindows(const AssemblyPatch& p, const Eigen::Vector2d& lo,
                                  const Eigen::Vector2d& hi, double overviewN, const PageFrame& f,
                                  double& n) {
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(1e-3);
  const double areaX = (f.areaWidth - 20.0) / 1000.0, areaY = (f.areaHeight - 12.0) / 1000.0;
  int nx = 1, ny = 1;
  for (n = fittingScale({overviewN / 2.5, 1.0}, {1.0, 1.0}); n < overviewN;
       n = fittingScale({n * 1.01, 1.0}, {1.0, 1.0})) {
    nx = static_cast<int>(std::ceil(extent.x() / (areaX * n) - 1e-9));
    ny = static_cast<int>(std::ceil(extent.y() / (areaY * n) - 1e-9));
    if (nx * ny <= 8) break;
  }
  std::vector<Window> windows;
  if (n >= overviewN) return windows;
  for (int j = ny - 1; j >= 0; --j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d a = lo + Eigen::Vector2d(extent.x() * i / nx, extent.y() * j / ny);
      const Eigen::Vector2d b =
          lo + Eigen::Vector2d(extent.x() * (i + 1) / nx, extent.y() * (j + 1) / ny);
      const bool any = std::any_of(p.connections.begin(), p.connections.end(), [&](const auto& c) {
        return (c.planar.array() >= a.array()).all() && (c.planar.array() <= b.array()).all();
      });
      if (any) windows.emplace_back(a, b);
    }
  }
  return windows;
}

// The detail windows outlined on the overview, dashed, each tagged "detail k" at its upper left
// corner: the key to the detail pages. Drawn before the ids, which mask its lines and keep off its
// tags.
void drawKeyMap(cairo_t* cr, const View& v, const std::vector<Window>& windows,
                PageLabels& labels) {
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
  cairo_set_line_width(cr, 0.25);
  const double dash[] = {2.0, 1.2};
  cairo_set_dash(cr, dash, 2, 0.0);
  cairo_set_font_size(cr, 2.4);
  for (size_t k = 0; k < windows.size(); ++k) {
    const Eigen::Vector2d a = v.page({windows[k].first.x(), windows[k].second.y()});
    const Eigen::Vector2d b = v.page({windows[k].second.x(), windows[k].first.y()});
    cairo_new_path(cr);
    cairo_rectangle(cr, a.x(), a.y(), b.x() - a.x(), b.y() - a.y());
    cairo_stroke(cr);
    const std::string tag = fmt::format("detail {}", k + 1);
    const Eigen::Vector2d box = labels.extent(tag, 2.4);
    cairo_move_to(cr, a.x() + 0.8, a.y() - 0.8);
    cairo_show_text(cr, tag.c_str());
    labels.reserve({a.x() + 0.5, a.y() - 0.8 - box.y(), a.x() + 1.1 + box.x(), a.y() - 0.4});
  }
  cairo_restore(cr);
}

// One page of a patch's planar grid: the part inside the window [lo, hi] (model metres) at the
// view `v`, every member clipped to it (a member cut by the window is labelled inside, at the
// cut), the connections inside with their notch arrows, and the ids laid out; `keyMap`: the
// detail windows to outline (the overview).
PageLabelCounts planarPage(PdfDocument& pdf, PaperSize paper, const AssemblyPatch& p, const View& v,
                           const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                           const std::string& title, const std::vector<Window>& keyMap = {}) {
  const PageFrame f = pageFrame(paper, true);
  cairo_t* cr = pdf.beginPage(f);
  PageLabels labels(cr, f);
  cairo_set_line_width(cr, 0.35);
  std::vector<MemberLabelSpot> spots;
  for (const auto& m : p.members) {
    double t0 = 0.0, t1 = 1.0;
    if (!clipSegment(m.planarStart, m.planarEnd, lo, hi, t0, t1)) continue;
    const Eigen::Vector2d d = m.planarEnd - m.planarStart;
    const Eigen::Vector2d a = v.page(m.planarStart + t0 * d), b = v.page(m.planarStart + t1 * d);
    cairo_set_source_rgb(cr, m.isU ? 0.75 : 0.0, 0.0, m.isU ? 0.0 : 0.75);
    cairo_move_to(cr, a.x(), a.y());
    cairo_line_to(cr, b.x(), b.y());
    cairo_stroke(cr);
    const Eigen::Vector2d u =
        (b - a).norm() > 0 ? Eigen::Vector2d((b - a).normalized()) : Eigen::Vector2d(1.0, 0.0);
    spots.push_back({m.id, m.isU, {a, b}, {t0 > 0.0 ? u : Eigen::Vector2d(-u), t1 < 1.0 ? -u : u}});
  }
  const double size = std::clamp(0.25 * 1000.0 / v.n * 0.2, 0.8, 1.8);
  std::vector<Eigen::Vector2d> dots;
  std::vector<std::string> ids;
  for (const auto& c : p.connections) {
    if ((c.planar.array() < lo.array()).any() || (c.planar.array() > hi.array()).any()) continue;
    const Eigen::Vector2d q = v.page(c.planar);
    dots.push_back(q);
    ids.push_back(c.id);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_new_path(cr);  // no line from the last path to the dot
    cairo_arc(cr, q.x(), q.y(), 0.5, 0.0, 2.0 * M_PI);
    cairo_fill(cr);
    // Notch directions: where the bolt slides while deploying, along its member.
    const Eigen::Vector2d slideU(c.slideU.x(), -c.slideU.y()), slideV(c.slideV.x(), -c.slideV.y());
    cairo_set_line_width(cr, 0.25);
    if (slideU.norm() > 0.0) {
      cairo_set_source_rgb(cr, 0.75, 0.0, 0.0);
      arrow(cr, q, slideU, 3.0);
    }
    if (slideV.norm() > 0.0) {
      cairo_set_source_rgb(cr, 0.0, 0.0, 0.75);
      arrow(cr, q, slideV, 3.0);
    }
    labels.reserveDot(q, 0.5, {slideU, slideV}, 3.0);
  }
  drawKeyMap(cr, v, keyMap, labels);
  const PageLabelCounts counts = layOutLabels(labels, spots, ids, dots, size);
  cairo_set_source_rgb(cr, 0, 0, 0);
  drawTitleBand(cr, f, title,
                "plan on the ground, scale " + scaleText(v.n) + " on " + toString(paper) +
                    "; u lamellas red, v blue; arrows: where each slotted bolt slides while "
                    "deploying (red along u, blue along v)" +
                    leftOutNote(counts, p.patchId) +
                    (keyMap.empty()
                         ? std::string()
                         : fmt::format("; dashed: the {} detail pages that follow", keyMap.size())),
                v.n);
  pdf.endPage();
  return counts;
}

// The whole planar grid on one page; where that leaves connection ids out, detail pages follow
// (detailWindows), outlined on the overview as its key map, so that the crew finds the ids the
// overview had no room for.
void planarPages(PdfDocument& pdf, PaperSize paper, const AssemblyPatch& p) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& m : p.members) points.push_back(m.planarStart), points.push_back(m.planarEnd);
  if (points.empty()) return;
  Eigen::Vector2d lo = points.front(), hi = points.front();
  for (const auto& q : points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const PageFrame f = pageFrame(paper, true);
  const View overview = fit(points, f);
  const std::string title =
      "patch P" + std::to_string(p.patchId) + ": planar grid as laid out and bolted";
  // The overview is laid out once to learn whether ids are left out; the PDF keeps only the page
  // drawn with its key map (a page is drawn to a scratch document first).
  PdfDocument trial;
  const PageLabelCounts counts = planarPage(trial, paper, p, overview, lo, hi, title);
  double n = overview.n;
  const std::vector<Window> windows = counts.connectionsLeftOut > 0
                                          ? detailWindows(p, lo, hi, overview.n, f, n)
                                          : std::vector<Window>{};
  planarPage(pdf, paper, p, overview, lo, hi, title, windows);
  for (size_t k = 0; k < windows.size(); ++k) {
    const auto& [a, b] = windows[k];
    View at = fit({a, b}, f);
    at.n = n;  // the detail scale, the window centred
    const Eigen::Vector2d size = (b - a) * 1000.0 / n;
    at.px = f.areaX + (f.areaWidth - size.x()) / 2.0;
    at.py = f.areaY + (f.areaHeight - size.y()) / 2.0;
    planarPage(pdf, paper, p, at, a, b,
               fmt::format("{}: detail {} of {}", title, k + 1, windows.size()));
  }
}

void deployedPage(PdfDocument& pdf, PaperSize paper, const AssemblyPatch& p) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& m : p.members) {
    for (const auto& q : m.deployed) points.push_back(axo(q));
  }
  const PageFrame f = pageFrame(paper, true);
  const View v = fit(points, f);
  cairo_t* cr = pdf.beginPage(f);
  PageLabels labels(cr, f);
  cairo_set_line_width(cr, 0.35);
  // Each member's ids beyond its two ends, along its chord.
  std::vector<MemberLabelSpot> spots;
  for (const auto& m : p.members) {
    if (m.deployed.size() < 2) continue;
    cairo_set_source_rgb(cr, m.isU ? 0.75 : 0.0, 0.0, m.isU ? 0.0 : 0.75);
    for (size_t k = 0; k < m.deployed.size(); ++k) {
      const Eigen::Vector2d q = v.page(axo(m.deployed[k]));
      k ? cairo_line_to(cr, q.x(), q.y()) : cairo_move_to(cr, q.x(), q.y());
    }
    cairo_stroke(cr);
    const Eigen::Vector2d a = v.page(axo(m.deployed.front())), b = v.page(axo(m.deployed.back()));
    const Eigen::Vector2d u =
        (b - a).norm() > 0 ? Eigen::Vector2d((b - a).normalized()) : Eigen::Vector2d(1.0, 0.0);
    spots.push_back({m.id, m.isU, {a, b}, {-u, u}});
  }
  const double size = std::clamp(0.25 * 1000.0 / v.n * 0.2, 0.8, 1.8);
  std::vector<Eigen::Vector2d> dots;
  std::vector<std::string> ids;
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (const auto& c : p.connections) {
    const Eigen::Vector2d q = v.page(axo(c.spatial));
    dots.push_back(q);
    ids.push_back(c.id);
    cairo_new_path(cr);  // no line from the last path to the dot
    cairo_arc(cr, q.x(), q.y(), 0.4, 0.0, 2.0 * M_PI);
    cairo_fill(cr);
    labels.reserveDot(q, 0.4, {}, 0.0);
  }
  const PageLabelCounts counts = layOutLabels(labels, spots, ids, dots, size);
  cairo_set_source_rgb(cr, 0, 0, 0);
  drawTitleBand(cr, f, "patch P" + std::to_string(p.patchId) + ": deployed, axonometric",
                "isometric (ISO 5456-3), lengths along x, y, z at " + scaleText(v.n) + " on " +
                    toString(paper) + "; same ids as the planar grid" +
                    leftOutNote(counts, p.patchId),
                v.n);
  pdf.endPage();
}

void supportPlanPage(PdfDocument& pdf, PaperSize paper, const std::vector<AssemblyPatch>& patches,
                     const std::vector<Support>& supports) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& p : patches) {
    for (const auto& m : p.members) {
      for (const auto& q : m.deployed) points.emplace_back(q.x(), q.y());
    }
  }
  for (const auto& s : supports) points.emplace_back(s.position.x(), s.position.y());
  const PageFrame f = pageFrame(paper, true);
  const View v = fit(points, f);
  cairo_t* cr = pdf.beginPage(f);
  cairo_set_line_width(cr, 0.2);
  cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
  for (const auto& p : patches) {
    for (const auto& m : p.members) {
      for (size_t k = 0; k < m.deployed.size(); ++k) {
        const Eigen::Vector2d q = v.page({m.deployed[k].x(), m.deployed[k].y()});
        k ? cairo_line_to(cr, q.x(), q.y()) : cairo_move_to(cr, q.x(), q.y());
      }
      cairo_stroke(cr);
    }
  }
  cairo_set_source_rgb(cr, 0.8, 0.0, 0.0);
  PageLabels labels(cr, f);
  for (const auto& s : supports) {
    const Eigen::Vector2d q = v.page({s.position.x(), s.position.y()});
    cairo_new_path(cr);
    cairo_rectangle(cr, q.x() - 0.8, q.y() - 0.8, 1.6, 1.6);
    cairo_fill(cr);
    labels.reserve(q, 0.9);
  }
  // Ids after every marker is reserved, so that no id covers another support.
  int leftOut = 0;
  for (const auto& s : supports) {
    const Eigen::Vector2d q = v.page({s.position.x(), s.position.y()});
    const Eigen::Vector2d box = labels.extent(s.id, 1.8);
    std::vector<Eigen::Vector2d> centres = PageLabels::besideDot(q, box, 1.0);
    for (const auto& c : PageLabels::besideDot(q, box, 3.5)) centres.push_back(c);
    if (!labels.place(s.id, 1.8, centres, {0.8, 0.0, 0.0})) ++leftOut;
  }
  labels.draw();
  cairo_set_source_rgb(cr, 0, 0, 0);
  drawTitleBand(cr, f, "support plan",
                "plan (site x right, y up), scale " + scaleText(v.n) + " on " + toString(paper) +
                    "; coordinates in the table that follows and supports/supports.csv" +
                    (leftOut > 0 ? fmt::format("; {} support ids left out where they would "
                                               "overlap (every support is in the table)",
                                               leftOut)
                                 : std::string()),
                v.n);
  pdf.endPage();
}

}  // namespace

std::vector<AssemblyPatch> assemblyPatches(const std::vector<FabricationPatch>& patches,
                                           const std::vector<LamellaPlan>& lamellae,
                                           const std::vector<SharedBoundary>& shared,
                                           double minNotchM) {
  (void)lamellae;
  // A shared side's member B is cut as A's lamella: draw it with A's id.
  std::map<std::tuple<int, bool, int>, std::string> renamed;
  for (const auto& s : shared) {
    renamed[{s.patchB, s.familyB == Family::U, s.indexB}] =
        memberId(s.patchA, s.familyA == Family::U, s.indexA);
  }
  std::vector<AssemblyPatch> out;
  for (const auto& patch : patches) {
    AssemblyPatch a;
    a.patchId = patch.patchId;
    a.boltedTo = patch.boltedTo;
    const EggGrid& g = *patch.grid;
    for (bool isU : {true, false}) {
      const auto& family = isU ? g.u : g.v;
      for (size_t i = 0; i < family.size(); ++i) {
        AssemblyMember m;
        const auto key = std::make_tuple(patch.patchId, isU, static_cast<int>(i));
        m.id =
            renamed.count(key) ? renamed[key] : memberId(patch.patchId, isU, static_cast<int>(i));
        m.isU = isU;
        m.planarStart = family[i].planarStart;
        m.planarEnd = family[i].planarEnd;
        const size_t k = isU ? i : g.u.size() + i;
        m.deployed = patch.deployedCentrelines && k < patch.deployedCentrelines->size()
                         ? (*patch.deployedCentrelines)[k]
                         : family[i].spatial;
        a.members.push_back(std::move(m));
      }
    }
    for (const GridConnection& c : g.connections) {
      AssemblyConnection ac;
      ac.id = fmt::format("P{}-C{}-{}", patch.patchId, c.memberU, c.memberV);
      ac.planar = c.planar;
      ac.spatial = c.spatial;
      auto along = [](const GridMember& m, double l) -> Eigen::Vector2d {
        const Eigen::Vector2d d = m.planarEnd - m.planarStart;
        return d.norm() > 0.0 ? Eigen::Vector2d(d.normalized() * l) : Eigen::Vector2d::Zero();
      };
      // Notches as cut (none on boundary members, none below min_notch_mm).
      const GridMember &u = g.u[c.memberU], &v = g.v[c.memberV];
      if (!u.boundary && std::abs(c.notchU) >= minNotchM) ac.slideU = along(u, c.notchU);
      if (!v.boundary && std::abs(c.notchV) >= minNotchM) ac.slideV = along(v, c.notchV);
      a.connections.push_back(ac);
    }
    out.push_back(std::move(a));
  }
  return out;
}

std::string assemblyPdf(const FabricationResult& r) {
  const PaperSize paper = r.options.paperSize;
  PdfDocument pdf;
  std::vector<std::string> reasons;
  const auto order = assemblyOrder(r.assembly, r.supports, r.shared, &reasons);
  std::map<int, const AssemblyPatch*> byId;
  for (const auto& p : r.assembly) byId[p.patchId] = &p;
  {
    TextPages text(pdf, paper, "assembly order");
    text.line("Assembly order", 5.0);
    text.line(
        "Patches are assembled flat on the ground, deployed and fixed one after another "
        "(Section 3.6: multi-patch grids are deployed and combined sequentially).");
    for (const auto& reason : reasons) text.line("  " + reason);
    int step = 1;
    for (int id : order) {
      const AssemblyPatch& p = *byId[id];
      text.line("");
      text.line(std::to_string(step++) + ". Patch P" + std::to_string(id), 4.0);
      std::string u, v;
      for (const auto& m : p.members)
        (m.isU ? u : v) += (m.isU ? u : v).empty() ? m.id : " " + m.id;
      text.line(
          "  a. Lay the u lamellas on the ground at their planar positions (next pages), in "
          "this order: " +
          u.substr(0, 150) + (u.size() > 150 ? " ..." : ""));
      for (size_t k = 150; k < u.size(); k += 170) text.line("     " + u.substr(k, 170));
      text.line("  b. Lay the v lamellas across them, on top, in this order: " + v.substr(0, 150) +
                (v.size() > 150 ? " ..." : ""));
      for (size_t k = 150; k < v.size(); k += 170) text.line("     " + v.substr(k, 170));
      text.line(
          "     Reason: one family wholly below the other (no weaving), so the grid can "
          "scissor open; a shared side's lamella is already standing from the patch before.");
      text.line(
          "  c. Stick the PTFE stickers at every slotted connection, then bolt every "
          "connection: tighten at plain holes, leave slotted bolts snug so they can slide.");
      text.line(p.boltedTo.empty()
                    ? "  d. Deploy the patch and fix its boundary joints to its supports (support "
                      "plan)."
                    : "  d. Deploy the patch: bolt the member ends that lap onto a standing "
                      "patch's boundary lamella to it, fix the others to their supports or the "
                      "ring beam (support plan).");
    }
    text.finish();
  }
  for (int id : order) {
    planarPages(pdf, paper, *byId[id]);
    deployedPage(pdf, paper, *byId[id]);
  }
  supportPlanPage(pdf, paper, r.assembly, r.supports);
  {
    TextPages table(pdf, paper, "support coordinates");
    table.line(
        "Supports (site coordinates in metres; the contact plane's inclination and direction "
        "in degrees)",
        4.0);
    for (const auto& s : r.supports) {
      table.line(s.id + "   " + s.connectionId + "   x " + fmt::sprintf("%.3f", s.position.x()) +
                     "   y " + fmt::sprintf("%.3f", s.position.y()) + "   z " +
                     fmt::sprintf("%.3f", s.position.z()) + "   inclination " +
                     fmt::sprintf("%.1f", s.inclinationDeg) + "   direction " +
                     fmt::sprintf("%.1f", s.directionDeg) + "   " +
                     (s.block ? "block" : "bracket") + "   " + s.reason,
                 2.8);
    }
    table.finish();
  }
  if (!r.shared.empty()) {
    TextPages joins(pdf, paper, "joins between patches");
    joins.line("Joins between patches: one lamella carries both patches' holes on a shared side",
               4.0);
    for (const auto& s : r.shared) {
      const std::string a = memberId(s.patchA, s.familyA == Family::U, s.indexA),
                        b = memberId(s.patchB, s.familyB == Family::U, s.indexB);
      joins.line("");
      joins.line(a + " of patch P" + std::to_string(s.patchA) + " is also " + b + " of patch P" +
                     std::to_string(s.patchB) + (s.reversed ? " (running the other way)" : "") +
                     ": cut once, as " + a,
                 3.2);
      for (const auto& plan : r.lamellae) {
        if (plan.id != a) continue;
        std::string line;
        for (const auto& f : plan.features) {
          if (f.alsoConnectionIds.empty()) continue;
          line += (line.empty() ? "" : "   ") + f.label();
          if (line.size() > 150) joins.line("  bolts through both: " + line, 2.8), line.clear();
        }
        if (!line.empty()) joins.line("  bolts through both: " + line, 2.8);
      }
    }
    joins.finish();
  }
  return pdf.finish();
}

}  // namespace egg::fabrication
