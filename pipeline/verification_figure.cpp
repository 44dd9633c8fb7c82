#include "pipeline/verification_figure.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace egg::pipeline {
namespace {
namespace vfig {  // own names: the pipeline is a unity build

using verification::CheckResult;
using verification::FeMesh;

constexpr double kPanelW = 300.0, kPanelH = 260.0, kTitleH = 34.0, kLegendH = 30.0;

// Isometric view: x to the lower right, y to the upper right, z up (SVG y grows down).
Eigen::Vector2d iso(const Eigen::Vector3d& p) {
  const double c = std::cos(M_PI / 6.0), s = std::sin(M_PI / 6.0);
  return {(p.x() - p.y()) * c, -(p.z() + (p.x() + p.y()) * s)};
}

struct View {
  Eigen::Vector2d min, max;
  double scale = 1.0;
  Eigen::Vector2d origin;  // panel's top-left drawing corner
  Eigen::Vector2d at(const Eigen::Vector3d& p) const {
    const Eigen::Vector2d q = iso(p);
    return origin + scale * (q - min);
  }
};

// Lamella elements only (bolts and support arms are short and clutter the view).
template <class Draw>
void forLamellaElements(const FeMesh& mesh, Draw draw) {
  for (const auto& e : mesh.elements)
    if (e.part == FeMesh::Part::Lamella) draw(e);
}

// Green at 0, yellow at 0.5, red at 1; dark red above 1 (over-utilised).
std::string utilisationColour(double u) {
  if (!(u <= 1.0)) return "#7f0000";
  const double t = std::clamp(u, 0.0, 1.0);
  const int r = t < 0.5 ? static_cast<int>(std::lround(2.0 * t * 230.0)) : 230;
  const int g = t < 0.5 ? 175 : static_cast<int>(std::lround(175.0 * (1.0 - t) * 2.0));
  return fmt::format("#{:02x}{:02x}20", r, g);
}

std::string polyline(const std::vector<Eigen::Vector2d>& points, const std::string& colour,
                     double width) {
  std::string out = "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"" +
                    fmt::format("{:.2f}", width) + "\" points=\"";
  for (const auto& p : points) out += fmt::format("{:.1f},{:.1f} ", p.x(), p.y());
  out.back() = '"';
  return out + "/>\n";
}

// The lamella elements of the mesh with nodes moved by `factor` times `shift` (empty: none).
std::string elements(const FeMesh& mesh, const View& view,
                     const std::vector<Eigen::Vector3d>& shift, double factor,
                     const std::function<std::string(int owner)>& colour, double width) {
  std::string out;
  forLamellaElements(mesh, [&](const FeMesh::Element& e) {
    std::vector<Eigen::Vector2d> points;
    for (const int n : e.nodes) {
      Eigen::Vector3d p = mesh.nodes[n - 1];
      if (!shift.empty()) p += factor * shift[n - 1];
      points.push_back(view.at(p));
    }
    out += polyline(points, colour(e.owner), width);
  });
  return out;
}

double extent(const FeMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const auto& p : mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return (hi - lo).norm();
}

double largest(const std::vector<Eigen::Vector3d>& v) {
  double m = 0.0;
  for (const auto& x : v) m = std::max(m, x.norm());
  return m;
}

}  // namespace vfig
}  // namespace

const verification::CaseResult& governingCase(const verification::CheckResult& result) {
  if (result.cases.empty()) throw InvalidInput("verificationSvg: a check without load cases");
  for (const auto& c : result.cases)
    if (c.name == result.buckling.loadCase) return c;
  return *std::max_element(
      result.cases.begin(), result.cases.end(),
      [](const auto& a, const auto& b) { return a.maxUtilisation < b.maxUtilisation; });
}

