#include "pipeline/cladding_plot.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;

json claddingEntry(const CladdingFunction& u, const CladdingFunction& v,
                   const FamilyMembers& membersU, const FamilyMembers& membersV,
                   const std::array<double, 2>& sidesU, const std::array<double, 2>& sidesV,
                   double slopeMin, double slopeMax, double infiniteSlopeFactor) {
  auto family = [](const CladdingFunction& f, const FamilyMembers& m,
                   const std::array<double, 2>& sides) {
    json x1 = json::array(), x2 = json::array();
    for (const auto& p : f.points) x1.push_back(p.x()), x2.push_back(p.y());
    return json{{"start_side_m", sides[0]},  {"end_side_m", sides[1]}, {"points_x1", x1},
                {"points_x2", x2},           {"members_x1", m.x1},     {"members_x2", m.x2},
                {"bijective", f.bijective()}};
  };
  return {{"slope_bounds", {slopeMin, slopeMax}},
          {"infinite_slope_factor", infiniteSlopeFactor},
          {"u", family(u, membersU, sidesU)},
          {"v", family(v, membersV, sidesV)}};
}

namespace {

double positiveField(const json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number() || !(j[key].get<double>() > 0.0))
    throw InvalidInput(where + "." + key + " must be a positive number");
  return j[key].get<double>();
}

std::vector<double> numbers(const json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_array())
    throw InvalidInput(where + "." + key + " must be an array of numbers");
  std::vector<double> out;
  for (const auto& x : j[key]) {
    if (!x.is_number()) throw InvalidInput(where + "." + key + " must be an array of numbers");
    out.push_back(x.get<double>());
  }
  return out;
}

std::vector<std::array<double, 2>> pairs(const json& j, const std::string& a, const std::string& b,
                                         const std::string& where) {
  const auto x = numbers(j, a, where), y = numbers(j, b, where);
  if (x.size() != y.size())
    throw InvalidInput(where + ": " + a + " and " + b + " differ in length");
  std::vector<std::array<double, 2>> out;
  for (size_t k = 0; k < x.size(); ++k) out.push_back({x[k], y[k]});
  return out;
}

CladdingCurve curveFrom(const json& j, const std::string& family, const std::string& where) {
  if (!j.is_object()) throw InvalidInput(where + " must be an object");
  CladdingCurve c;
  c.family = family;
  c.startSideM = positiveField(j, "start_side_m", where);
  c.endSideM = positiveField(j, "end_side_m", where);
  c.points = pairs(j, "points_x1", "points_x2", where);
  c.members = pairs(j, "members_x1", "members_x2", where);
  return c;
}

const char* kColours[2] = {"#1f77b4",
                           "#ff7f0e"};  // u blue, v orange, as the planar grids (writePlanarSvg)
constexpr double kColumn = 320.0, kLeft = 58.0, kCurveTop = 40.0, kCurveSize = 250.0,
                 kSlopeTop = 340.0, kSlopeHeight = 110.0;
constexpr double kWidth = 2 * kColumn + 20.0, kHeight = 500.0;

}  // namespace

std::optional<CladdingPlot> claddingFromReport(const json& patchEntry) {
  if (!patchEntry.is_object() || !patchEntry.contains("cladding")) return std::nullopt;
  const json& c = patchEntry["cladding"];
  const std::string where =
      "patches[" + (patchEntry.contains("id") ? patchEntry["id"].dump() : std::string("?")) +
      "].cladding";
  if (!c.is_object()) throw InvalidInput(where + " must be an object");
  CladdingPlot plot;
  plot.patch = patchEntry.value("id", 0);
  const auto bounds = numbers(c, "slope_bounds", where);
  if (bounds.size() != 2 || !(bounds[0] > 0.0 && bounds[1] > bounds[0]))
    throw InvalidInput(where + ".slope_bounds must be [k_min, k_max] with 0 < k_min < k_max");
  plot.slopeMin = bounds[0], plot.slopeMax = bounds[1];
  plot.infiniteSlopeFactor = positiveField(c, "infinite_slope_factor", where);
  plot.u = curveFrom(c.value("u", json()), "u", where + ".u");
  plot.v = curveFrom(c.value("v", json()), "v", where + ".v");
  return plot;
}

