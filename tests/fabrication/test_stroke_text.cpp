#include "fabrication/stroke_text.hpp"

#include <gtest/gtest.h>

namespace egg::fabrication {
namespace {

// futural.jhf's "A" is `I[RFJ[ RRFZ[ RMTWT`: bounds I..[ (-9..9: 18 units wide), strokes from the
// apex R F = (0, -12) to J [ = (-8, 9), to Z [ = (8, 9), and the bar M T..W T = (-5, 2)..(5, 2);
// the baseline is y = 9, capitals 21 units high (F = -12), y down. At a capital height of 21 mm a
// unit is a millimetre: shifted by the left bound and flipped, the apex is (9, 21).
TEST(StrokeText, HersheyCapitalAAtKnownMillimetres) {
  const auto strokes = textStrokes("A", 21.0);
  ASSERT_EQ(strokes.size(), 3u);
  ASSERT_EQ(strokes[0].size(), 2u);
  EXPECT_TRUE(strokes[0][0].isApprox(Eigen::Vector2d(9.0, 21.0)));
  EXPECT_TRUE(strokes[0][1].isApprox(Eigen::Vector2d(1.0, 0.0)));
  EXPECT_TRUE(strokes[1][1].isApprox(Eigen::Vector2d(17.0, 0.0)));
  EXPECT_TRUE(strokes[2][0].isApprox(Eigen::Vector2d(4.0, 7.0)));
  EXPECT_DOUBLE_EQ(strokeTextWidthMm("A", 21.0), 18.0);
  EXPECT_DOUBLE_EQ(strokeTextWidthMm("A", 3.0), 18.0 * 3.0 / 21.0);
  // Advances add up: "AA"'s second A starts 18 units on.
  const auto two = textStrokes("AA", 21.0);
  ASSERT_EQ(two.size(), 6u);
  EXPECT_TRUE(two[3][0].isApprox(Eigen::Vector2d(27.0, 21.0)));
}

TEST(StrokeText, PlacedCentredOnItsAnchor) {
  // Centred: the advance width's middle on the anchor, capitals from anchor.y - h/2 to + h/2.
  const DrawText t{Layer::Label, {100.0, 50.0}, 21.0, "A", TextAlign::Centre};
  const auto strokes = placedStrokes(t);
  ASSERT_EQ(strokes.size(), 3u);
  EXPECT_TRUE(strokes[0][0].isApprox(Eigen::Vector2d(100.0, 60.5)));  // apex: 91 + 9, 39.5 + 21
  EXPECT_TRUE(strokes[0][1].isApprox(Eigen::Vector2d(92.0, 39.5)));
  // Left-aligned: the advance starts at the anchor.
  const auto left = placedStrokes({Layer::Label, {100.0, 50.0}, 21.0, "A", TextAlign::Left});
  EXPECT_TRUE(left[0][0].isApprox(Eigen::Vector2d(109.0, 60.5)));
}

TEST(StrokeText, CharactersTheFontLacksAdvanceAsASpace) {
  // futural covers printable ASCII only; a byte above it is drawn as a space (no strokes).
  EXPECT_TRUE(textStrokes("\xe9", 10.0).empty());
  EXPECT_DOUBLE_EQ(strokeTextWidthMm("\xe9", 10.0), strokeTextWidthMm(" ", 10.0));
  EXPECT_GT(strokeTextWidthMm(" ", 10.0), 0.0);
}

}  // namespace
}  // namespace egg::fabrication