std::string verificationSvg(const verification::CheckResult& result) {
  using namespace vfig;  // inside the function: a file-scope directive leaks into unity neighbours
  if (!result.solved) throw InvalidInput("verificationSvg: the check was not solved");
  const auto& mesh = result.mesh;
  const auto& governing = governingCase(result);
  const double size = extent(mesh);
  // Deformations drawn so that the largest is a twentieth of the structure's size.
  const double target = size / 20.0;
  const double dMax = largest(governing.displacements);
  const double dFactor = dMax > 0.0 ? target / dMax : 0.0;
  const bool buckled = !result.buckling.modes.empty() && !result.buckling.factors.empty();
  const std::vector<Eigen::Vector3d> none;
  const std::vector<Eigen::Vector3d>& mode = buckled ? result.buckling.modes.front() : none;
  const double mMax = largest(mode);
  const double mFactor = mMax > 0.0 ? target / mMax : 0.0;

  // One scale for the three panels: the undeformed bounds widened by the drawn deformations.
  View view;
  view.min = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  view.max = -view.min;
  auto widen = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d q = iso(p);
    view.min = view.min.cwiseMin(q), view.max = view.max.cwiseMax(q);
  };
  for (size_t i = 0; i < mesh.nodes.size(); ++i) {
    widen(mesh.nodes[i]);
    if (i < governing.displacements.size())
      widen(mesh.nodes[i] + dFactor * governing.displacements[i]);
    if (i < mode.size()) widen(mesh.nodes[i] + mFactor * mode[i]);
  }
  const Eigen::Vector2d span = (view.max - view.min).cwiseMax(1e-9);
  const double margin = 10.0;
  view.scale = std::min((kPanelW - 2 * margin) / span.x(),
                        (kPanelH - kTitleH - kLegendH - 2 * margin) / span.y());
  const Eigen::Vector2d drawn = view.scale * span;
  auto panelOrigin = [&](int k) {
    return Eigen::Vector2d(
        k * kPanelW + (kPanelW - drawn.x()) / 2.0,
        kTitleH + margin + (kPanelH - kTitleH - kLegendH - 2 * margin - drawn.y()) / 2.0);
  };
  const std::string grey = "#c8c8c8";
  auto flat = [&](const std::string& colour) { return [colour](int) { return colour; }; };
  auto title = [&](int k, const std::string& line1, const std::string& line2) {
    return fmt::format(
        "<text x=\"{:.0f}\" y=\"14\" font-size=\"12\" font-weight=\"bold\">{}</text>\n"
        "<text x=\"{:.0f}\" y=\"28\" font-size=\"11\" fill=\"#444\">{}</text>\n",
        k * kPanelW + 8, escapeXml(line1), k * kPanelW + 8, escapeXml(line2));
  };

  std::string svg = fmt::format(
      "<svg id=\"verification\" class=\"chart\" width=\"{0:.0f}\" height=\"{1:.0f}\" "
      "viewBox=\"0 0 {0:.0f} {1:.0f}\" font-family=\"sans-serif\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      3 * kPanelW, kPanelH);

  // 1: utilisation per lamella.
  view.origin = panelOrigin(0);
  const auto& u = governing.lamellaUtilisation;
  svg +=
      title(0, "Utilisation, case " + governing.name,
            fmt::format("(deployment + load stress) / f_m; max {:.2f}", governing.maxUtilisation));
  svg += elements(
      mesh, view, none, 0.0,
      [&](int owner) {
        return owner >= 0 && owner < static_cast<int>(u.size()) ? utilisationColour(u[owner])
                                                                : grey;
      },
      1.6);
  const double ly = kPanelH - kLegendH + 8;
  for (int k = 0; k <= 10; ++k)
    svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.0f}\" width=\"18\" height=\"8\" fill=\"{}\"/>\n",
                       20.0 + 18.0 * k, ly, utilisationColour(k / 10.0));
  svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.0f}\" width=\"18\" height=\"8\" fill=\"{}\"/>\n",
                     20.0 + 18.0 * 11 + 6, ly, utilisationColour(1.5));
  svg += fmt::format(
      "<text x=\"20\" y=\"{0:.0f}\" font-size=\"10\">0</text><text x=\"{1:.0f}\" y=\"{0:.0f}\" "
      "font-size=\"10\">0.5</text><text x=\"{2:.0f}\" y=\"{0:.0f}\" font-size=\"10\">1</text>"
      "<text x=\"{3:.0f}\" y=\"{0:.0f}\" font-size=\"10\">&gt;1</text>\n",
      ly + 19, 20.0 + 18.0 * 5, 20.0 + 18.0 * 10, 20.0 + 18.0 * 11 + 6);

  // 2: deflected shape of the governing case over the undeformed structure.
  view.origin = panelOrigin(1);
  svg += title(
      1, "Deflected shape, case " + governing.name,
      fmt::format("max {:.1f} mm, drawn x{:.0f} (blue; grey: undeformed)", 1e3 * dMax, dFactor));
  svg += elements(mesh, view, none, 0.0, flat(grey), 1.0);
  svg += elements(mesh, view, governing.displacements, dFactor, flat("#1f5fbf"), 1.4);

  // 3: buckling mode 1.
  view.origin = panelOrigin(2);
  if (buckled) {
    svg += title(2, fmt::format("Buckling mode 1, factor {:.3g}", result.buckling.factors.front()),
                 "of case " + result.buckling.loadCase + " (purple; grey: undeformed)");
    svg += elements(mesh, view, none, 0.0, flat(grey), 1.0);
    svg += elements(mesh, view, mode, mFactor, flat("#7b2fa0"), 1.4);
  } else {
    svg += title(2, "Buckling", "no buckling step (loads.buckling_modes = 0)");
    svg += elements(mesh, view, none, 0.0, flat(grey), 1.0);
  }
  for (int k = 1; k < 3; ++k)
    svg += fmt::format(
        "<line x1=\"{0:.0f}\" y1=\"4\" x2=\"{0:.0f}\" y2=\"{1:.0f}\" stroke=\"#ddd\"/>\n",
        k * kPanelW, kPanelH - 4);
  return svg + "</svg>\n";
}

}  // namespace egg::pipeline
