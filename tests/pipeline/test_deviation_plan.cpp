#include "pipeline/deviation_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace egg::pipeline {
namespace {

TEST(DeviationPlan, KnownDistancesGetKnownColours) {
  EXPECT_EQ(deviationColour(0.0, 0.2), "#2c7bb6");  // on the surface: blue
  EXPECT_EQ(deviationColour(0.1, 0.2), "#ffffbf");  // half the bar: pale yellow
  EXPECT_EQ(deviationColour(0.2, 0.2), "#d7191c");  // the bar's top: red
  EXPECT_EQ(deviationColour(5.0, 0.2), "#d7191c");  // beyond it stays red
  EXPECT_EQ(deviationColour(0.05, 0.2),
            "#96bdbb");  // a quarter: halfway blue -> yellow, (44+255)/2 = 149.5 -> 150
  EXPECT_EQ(deviationColour(NAN, 0.2), "#d7191c");  // unknown reads as the worst
}

TEST(DeviationPlan, ScaleRoundsUpToOneTwoFive) {
  EXPECT_DOUBLE_EQ(deviationScale(0.96), 1.0);
  EXPECT_DOUBLE_EQ(deviationScale(0.123), 0.2);
  EXPECT_DOUBLE_EQ(deviationScale(0.3), 0.5);
  EXPECT_DOUBLE_EQ(deviationScale(0.5), 0.5);
  EXPECT_DOUBLE_EQ(deviationScale(0.0), 0.01);
}

TEST(DeviationPlan, StretchesOfOneColourAreOnePolyline) {
  // A rod whose first three points lie on the surface and last two 1 m off: two colour runs.
  DeployedRod rod;
  for (int i = 0; i < 5; ++i) rod.points.emplace_back(i, 0.5 * i, 0.0);
  rod.distanceM = {0.0, 0.0, 0.0, 1.0, 1.0};
  const std::string svg = deployedPlanSvg({rod}, "a <test> & caption");
  EXPECT_EQ(svg.rfind("<svg id=\"deployed\" xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  size_t polylines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos;
       at = svg.find("<polyline", at + 1))
    ++polylines;
  EXPECT_EQ(polylines, 3u);  // 0-0-0 (blue), the 0 -> 1 segment (middle bin), 1-1 (red)
  // The bar runs to 1 m (the largest distance); the 1 m stretch is in the top bin of 16.
  EXPECT_NE(svg.find("stroke=\"" + deviationColour(15.5 / 16.0, 1.0) + "\""), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"" + deviationColour(0.5 / 16.0, 1.0) + "\""), std::string::npos);
  EXPECT_NE(svg.find("a &lt;test&gt; &amp; caption"), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

}  // namespace
}  // namespace egg::pipeline