PlotFrame claddingFrame(const CladdingCurve& curve, int column) {
  return {kLeft + kColumn * column, kCurveTop, kCurveSize,     kCurveSize, 0.0,
          curve.startSideM,         0.0,       curve.endSideM, false};
}

PlotFrame slopeFrame(const CladdingCurve& curve, int column, double slopeMin, double slopeMax) {
  // A factor 4 either side of the band: slopes just outside it still show by how much.
  return {kLeft + kColumn * column, kSlopeTop,      kCurveSize,     kSlopeHeight, 0.0,
          curve.startSideM,         slopeMin / 4.0, slopeMax * 4.0, true};
}

std::vector<std::array<double, 3>> claddingSlopes(const CladdingCurve& curve,
                                                  double infiniteSlopeFactor) {
  std::vector<std::array<double, 3>> out;
  for (size_t k = 1; k < curve.points.size(); ++k) {
    const double dx1 = curve.points[k][0] - curve.points[k - 1][0],
                 dx2 = curve.points[k][1] - curve.points[k - 1][1];
    if (dx1 == 0.0 && dx2 == 0.0) continue;
    out.push_back({curve.points[k - 1][0], curve.points[k][0],
                   dx1 == 0.0 ? infiniteSlopeFactor * dx2 : dx2 / dx1});
  }
  return out;
}

namespace {

std::string axisTicksX(const PlotFrame& f, double bottom) {
  std::string out;
  const double step = tickStep(f.xMax - f.xMin, 5);
  for (int k = 0; k * step <= f.xMax * (1.0 + 1e-9); ++k) {
    const double x = k * step;
    out += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#999\"/>",
        f.px(x), bottom, bottom + 4.0);
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:g}</text>\n",
                       f.px(x), bottom + 15.0, x);
  }
  return out;
}

