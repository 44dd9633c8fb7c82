#pragma once
// The coordinate frame of the report's small line charts (cladding_plot, error_time_plot): a plot
// rectangle on the SVG canvas (pixels, y down) and the data range it shows. Header only.
#include <algorithm>
#include <cmath>

namespace egg::pipeline {

struct PlotFrame {
  double left = 0.0, top = 0.0, width = 1.0, height = 1.0;
  double xMin = 0.0, xMax = 1.0, yMin = 0.0, yMax = 1.0;
  bool logY = false;  // y data plotted as log10 (yMin > 0)

  double px(double x) const { return left + width * (x - xMin) / (xMax - xMin); }
  // y clamped into the range, so that an outlier stays on the frame's edge (a log of y <= 0 at the
  // bottom).
  double py(double y) const {
    double t;
    if (logY)
      t = y > 0.0 ? (std::log10(y) - std::log10(yMin)) / (std::log10(yMax) - std::log10(yMin))
                  : 0.0;
    else
      t = (y - yMin) / (yMax - yMin);
    return top + height * (1.0 - std::clamp(t, 0.0, 1.0));
  }
};

// A round tick step (1, 2 or 5 x 10^k) giving at most `count` + 1 ticks over [0, span] (span > 0).
inline double tickStep(double span, int count) {
  const double raw = span / count;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

}  // namespace egg::pipeline
