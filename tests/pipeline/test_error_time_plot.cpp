#include "pipeline/error_time_plot.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <regex>
#include <string>

namespace egg::pipeline {
namespace {

std::vector<rods::DeviationSample> samples() {
  // (iteration, load step, seconds, rmse, max)
  return {{0, 0, 0.0, 0.0, 0.0}, {8, 0, 1.0, 0.05, 0.2}, {16, 1, 2.0, 0.1, 0.5}};
}

std::string svgAttribute(const std::string& svg, const std::string& id, const std::string& name) {
  const std::regex element("id=\"" + id + "\"[^>]*?" + name + "=\"([^\"]*)\"");
  std::smatch match;
  return std::regex_search(svg, match, element) ? match[1].str() : std::string("<none>");
}

TEST(ErrorTimePlot, HistoryRoundTripsThroughTheReport) {
  const nlohmann::json j = historyJson(samples());
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[1], nlohmann::json({{"seconds", 1.0},
                                  {"iteration", 8},
                                  {"load_step", 0},
                                  {"rmse_m", 0.05},
                                  {"max_error_m", 0.2}}));
  const auto back = historyFromJson(j, "simulation.joined.history");
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].iteration, 16);
  EXPECT_EQ(back[2].loadStep, 1);
  EXPECT_EQ(back[2].seconds, 2.0);
  EXPECT_EQ(back[2].rmseM, 0.1);
  EXPECT_EQ(back[2].maxM, 0.5);
  nlohmann::json broken = j;
  broken[1].erase("rmse_m");
  try {
    historyFromJson(broken, "simulation.joined.history");
    FAIL() << "a sample without rmse_m must be refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("simulation.joined.history[1].rmse_m"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(historyFromJson(nlohmann::json::object(), "h"), InvalidInput);
}

TEST(ErrorTimePlot, KnownSamplesPlotToKnownCoordinates) {
  const std::vector<ErrorTimeSeries> series{{"patch 0", samples()}, {"patch 1", {}}};
  // Time 0 .. 2 s over 300 px from x = 64; RMSE 0 .. 0.108 (8 % headroom) over 200 px up from y =
  // 240.
  const PlotFrame rmse = errorTimeFrame(0, series), max = errorTimeFrame(1, series);
  EXPECT_DOUBLE_EQ(rmse.xMax, 2.0);
  EXPECT_DOUBLE_EQ(rmse.yMax, 0.108);
  EXPECT_DOUBLE_EQ(max.yMax, 0.54);
  EXPECT_DOUBLE_EQ(max.left, 64.0 + 300.0 + 90.0);
  const std::string svg = errorTimeSvg("error-time-test", "a <title>", series);
  EXPECT_EQ(svg.rfind("<svg id=\"error-time-test\" class=\"chart\"", 0), 0u);
  EXPECT_NE(svg.find("a &lt;title&gt;"), std::string::npos);
  // RMSE: (0 s, 0) (1 s, 0.05) (2 s, 0.1) -> y = 240 - 200 e / 0.108.
  EXPECT_EQ(svgAttribute(svg, "error-time-test-rmse-0", "points"),
            fmt::format("64.00,240.00 214.00,{:.2f} 364.00,{:.2f}", 240.0 - 200.0 * 0.05 / 0.108,
                        240.0 - 200.0 * 0.1 / 0.108));
  EXPECT_EQ(svgAttribute(svg, "error-time-test-max-0", "points"),
            fmt::format("454.00,240.00 604.00,{:.2f} 754.00,{:.2f}", 240.0 - 200.0 * 0.2 / 0.54,
                        40.0 + 200.0 * (1.0 - 0.5 / 0.54)));
  // Each sample a dot, in both panels: (1 s, 0.2 m) in the max panel.
  size_t dots = 0;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1))
    ++dots;
  EXPECT_EQ(dots, 6u);
  EXPECT_NE(
      svg.find(fmt::format("<circle cx=\"604.00\" cy=\"{:.2f}\"", 240.0 - 200.0 * 0.2 / 0.54)),
      std::string::npos);
  // The empty series is not drawn and not in the legend.
  EXPECT_EQ(svgAttribute(svg, "error-time-test-rmse-1", "points"), "<none>");
  EXPECT_EQ(svg.find("patch 1"), std::string::npos);
  EXPECT_NE(svg.find(">patch 0<"), std::string::npos);
}

TEST(ErrorTimePlot, SeriesBeyondTenColoursAreDashed) {
  std::vector<ErrorTimeSeries> series;
  for (int k = 0; k < 12; ++k) series.push_back({"patch " + std::to_string(k), samples()});
  const std::string svg = errorTimeSvg("e", "twelve", series);
  const std::regex first("id=\"e-rmse-0\"[^>]*stroke=\"#1f77b4\" stroke-width=\"1.5\"/>");
  const std::regex eleventh(
      "id=\"e-rmse-10\"[^>]*stroke=\"#1f77b4\" stroke-width=\"1.5\" stroke-dasharray=\"6 3\"/>");
  EXPECT_TRUE(std::regex_search(svg, first));
  EXPECT_TRUE(std::regex_search(svg, eleventh));
}

}  // namespace
}  // namespace egg::pipeline