std::string panel(const CladdingCurve& curve, int column, const CladdingPlot& plot) {
  const std::string colour = kColours[column];
  const PlotFrame f = claddingFrame(curve, column);
  const std::string id = fmt::format("patch-{}-{}", plot.patch, curve.family);
  std::string svg = fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"13\" font-weight=\"bold\">F<tspan "
      "baseline-shift=\"sub\">{}</tspan> "
      "of patch {} ({} members)</text>\n",
      f.left, f.top - 14.0, curve.family, plot.patch, curve.members.size());
  svg += fmt::format(
      "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
      "stroke=\"#999\"/>\n",
      f.left, f.top, f.width, f.height);
  // The diagonal: F of a developable patch at its unrolled angle (the identity pairing).
  svg += fmt::format(
      "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ccc\" "
      "stroke-dasharray=\"3 3\"/>\n",
      f.px(0.0), f.py(0.0), f.px(f.xMax), f.py(f.yMax));
  svg += axisTicksX(f, f.top + f.height);
  const double yStep = tickStep(f.yMax, 5);
  for (int k = 0; k * yStep <= f.yMax * (1.0 + 1e-9); ++k)
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{:g}</text>\n",
                       f.left - 5.0, f.py(k * yStep) + 4.0, k * yStep);
  svg +=
      fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">start side (m)</text>\n",
                  f.left + f.width / 2, f.top + f.height + 30.0);
  svg += fmt::format(
      "<text transform=\"translate({:.1f},{:.1f}) rotate(-90)\" text-anchor=\"middle\">end side "
      "(m)</text>\n",
      f.left - 40.0, f.top + f.height / 2);
  std::string points;
  for (const auto& p : curve.points)
    points += fmt::format("{}{:.2f},{:.2f}", points.empty() ? "" : " ",
                          f.px(p[0] * curve.startSideM), f.py(p[1] * curve.endSideM));
  svg += fmt::format(
      "<polyline id=\"{}-curve\" points=\"{}\" fill=\"none\" stroke=\"{}\" "
      "stroke-width=\"1.5\"/>\n",
      id, points, colour);
  for (const auto& m : curve.members)
    svg += fmt::format(
        "<circle class=\"member\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"2.5\" fill=\"#222\"/>",
        f.px(m[0] * curve.startSideM), f.py(m[1] * curve.endSideM));
  svg += "\n";

  // The slopes against the band (k_min, k_max) of Problem 2.3; segments outside it in red.
  const PlotFrame s = slopeFrame(curve, column, plot.slopeMin, plot.slopeMax);
  svg += fmt::format(
      "<rect id=\"{}-band\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.2f}\" "
      "fill=\"#e3f1e3\"/>\n",
      id, s.left, s.py(plot.slopeMax), s.width, s.py(plot.slopeMin) - s.py(plot.slopeMax));
  svg += fmt::format(
      "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
      "stroke=\"#999\"/>\n",
      s.left, s.top, s.width, s.height);
  for (double k : {plot.slopeMin, 1.0, plot.slopeMax}) {
    const bool bound = k != 1.0;
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.2f}\" x2=\"{2:.1f}\" y2=\"{1:.2f}\" stroke=\"{3}\"{4}/>",
        s.left, s.py(k), s.left + s.width, bound ? "#2e7d32" : "#bbb",
        bound ? " stroke-dasharray=\"5 3\"" : "");
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.2f}\" text-anchor=\"end\">{:g}</text>\n",
                       s.left - 5.0, s.py(k) + 4.0, k);
  }
  // Labels inside the strip, just above their lines (the right column has no margin beyond it).
  svg += fmt::format(
      "<text x=\"{0:.1f}\" y=\"{1:.1f}\" font-size=\"10\" fill=\"#2e7d32\" "
      "text-anchor=\"end\">k_max</text>"
      "<text x=\"{0:.1f}\" y=\"{2:.1f}\" font-size=\"10\" fill=\"#2e7d32\" "
      "text-anchor=\"end\">k_min</text>\n",
      s.left + s.width - 3.0, s.py(plot.slopeMax) - 3.0, s.py(plot.slopeMin) - 3.0);
  std::string inside, outside;
  for (const auto& [a, b, k] : claddingSlopes(curve, plot.infiniteSlopeFactor)) {
    const bool ok = k > plot.slopeMin && k < plot.slopeMax;
    (ok ? inside : outside) += fmt::format("M{:.2f} {:.2f}H{:.2f}", s.px(a * curve.startSideM),
                                           s.py(k), s.px(b * curve.startSideM));
  }
  if (!inside.empty())
    svg += fmt::format(
        "<path id=\"{}-slopes\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", id,
        inside, colour);
  if (!outside.empty())
    svg += fmt::format(
        "<path id=\"{}-violations\" d=\"{}\" fill=\"none\" stroke=\"#c62828\" "
        "stroke-width=\"2.5\"/>\n",
        id, outside);
  // Members on the slope strip: where along the start side they sit.
  for (const auto& m : curve.members)
    svg += fmt::format(
        "<line x1=\"{0:.2f}\" y1=\"{1:.1f}\" x2=\"{0:.2f}\" y2=\"{2:.1f}\" stroke=\"#222\"/>",
        s.px(m[0] * curve.startSideM), s.top + s.height - 5.0, s.top + s.height);
  svg += "\n" + axisTicksX(s, s.top + s.height);
  svg += fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">start side (m); slope dx2/dx1 "
      "(log)</text>\n",
      s.left + s.width / 2, s.top + s.height + 30.0);
  return svg;
}

}  // namespace

std::string claddingSvg(const CladdingPlot& plot) {
  std::string svg = fmt::format(
      "<svg id=\"cladding-patch-{0}\" class=\"chart\" width=\"{1:.0f}\" height=\"{2:.0f}\" "
      "viewBox=\"0 0 {1:.0f} {2:.0f}\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\">\n"
      "<rect width=\"{1:.0f}\" height=\"{2:.0f}\" fill=\"white\"/>\n",
      plot.patch, kWidth, kHeight);
  svg += panel(plot.u, 0, plot) + panel(plot.v, 1, plot);
  return svg + "</svg>\n";
}

}  // namespace egg::pipeline
