#include "core/drawing/label_layout.hpp"

#include <gtest/gtest.h>

#include <random>

namespace egg::drawing {
namespace {

TEST(LabelLayout, ABoxOverlappingATakenOneIsRefusedButTouchingEdgesAreNot) {
  LabelLayout layout({0, 0, 100, 50}, 5.0);
  EXPECT_TRUE(layout.placeBox({10, 10, 20, 14}));
  EXPECT_FALSE(layout.placeBox({19, 13, 30, 18}));  // one corner inside
  EXPECT_FALSE(layout.placeBox({12, 11, 18, 13}));  // wholly inside
  EXPECT_FALSE(layout.placeBox({0, 0, 100, 50}));   // covers it
  EXPECT_TRUE(layout.placeBox({20, 10, 30, 14}));   // shares the edge x = 20
  EXPECT_TRUE(layout.placeBox({10, 14, 20, 18}));   // shares the edge y = 14
  EXPECT_EQ(layout.taken().size(), 3u);
}

TEST(LabelLayout, ABoxReachingOffThePageIsRefused) {
  LabelLayout layout({10, 20, 110, 70}, 5.0);
  EXPECT_FALSE(layout.placeBox({9, 30, 15, 34}));
  EXPECT_FALSE(layout.placeBox({100, 66, 111, 69}));
  EXPECT_FALSE(layout.placeBox({50, 69, 60, 71}));
  EXPECT_TRUE(layout.placeBox({10, 20, 110, 70}));  // the page itself fits
}

TEST(LabelLayout, AReservedMarkerKeepsLabelsOffItEvenWhereItLeavesThePage) {
  LabelLayout layout({0, 0, 100, 100}, 4.0);
  layout.reserve({-5, -5, 3, 3});  // a dot at the corner, partly off the page
  EXPECT_FALSE(layout.isFree({0, 0, 2, 2}));
  EXPECT_TRUE(layout.isFree({3, 0, 8, 2}));
}

TEST(LabelLayout, PlaceFirstTakesTheFirstFreeCandidateInOrder) {
  LabelLayout layout({0, 0, 100, 100}, 10.0);
  layout.reserve({40, 40, 60, 60});
  EXPECT_EQ(layout.placeFirst({{45, 45, 55, 55}, {95, 0, 105, 10}, {60, 45, 70, 55}, {0, 0, 5, 5}}),
            2);
  EXPECT_EQ(layout.placeFirst({{41, 41, 42, 42}, {61, 50, 62, 51}}), -1);  // both taken now
}

// The grid of cells is only an index: the answers are those of testing every taken box, for
// boxes of any size against cells of any size (smaller than the labels, and larger).
TEST(LabelLayout, TheCellGridGivesTheAnswersOfTestingEveryBox) {
  for (const double cell : {0.5, 3.0, 40.0}) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> x(-10.0, 210.0), y(-10.0, 110.0), size(0.2, 25.0);
    LabelLayout layout({0, 0, 200, 100}, cell);
    std::vector<LabelBox> taken;
    int placed = 0;
    for (int k = 0; k < 3000; ++k) {
      const double x0 = x(random), y0 = y(random);
      const LabelBox box{x0, y0, x0 + size(random), y0 + 0.4 * size(random)};
      const bool inside = box.x0 >= 0 && box.y0 >= 0 && box.x1 <= 200 && box.y1 <= 100;
      bool free = inside;
      for (const auto& t : taken) free = free && !t.overlaps(box);
      ASSERT_EQ(layout.placeBox(box), free) << "box " << k << ", cell " << cell;
      if (free) taken.push_back(box), ++placed;
    }
    EXPECT_GT(placed, 100);
    EXPECT_EQ(layout.taken().size(), taken.size());
  }
}

TEST(LabelLayout, CandidatesStartAtThePointThenRingsEastFirstCounterClockwise) {
  const auto c = candidatesAround(10.0, 20.0, 2.0, 2);
  ASSERT_EQ(c.size(), 17u);
  EXPECT_EQ(c[0], Eigen::Vector2d(10.0, 20.0));
  EXPECT_NEAR(c[1].x(), 12.0, 1e-12);  // east
  EXPECT_NEAR(c[1].y(), 20.0, 1e-12);
  EXPECT_NEAR(c[3].x(), 10.0, 1e-12);  // north: up the page, y down
  EXPECT_NEAR(c[3].y(), 18.0, 1e-12);
  EXPECT_NEAR(c[9].x(), 14.0, 1e-12);  // second ring, east
}

}  // namespace
}  // namespace egg::drawing
