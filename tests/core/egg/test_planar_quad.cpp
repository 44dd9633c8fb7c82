#include "core/egg/planar_quad.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

TEST(PlanarQuad, UnitSquareAtRightAngle) {
  const auto quad = planarQuad({1, 1, 1, 1}, M_PI / 2);
  ASSERT_TRUE(quad);
  EXPECT_NEAR((quad->corners[2] - Eigen::Vector2d(1, 1)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((quad->corners[3] - Eigen::Vector2d(0, 1)).norm(), 0.0, 1e-14);
  for (double angle : innerAngles(quad->corners)) EXPECT_NEAR(angle, M_PI / 2, 1e-14);
}

TEST(PlanarQuad, KeepsSideLengthsAndAngleSumsToTwoPi) {
  const QuadSides sides{2.0, 1.2, 1.6, 1.0};
  for (double alpha : {1.0, 1.3, 1.7}) {
    const auto quad = planarQuad(sides, alpha);
    ASSERT_TRUE(quad) << alpha;
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR((quad->corners[(k + 1) % 4] - quad->corners[k]).norm(), sides[k], 1e-12);
    const auto angles = innerAngles(quad->corners);
    EXPECT_NEAR(angles[0], alpha, 1e-12);
    EXPECT_NEAR(angles[0] + angles[1] + angles[2] + angles[3], 2 * M_PI, 1e-12);
  }
}

TEST(PlanarQuad, RhombusCollapsesAtBothEnds) {
  // Opposite sides equal: the linkage folds flat at 0 and pi (Section 3.4.2).
  const auto range = convexAlphaRange({1.5, 1.0, 1.5, 1.0}, 1e-6);
  ASSERT_TRUE(range);
  EXPECT_NEAR(range->lo, 0.0, 1e-5);
  EXPECT_NEAR(range->hi, M_PI, 1e-5);
}

TEST(PlanarQuad, MinimumAngleNarrowsTheRange) {
  // A parallelogram's inner angles are alpha_bar and pi - alpha_bar.
  const auto range = convexAlphaRange({1.5, 1.0, 1.5, 1.0}, 0.0, 0.2);
  ASSERT_TRUE(range);
  EXPECT_NEAR(range->lo, 0.2, 1e-9);
  EXPECT_NEAR(range->hi, M_PI - 0.2, 1e-9);
  EXPECT_FALSE(planarQuad({1.5, 1.0, 1.5, 1.0}, 0.19, 0.2));
}

TEST(PlanarQuad, ConvexRangeEndsWhereAnAngleReachesPi) {
  const QuadSides sides{2.0, 1.2, 1.6, 1.0};
  const auto range = convexAlphaRange(sides, 1e-9);
  ASSERT_TRUE(range);
  EXPECT_GT(range->lo, 0.05);
  EXPECT_LT(range->hi, M_PI - 0.05);
  EXPECT_TRUE(planarQuad(sides, range->lo));
  EXPECT_TRUE(planarQuad(sides, range->hi));
  EXPECT_FALSE(planarQuad(sides, range->lo - 1e-6));
  EXPECT_FALSE(planarQuad(sides, range->hi + 1e-6));
  // At the lower end the quad degenerates: one inner angle reaches pi or the linkage stretches
  // straight (|c1 c3| = sides[1] + sides[2]).
  const auto quad = *planarQuad(sides, range->lo);
  const auto angles = innerAngles(quad.corners);
  const double largest = std::max({angles[1], angles[2], angles[3]});
  const double stretch = (quad.corners[3] - quad.corners[1]).norm() - (sides[1] + sides[2]);
  EXPECT_TRUE(largest > M_PI - 1e-3 || std::abs(stretch) < 1e-6) << largest << " " << stretch;
}

TEST(PlanarQuad, ImpossibleSidesHaveNoRange) {
  EXPECT_FALSE(convexAlphaRange({10.0, 1.0, 1.0, 1.0}));
  EXPECT_FALSE(planarQuad({1, 1, 1, 1}, 0.0));
  EXPECT_FALSE(planarQuad({1, 1, 1, 1}, M_PI));
}

TEST(PlanarQuad, MembersRunBetweenOppositeSides) {
  const auto quad = *planarQuad({1, 1, 1, 1}, M_PI / 2);
  // u-family: c0->c3 to c1->c2; (0,0) is side c0c1.
  auto ends = planarMember(quad, Family::U, 0.25, 0.75);
  EXPECT_NEAR((ends[0] - Eigen::Vector2d(0, 0.25)).norm(), 0, 1e-14);
  EXPECT_NEAR((ends[1] - Eigen::Vector2d(1, 0.75)).norm(), 0, 1e-14);
  EXPECT_NEAR(planarDistance(quad, Family::U, 0.25, 0.75), std::sqrt(1.25), 1e-14);
  // v-family: c0->c1 to c3->c2.
  ends = planarMember(quad, Family::V, 0.5, 0.5);
  EXPECT_NEAR((ends[0] - Eigen::Vector2d(0.5, 0)).norm(), 0, 1e-14);
  EXPECT_NEAR((ends[1] - Eigen::Vector2d(0.5, 1)).norm(), 0, 1e-14);
}

}  // namespace
}  // namespace egg
