// The planar pieces of the window propagation with known answers: the cone of directions a
// shortest path may leave a pseudo-source in, and where its rays cross the opposite edge.
#include "core/geodesic/window_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace egg::geodesic::detail {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WindowGeometry, InteriorSaddleAllowsTheExcessConeOppositeTheIncomingDirection) {
  // Angle sum 2 pi + 0.2, path arriving from fan angle 0: allowed [pi, pi + 0.2].
  double lo = 0, hi = 0;
  ASSERT_TRUE(allowedFanInterval(3.0, 3.5, 0.0, 2 * kPi + 0.2, false, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, kPi);
  EXPECT_DOUBLE_EQ(hi, kPi + 0.2);
  EXPECT_FALSE(allowedFanInterval(0.5, 2.0, 0.0, 2 * kPi + 0.2, false, 0.0, lo, hi));
  // The cone wraps around the angle sum: arriving from 4.0, allowed [4 + pi, 4 + pi + 0.2] - total.
  const double total = 2 * kPi + 0.2;
  ASSERT_TRUE(allowedFanInterval(0.0, 1.5, 4.0, total, false, 0.0, lo, hi));
  EXPECT_NEAR(lo, 4.0 + kPi - total, 1e-15);
  EXPECT_NEAR(hi, 4.0 + kPi + 0.2 - total, 1e-15);
}

TEST(WindowGeometry, ReflexBoundaryCornerAllowsBothSidesBeyondPi) {
  // Angle sum 1.5 pi, arriving from 0.25 pi: nothing on the near side (it would need angles below
  // -0.75 pi), and [1.25 pi, 1.5 pi] on the far side.
  double lo = 0, hi = 0;
  ASSERT_TRUE(allowedFanInterval(1.0 * kPi, 1.5 * kPi, 0.25 * kPi, 1.5 * kPi, true, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, 1.25 * kPi);
  EXPECT_DOUBLE_EQ(hi, 1.5 * kPi);
  // Arriving from 1.25 pi the allowed side is [0, 0.25 pi].
  ASSERT_TRUE(allowedFanInterval(0.0, 0.5 * kPi, 1.25 * kPi, 1.5 * kPi, true, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_NEAR(hi, 0.25 * kPi, 1e-15);
}

TEST(WindowGeometry, ConeRaysCrossTheOppositeEdgeWhereTheyShould) {
  // v at (0.5, 0.5) above the edge from B = (0,0) to C = (1,0): the corner at v is 90 degrees and
  // the ray turned 45 degrees from v->B hits the middle; 0 and 90 degrees hit B and C.
  const double corner = kPi / 2;
  const auto [b, c] = coneCrossings(0.5, 0.5, 1.0, corner, 0.0, corner);
  EXPECT_DOUBLE_EQ(b, 0.0);
  EXPECT_DOUBLE_EQ(c, 1.0);
  const auto [m0, m1] = coneCrossings(0.5, 0.5, 1.0, corner, kPi / 4, kPi / 4);
  EXPECT_NEAR(m0, 0.5, 1e-15);
  EXPECT_NEAR(m1, 0.5, 1e-15);
  // 30 degrees from v->B: x = 0.5 - 0.5 tan(15 deg).
  const auto [x, unused] = coneCrossings(0.5, 0.5, 1.0, corner, kPi / 6, corner);
  EXPECT_NEAR(x, 0.5 - 0.5 * std::tan(kPi / 12), 1e-14);
  (void)unused;
  // A needle face keeps the whole edge.
  const auto [n0, n1] = coneCrossings(0.5, 1e-12, 1.0, kPi - 1e-10, 0.1, 0.2);
  EXPECT_EQ(n0, 0.0);
  EXPECT_EQ(n1, 1.0);
}

}  // namespace
}  // namespace egg::geodesic::detail
