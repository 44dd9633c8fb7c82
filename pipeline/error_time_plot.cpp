#include "pipeline/error_time_plot.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>

#include <algorithm>

namespace egg::pipeline {

using nlohmann::json;

json historyJson(const std::vector<rods::DeviationSample>& history) {
  json out = json::array();
  for (const auto& s : history)
    out.push_back({{"seconds", s.seconds},
                   {"iteration", s.iteration},
                   {"load_step", s.loadStep},
                   {"rmse_m", s.rmseM},
                   {"max_error_m", s.maxM}});
  return out;
}

std::vector<rods::DeviationSample> historyFromJson(const json& history, const std::string& where) {
  if (!history.is_array()) throw InvalidInput(where + " must be an array");
  std::vector<rods::DeviationSample> out;
  for (size_t k = 0; k < history.size(); ++k) {
    const json& h = history[k];
    const std::string at = where + "[" + std::to_string(k) + "]";
    for (const char* key : {"seconds", "iteration", "rmse_m", "max_error_m"})
      if (!h.is_object() || !h.contains(key) || !h[key].is_number())
        throw InvalidInput(at + "." + key + " must be a number");
    rods::DeviationSample s;
    s.seconds = h["seconds"].get<double>();
    s.iteration = h["iteration"].get<int>();
    s.loadStep = h.value("load_step", 0);
    s.rmseM = h["rmse_m"].get<double>();
    s.maxM = h["max_error_m"].get<double>();
    out.push_back(s);
  }
  return out;
}

namespace {
constexpr double kPanelLeft = 64.0, kPanelWidth = 300.0, kPanelGap = 90.0, kTop = 40.0,
                 kPlotHeight = 200.0;
const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
// Ten colours, then the same dashed, then dotted: 30 series stay apart (Yas and Lilium have 12-16
// patches).
const char* dashes(size_t series) {
  static const char* kDashes[] = {"", " stroke-dasharray=\"6 3\"", " stroke-dasharray=\"2 2\""};
  return kDashes[(series / 10) % 3];
}
}  // namespace

PlotFrame errorTimeFrame(int panel, const std::vector<ErrorTimeSeries>& series) {
  double seconds = 0.0, error = 0.0;
  for (const auto& s : series)
    for (const auto& p : s.samples) {
      seconds = std::max(seconds, p.seconds);
      error = std::max(error, panel == 0 ? p.rmseM : p.maxM);
    }
  return {kPanelLeft + panel * (kPanelWidth + kPanelGap),
          kTop,
          kPanelWidth,
          kPlotHeight,
          0.0,
          seconds > 0.0 ? seconds : 1.0,
          0.0,
          error > 0.0 ? 1.08 * error : 1.0,
          false};
}

std::string errorTimeSvg(const std::string& id, const std::string& title,
                         const std::vector<ErrorTimeSeries>& series) {
  std::vector<const ErrorTimeSeries*> drawn;
  for (const auto& s : series)
    if (!s.samples.empty()) drawn.push_back(&s);
  const int legendRows = (static_cast<int>(drawn.size()) + 5) / 6;
  const double width = kPanelLeft + 2 * kPanelWidth + kPanelGap + 30.0,
               height = kTop + kPlotHeight + 50.0 + 16.0 * legendRows;
  std::string svg = fmt::format(
      "<svg id=\"{0}\" class=\"chart\" width=\"{1:.0f}\" height=\"{2:.0f}\" "
      "viewBox=\"0 0 {1:.0f} {2:.0f}\" font-family=\"sans-serif\" font-size=\"11\" role=\"img\">\n"
      "<rect width=\"{1:.0f}\" height=\"{2:.0f}\" fill=\"white\"/>\n<text x=\"{3:.0f}\" y=\"16\" "
      "font-size=\"13\">{4}</text>\n",
      escapeXml(id), width, height, kPanelLeft, escapeXml(title));
  for (int panel = 0; panel < 2; ++panel) {
    const PlotFrame f = errorTimeFrame(panel, series);
    svg += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
        "stroke=\"#999\"/>\n",
        f.left, f.top, f.width, f.height);
    const double xStep = tickStep(f.xMax, 5), yStep = tickStep(f.yMax, 5);
    for (int k = 0; k * xStep <= f.xMax * (1.0 + 1e-9); ++k)
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:g}</text>",
                         f.px(k * xStep), f.top + f.height + 15.0, k * xStep);
    for (int k = 0; k * yStep <= f.yMax * (1.0 + 1e-9); ++k) {
      svg += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"{1:.2f}\" x2=\"{2:.1f}\" y2=\"{1:.2f}\" stroke=\"#eee\"/>",
          f.left, f.py(k * yStep), f.left + f.width);
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.2f}\" text-anchor=\"end\">{:g}</text>",
                         f.left - 5.0, f.py(k * yStep) + 4.0, k * yStep);
    }
    svg += fmt::format(
        "\n<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">wall time of the run "
        "(s)</text>\n",
        f.left + f.width / 2, f.top + f.height + 30.0);
    svg += fmt::format(
        "<text transform=\"translate({:.1f},{:.1f}) rotate(-90)\" text-anchor=\"middle\">{} "
        "(m)</text>\n",
        f.left - 46.0, f.top + f.height / 2, panel == 0 ? "RMSE" : "max error");
    for (size_t k = 0; k < drawn.size(); ++k) {
      std::string points;
      for (const auto& p : drawn[k]->samples)
        points += fmt::format("{}{:.2f},{:.2f}", points.empty() ? "" : " ", f.px(p.seconds),
                              f.py(panel == 0 ? p.rmseM : p.maxM));
      svg += fmt::format(
          "<polyline id=\"{}-{}-{}\" points=\"{}\" fill=\"none\" stroke=\"{}\" "
          "stroke-width=\"1.5\"{}/>\n",
          escapeXml(id), panel == 0 ? "rmse" : "max", k, points, kPalette[k % 10], dashes(k));
      // The samples themselves: the line between them is no measurement.
      for (const auto& p : drawn[k]->samples)
        svg += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"1.8\" fill=\"{}\"/>",
                           f.px(p.seconds), f.py(panel == 0 ? p.rmseM : p.maxM), kPalette[k % 10]);
      svg += "\n";
    }
  }
  for (size_t k = 0; k < drawn.size(); ++k) {
    const double x = kPanelLeft + 110.0 * static_cast<double>(k % 6),
                 y = kTop + kPlotHeight + 50.0 + 16.0 * static_cast<double>(k / 6);
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"{3}\" "
        "stroke-width=\"2\"{7}/>"
        "<text x=\"{4:.1f}\" y=\"{5:.1f}\">{6}</text>\n",
        x, y - 4.0, x + 18.0, kPalette[k % 10], x + 22.0, y, escapeXml(drawn[k]->label), dashes(k));
  }
  return svg + "</svg>\n";
}

}  // namespace egg::pipeline
