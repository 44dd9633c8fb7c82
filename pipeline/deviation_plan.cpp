#include "pipeline/deviation_plan.hpp"

#include "core/io/xml_text.hpp"
#include "patching/plan_drawing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace egg::pipeline {

std::string deviationColour(double distanceM, double scaleM) {
  // A diverging ramp (ColorBrewer RdYlBu ends and middle): near the surface reads as cool.
  static const std::array<std::array<double, 3>, 3> stops{
      {{44, 123, 182}, {255, 255, 191}, {215, 25, 28}}};
  double t = scaleM > 0.0 && std::isfinite(distanceM) ? std::clamp(distanceM / scaleM, 0.0, 1.0)
                                                      : (std::isfinite(distanceM) ? 0.0 : 1.0);
  const int k = t < 0.5 ? 0 : 1;
  const double u = t < 0.5 ? t / 0.5 : (t - 0.5) / 0.5;
  std::array<int, 3> rgb{};
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<int>(std::lround(stops[k][c] + u * (stops[k + 1][c] - stops[k][c])));
  return fmt::format("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
}

double deviationScale(double maxDistanceM) {
  if (!(maxDistanceM > 0.0) || !std::isfinite(maxDistanceM)) return 0.01;
  const double decade = std::pow(10.0, std::floor(std::log10(maxDistanceM)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= maxDistanceM * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

std::string deployedPlanSvg(const std::vector<DeployedRod>& rods, const std::string& caption) {
  constexpr int kBins = 16;
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX,
         maxD = 0.0;
  for (const auto& r : rods)
    for (size_t i = 0; i < r.points.size(); ++i) {
      minX = std::min(minX, r.points[i].x()), maxX = std::max(maxX, r.points[i].x());
      minY = std::min(minY, r.points[i].y()), maxY = std::max(maxY, r.points[i].y());
      if (i < r.distanceM.size() && std::isfinite(r.distanceM[i]))
        maxD = std::max(maxD, r.distanceM[i]);
    }
  if (!(maxX >= minX)) minX = minY = 0.0, maxX = maxY = 1.0;
  const double plotW = 900.0, pad = 20.0, barW = 110.0;
  const double spanX = std::max(maxX - minX, 1e-9), spanY = std::max(maxY - minY, 1e-9);
  const double s = plotW / std::max(spanX, spanY);
  const double w = spanX * s + 2 * pad + barW,
               h = std::max(spanY * s, 260.0) + 2 * pad + 30.0 + 44.0;  // + the scale bar
  const double scale = deviationScale(maxD);
  const auto px = [&](const Eigen::Vector3d& p) {
    return fmt::format("{:.1f},{:.1f}", pad + (p.x() - minX) * s, pad + 24.0 + (maxY - p.y()) * s);
  };
  std::string svg = fmt::format(
      "<svg id=\"deployed\" xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" width=\"{0:.0f}\" "
      "height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\" "
      "font-family=\"sans-serif\" font-size=\"12\" role=\"img\">\n<rect width=\"{0:.0f}\" "
      "height=\"{1:.0f}\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"16\">{3}</text>\n",
      w, h, pad, escapeXml(caption));
  for (const auto& r : rods) {
    const size_t n = std::min(r.points.size(), r.distanceM.size());
    size_t i = 0;
    while (i + 1 < n) {
      const auto binOf = [&](size_t k) {
        const double d = 0.5 * (r.distanceM[k] + r.distanceM[k + 1]);
        return std::isfinite(d) ? std::min(kBins - 1, static_cast<int>(d / scale * kBins))
                                : kBins - 1;
      };
      const int bin = binOf(i);
      std::string points = px(r.points[i]);
      size_t j = i;
      while (j + 1 < n && binOf(j) == bin) points += ' ' + px(r.points[++j]);
      svg += fmt::format(
          "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.2\"/>\n", points,
          deviationColour((bin + 0.5) * scale / kBins, scale));
      i = j;
    }
  }
  // The colour bar: 0 at the bottom, the scale at the top, in centimetres.
  const double bx = w - barW + 20.0, by = pad + 30.0, bh = 200.0;
  for (int k = 0; k < kBins; ++k)
    svg += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"18\" height=\"{:.2f}\" fill=\"{}\"/>\n", bx,
        by + bh * (kBins - 1 - k) / kBins, bh / kBins + 0.3,
        deviationColour((k + 0.5) * scale / kBins, scale));
  for (int k = 0; k <= 4; ++k)
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{:.3g}</text>\n", bx + 24.0,
                       by + bh * (1.0 - k / 4.0) + 4.0, 100.0 * scale * k / 4.0);
  svg += fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\">cm from the</text><text x=\"{:.1f}\" y=\"{:.1f}\">design "
      "surface</text>\n",
      bx - 6.0, by + bh + 22.0, bx - 6.0, by + bh + 36.0);
  // A scale bar and north arrow under the plan (y is north, as on plan.svg).
  patching::plan::Projection proj;
  proj.scale = s;
  svg += patching::plan::scaleBarSvg(proj, spanX, pad, pad + 24.0 + spanY * s + 14.0,
                                     pad + spanX * s - 10.0);
  return svg + "</svg>\n";
}

}  // namespace egg::pipeline
