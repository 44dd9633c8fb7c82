#include "fabrication/sheet_layout.hpp"

#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

namespace egg::fabrication {
namespace {

TEST(SheetLayout, HandLamellaPrimitivesAtKnownMillimetres) {
  const EggGrid grid = testing::handGrid();
  const auto options = testing::handOptions();
  const auto plans = planLamellae({{0, &grid, std::nullopt}}, options);
  Drawing d;
  d.widthMm = 500.0;
  d.heightMm = 300.0;
  drawLamellaSegment(plans[1], 0, {215.5, 5.0}, options, d);  // P0-U1 where the nesting puts it
  // Outline 210 x 10.
  ASSERT_GE(d.polylines.size(), 1u);
  EXPECT_TRUE(d.polylines[0].closed);
  EXPECT_TRUE(d.polylines[0].points[2].isApprox(Eigen::Vector2d(425.5, 15.0)));
  // Holes at 5 and 205 mm along the strip, on the centreline y = 5 + 5.
  ASSERT_EQ(d.circles.size(), 2u);
  EXPECT_TRUE(d.circles[0].centre.isApprox(Eigen::Vector2d(220.5, 10.0)));
  EXPECT_TRUE(d.circles[1].centre.isApprox(Eigen::Vector2d(420.5, 10.0)));
  EXPECT_DOUBLE_EQ(d.circles[0].radius, 1.5);
  // The slot from 105 to 110 mm.
  ASSERT_EQ(d.slots.size(), 1u);
  EXPECT_TRUE(d.slots[0].a.isApprox(Eigen::Vector2d(320.5, 10.0)));
  EXPECT_TRUE(d.slots[0].b.isApprox(Eigen::Vector2d(325.5, 10.0)));
  // Connection labels 0.25 h after each feature's end; the lamella label centred in the longest gap
  // (from the first label's end 7.25 + 15.4 = 22.65 to the slot's start 103.5). "P0-C1-0" is 154
  // font units wide in futural.jhf (its glyphs' left and right bounds), at 2.1 / 21 mm per unit.
  ASSERT_EQ(d.texts.size(), 4u);
  EXPECT_EQ(d.texts[0].text, "P0-C1-0");
  EXPECT_NEAR(d.texts[0].anchor.x(), 222.75, 1e-12);
  EXPECT_NEAR(d.texts[0].height, 2.1, 1e-12);
  EXPECT_EQ(d.texts[1].text, "P0-C1-1");
  EXPECT_NEAR(d.texts[1].anchor.x(), 327.75, 1e-12);
  // The end hole's label would run off the strip: it ends 0.25 h before the hole instead.
  EXPECT_EQ(d.texts[2].text, "P0-C1-2");
  EXPECT_NEAR(d.texts[2].anchor.x(), 215.5 + 203.5 - 0.75 - 15.4, 1e-9);
  EXPECT_EQ(d.texts[3].text, "P0-U1");
  EXPECT_EQ(d.texts[3].align, TextAlign::Centre);
  EXPECT_NEAR(d.texts[3].anchor.x(), 215.5 + (22.65 + 103.5) / 2.0, 1e-9);
  EXPECT_NEAR(d.texts[3].anchor.y(), 10.0, 1e-12);
  // The slide arrow: engraved at y = 5 + (5 - 1.5) / 2, from the bolt's planar position 6 mm (2 h)
  // in the sliding direction (+x), with a head.
  ASSERT_EQ(d.polylines.size(), 3u);
  EXPECT_EQ(d.polylines[1].layer, Layer::Engrave);
  EXPECT_TRUE(d.polylines[1].points[0].isApprox(Eigen::Vector2d(320.5, 6.75)));
  EXPECT_TRUE(d.polylines[1].points[1].isApprox(Eigen::Vector2d(326.5, 6.75)));
  EXPECT_TRUE(d.polylines[2].points[1].isApprox(Eigen::Vector2d(326.5, 6.75)));
  EXPECT_LT(d.polylines[2].points[0].x(), 326.5);  // head points along +x
}

TEST(SheetLayout, SplicedSegmentsCarryTheirLabelAndSpliceMark) {
  const EggGrid grid = testing::handGrid();
  auto options = testing::handOptions();
  options.stockLengthMm = 150.0;
  const auto plans = planLamellae({{0, &grid, std::nullopt}}, options);
  const LamellaPlan& u1 = plans[1];
  ASSERT_EQ(u1.splicesMm.size(), 1u);
  EXPECT_DOUBLE_EQ(u1.splicesMm[0],
                   150.0);  // clear of the slot (93.5..121.5) and the end hole (193.5..216.5)
  EXPECT_EQ(segmentLabel(u1, 1), "P0-U1 2/2");
  Drawing d;
  drawLamellaSegment(u1, 1, {0.0, 0.0}, options, d);
  ASSERT_EQ(d.circles.size(), 1u);  // only the end hole lies in 150..210
  EXPECT_NEAR(d.circles[0].centre.x(), 55.0, 1e-12);
  EXPECT_TRUE(d.slots.empty());
  // The splice mark clearance/2 = 5 mm inside the spliced end.
  ASSERT_EQ(d.polylines.size(), 2u);
  EXPECT_EQ(d.polylines[1].layer, Layer::Engrave);
  EXPECT_NEAR(d.polylines[1].points[0].x(), 5.0, 1e-12);
}

TEST(SheetLayout, StickerWithItsSlotCutOut) {
  Sticker s;
  s.connectionId = "P0-C1-1";
  s.lamellaId = "P0-U1";
  s.lengthMm = 19.0;
  s.widthMm = 10.0;
  s.boltXMm = 8.0;
  s.slideMm = 5.0;
  Drawing d;
  drawSticker(s, {10.0, 20.0}, testing::handOptions(), d);
  ASSERT_EQ(d.slots.size(), 1u);
  EXPECT_TRUE(d.slots[0].a.isApprox(Eigen::Vector2d(18.0, 25.0)));
  EXPECT_TRUE(d.slots[0].b.isApprox(Eigen::Vector2d(23.0, 25.0)));
  ASSERT_EQ(d.texts.size(), 2u);
  // The longer free end is the start (0 .. 6.5 mm against 14.5 .. 19): labels centred at 3.25.
  EXPECT_NEAR(d.texts[0].anchor.x(), 13.25, 1e-12);
  EXPECT_NEAR(d.texts[0].height, 3.0, 1e-12);
}

TEST(SheetLayout, StadiumClippedToAPieceIsTheConvexPartInsideIt) {
  // Slot from x = 0 to 100, radius 8, clipped to 50 .. 200: a U open at x = 50, from -8 to +8.
  const auto poly = clippedStadium(0.0, 100.0, 8.0, 50.0, 200.0);
  ASSERT_GE(poly.size(), 4u);
  double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
  for (const auto& p : poly)
    minX = std::min(minX, p.x()), maxX = std::max(maxX, p.x()), minY = std::min(minY, p.y()),
    maxY = std::max(maxY, p.y());
  EXPECT_DOUBLE_EQ(minX, 50.0);
  EXPECT_NEAR(maxX, 108.0, 1e-9);
  EXPECT_NEAR(minY, -8.0, 1e-9);
  EXPECT_NEAR(maxY, 8.0, 1e-9);
  // Area: the 50 x 16 rectangle plus the half disc.
  double area = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % poly.size()];
    area += p.x() * q.y() - q.x() * p.y();
  }
  EXPECT_NEAR(std::abs(area) / 2.0, 50.0 * 16.0 + M_PI * 64.0 / 2.0, 0.5);  // 32-gon half circle
  EXPECT_TRUE(clippedStadium(0.0, 100.0, 8.0, 200.0, 300.0).empty());
}

}  // namespace
}  // namespace egg::fabrication
