#include "pipeline/cladding_plot.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <string>

namespace egg::pipeline {
namespace {

// A known piecewise-linear F: (0,0) -> (0.5,0.25) -> (0.5,0.5) -> (1,1), slopes 0.5, vertical, 1;
// start side 10 m, end side 20 m; three members.
CladdingPlot knownPlot() {
  CladdingPlot plot;
  plot.patch = 7;
  plot.slopeMin = 0.1, plot.slopeMax = 10.0, plot.infiniteSlopeFactor = 1e4;
  plot.u.family = "u";
  plot.u.startSideM = 10.0, plot.u.endSideM = 20.0;
  plot.u.points = {{0.0, 0.0}, {0.5, 0.25}, {0.5, 0.5}, {1.0, 1.0}};
  plot.u.members = {{0.0, 0.0}, {0.5, 0.25}, {1.0, 1.0}};
  plot.v = plot.u;
  plot.v.family = "v";
  plot.v.points = {{0.0, 0.0}, {1.0, 1.0}};
  plot.v.members = {{0.0, 0.0}, {1.0, 1.0}};
  return plot;
}

std::string attribute(const std::string& svg, const std::string& id, const std::string& name) {
  const std::regex element("id=\"" + id + "\"[^>]*?" + name + "=\"([^\"]*)\"");
  std::smatch match;
  return std::regex_search(svg, match, element) ? match[1].str() : std::string("<none>");
}

TEST(CladdingPlot, FramesMapMetresAndLogSlopesToKnownPixels) {
  const CladdingPlot plot = knownPlot();
  const PlotFrame u = claddingFrame(plot.u, 0), v = claddingFrame(plot.v, 1);
  // The F panel of u: 250 px square at (58, 40); x over the 10 m start side, y over the 20 m end
  // side, y up.
  EXPECT_DOUBLE_EQ(u.px(0.0), 58.0);
  EXPECT_DOUBLE_EQ(u.px(10.0), 308.0);
  EXPECT_DOUBLE_EQ(u.py(0.0), 290.0);
  EXPECT_DOUBLE_EQ(u.py(20.0), 40.0);
  EXPECT_DOUBLE_EQ(v.px(0.0), 58.0 + 320.0);  // the v panel one column to the right
  // The slope strip: log axis from k_min / 4 to 4 k_max, 110 px high from y = 340; slope 1 sits
  // in the middle of the symmetric range [0.025, 40] (log10: -1.602 .. 1.602).
  const PlotFrame s = slopeFrame(plot.u, 0, 0.1, 10.0);
  EXPECT_DOUBLE_EQ(s.py(1.0), 340.0 + 55.0);
  EXPECT_NEAR(
      s.py(10.0),
      340.0 + 110.0 * (1.0 - (1.0 - std::log10(0.025)) / (std::log10(40.0) - std::log10(0.025))),
      1e-9);
  EXPECT_DOUBLE_EQ(s.py(40.0), 340.0);
  EXPECT_DOUBLE_EQ(s.py(1e9), 340.0);  // clamped to the top
  EXPECT_DOUBLE_EQ(s.py(0.0), 450.0);  // a flat segment: at the bottom
}

TEST(CladdingPlot, KnownPiecewiseLinearFunctionPlotsToKnownCoordinates) {
  const CladdingPlot plot = knownPlot();
  const std::string svg = claddingSvg(plot);
  EXPECT_EQ(svg.rfind("<svg id=\"cladding-patch-7\" class=\"chart\"", 0), 0u);
  // (0,0) (5 m, 5 m) (5 m, 10 m) (10 m, 20 m): x = 58 + 25 x, y = 290 - 12.5 y.
  EXPECT_EQ(attribute(svg, "patch-7-u-curve", "points"),
            "58.00,290.00 183.00,227.50 183.00,165.00 308.00,40.00");
  EXPECT_EQ(attribute(svg, "patch-7-v-curve", "points"), "378.00,290.00 628.00,40.00");
  // Slopes 0.5 on [0, 5 m] and 1 on [5 m, 10 m] inside the band; the vertical segment (c dx2 =
  // 2500) outside it, in the violations path at the strip's top.
  const PlotFrame s = slopeFrame(plot.u, 0, 0.1, 10.0);
  char expected[200];
  std::snprintf(expected, sizeof(expected), "M58.00 %.2fH183.00M183.00 395.00H308.00", s.py(0.5));
  EXPECT_EQ(attribute(svg, "patch-7-u-slopes", "d"), expected);
  EXPECT_EQ(attribute(svg, "patch-7-u-violations", "d"), "M183.00 340.00H183.00");
  EXPECT_EQ(attribute(svg, "patch-7-v-violations", "d"), "<none>");  // the diagonal: slope 1 only
  // The band between k_min and k_max.
  EXPECT_EQ(attribute(svg, "patch-7-u-band", "y"), fmt::format("{:.1f}", s.py(10.0)));
  // Three members of u and two of v as dots.
  size_t dots = 0;
  for (size_t at = svg.find("class=\"member\""); at != std::string::npos;
       at = svg.find("class=\"member\"", at + 1))
    ++dots;
  EXPECT_EQ(dots, 5u);
  EXPECT_NE(svg.find("cx=\"183.00\" cy=\"227.50\""),
            std::string::npos);  // member (0.5, 0.25) = (5 m, 5 m)
}

TEST(CladdingPlot, SlopesFollowTheThesisRule) {
  CladdingCurve c;
  c.points = {{0.0, 0.0}, {0.25, 0.5}, {0.25, 0.5}, {0.25, 0.75}, {1.0, 0.75}, {1.0, 1.0}};
  const auto slopes = claddingSlopes(c, 100.0);
  ASSERT_EQ(slopes.size(), 4u);  // the zero-length segment is skipped
  EXPECT_DOUBLE_EQ(slopes[0][2], 2.0);
  EXPECT_DOUBLE_EQ(slopes[1][2], 25.0);  // vertical: c dx2 = 100 x 0.25
  EXPECT_DOUBLE_EQ(slopes[2][2], 0.0);
  EXPECT_DOUBLE_EQ(slopes[3][2], 25.0);
  EXPECT_DOUBLE_EQ(slopes[2][0], 0.25);
  EXPECT_DOUBLE_EQ(slopes[2][1], 1.0);
}

TEST(CladdingPlot, ReportEntryRoundTrips) {
  CladdingFunction u, v;
  u.family = Family::U, v.family = Family::V;
  u.points = {{0.0, 0.0}, {0.5, 0.25}, {1.0, 1.0}};
  v.points = {{0.0, 0.0}, {1.0, 1.0}};
  u.connectsCorners = true;
  v.connectsCorners =
      false;  // as an intersection that misses a corner: not bijective (criterion iii)
  FamilyMembers mu, mv;
  mu.x1 = {0.0, 0.5, 1.0}, mu.x2 = {0.0, 0.25, 1.0};
  mv.x1 = {0.0, 1.0}, mv.x2 = {0.0, 1.0};
  nlohmann::json entry{{"id", 3}};
  entry["cladding"] = claddingEntry(u, v, mu, mv, {10.0, 20.0}, {30.0, 40.0}, 0.2, 5.0, 1e4);
  EXPECT_EQ(entry["cladding"]["slope_bounds"], nlohmann::json({0.2, 5.0}));
  EXPECT_TRUE(entry["cladding"]["u"]["bijective"].get<bool>());
  EXPECT_FALSE(entry["cladding"]["v"]["bijective"].get<bool>());
  const auto plot = claddingFromReport(entry);
  ASSERT_TRUE(plot.has_value());
  EXPECT_EQ(plot->patch, 3);
  EXPECT_EQ(plot->slopeMin, 0.2);
  EXPECT_EQ(plot->slopeMax, 5.0);
  EXPECT_EQ(plot->u.startSideM, 10.0);
  EXPECT_EQ(plot->v.endSideM, 40.0);
  ASSERT_EQ(plot->u.points.size(), 3u);
  EXPECT_EQ(plot->u.points[1][1], 0.25);
  ASSERT_EQ(plot->u.members.size(), 3u);
  EXPECT_EQ(plot->u.members[1][0], 0.5);
  // No entry: no plot; a broken one names the key.
  EXPECT_FALSE(claddingFromReport(nlohmann::json{{"id", 1}}).has_value());
  entry["cladding"]["u"]["points_x2"].erase(0);
  try {
    claddingFromReport(entry);
    FAIL() << "a short points_x2 must be refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("patches[3].cladding.u"), std::string::npos) << e.what();
  }
  entry["cladding"]["slope_bounds"] = {5.0, 0.2};
  EXPECT_THROW(claddingFromReport(entry), InvalidInput);
}

}  // namespace
}  // namespace egg::pipeline
