#include "fabrication/drawing.hpp"

#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace egg::fabrication {
namespace {

Drawing sample() {
  Drawing d;
  d.title = "sample & <test>";
  d.widthMm = 120.0;
  d.heightMm = 80.0;
  d.circles.push_back({Layer::Cut, {10.0, 20.0}, 1.5});
  d.slots.push_back({Layer::Cut, {30.0, 20.0}, {40.0, 20.0}, 2.0});
  d.polylines.push_back({Layer::Cut, {{0, 0}, {100, 0}, {100, 40}, {0, 40}}, true});
  d.polylines.push_back({Layer::Engrave, {{50, 5}, {60, 5}}, false});
  d.texts.push_back({Layer::Label, {70.0, 20.0}, 3.0, "P0-U1", TextAlign::Centre});
  return d;
}

TEST(Drawing, SlotCornersRunCounterClockwise) {
  const auto k = slotCorners({Layer::Cut, {30.0, 20.0}, {40.0, 20.0}, 2.0});
  EXPECT_TRUE(k[0].isApprox(Eigen::Vector2d(30, 18)));
  EXPECT_TRUE(k[1].isApprox(Eigen::Vector2d(40, 18)));
  EXPECT_TRUE(k[2].isApprox(Eigen::Vector2d(40, 22)));
  EXPECT_TRUE(k[3].isApprox(Eigen::Vector2d(30, 22)));
}

TEST(Drawing, SvgIsInMillimetresWithLaserColoursAndReadsBack) {
  const std::string svg = toSvg(sample());
  EXPECT_NE(svg.find("width=\"120.0000mm\" height=\"80.0000mm\" viewBox=\"0 0 120.0000 80.0000\""),
            std::string::npos);
  EXPECT_NE(svg.find("stroke=\"#ff0000\""), std::string::npos);     // cut: red
  EXPECT_NE(svg.find("stroke=\"#0000ff\""), std::string::npos);     // engrave: blue
  EXPECT_NE(svg.find("stroke-width=\"0.01\""), std::string::npos);  // hairline
  EXPECT_NE(svg.find("sample &amp; &lt;test&gt;"), std::string::npos);
  const auto back = testing::readSvg(svg);
  ASSERT_EQ(back["circles"].size(), 1u);
  EXPECT_NEAR(back["circles"][0][0].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(back["circles"][0][1].get<double>(), 20.0, 1e-9);  // y up again
  EXPECT_NEAR(back["circles"][0][2].get<double>(), 1.5, 1e-9);
  ASSERT_EQ(back["slots"].size(), 1u);
  EXPECT_NEAR(back["slots"][0][0].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(back["slots"][0][1].get<double>(), 18.0, 1e-9);
  EXPECT_NEAR(back["slots"][0][4].get<double>(), 40.0, 1e-9);
  EXPECT_NEAR(back["slots"][0][5].get<double>(), 22.0, 1e-9);
  ASSERT_EQ(back["texts"].size(), 1u);
  EXPECT_EQ(back["texts"][0][3], "P0-U1");
  EXPECT_NEAR(back["texts"][0][1].get<double>(), 20.0, 1e-9);
  EXPECT_EQ(back["polylines"].size(), 2u);
}

TEST(Drawing, SvgRendersWithRsvgConvert) {
  ASSERT_TRUE(testing::haveTool("rsvg-convert"))
      << "rsvg-convert missing: run scripts/install-deps.sh (librsvg2-bin)";
  const auto dir = testing::scratchDir("drawing_svg");
  std::ofstream(dir / "sample.svg") << toSvg(sample());
  const auto run =
      testing::runTool("rsvg-convert --format=png --output " + (dir / "sample.png").string() + " " +
                       (dir / "sample.svg").string());
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_GT(std::filesystem::file_size(dir / "sample.png"), 100u);
}

}  // namespace
}  // namespace egg::fabrication
