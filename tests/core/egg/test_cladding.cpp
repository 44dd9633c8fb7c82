#include "core/egg/cladding.hpp"

#include "synthetic_maps.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

using testing::planarPatchMaps;
using testing::spherePatchMaps;

double meanSide(const PatchDistanceMaps& m) {
  return 0.25 * (m.sides[0] + m.sides[1] + m.sides[2] + m.sides[3]);
}

CladdingFunction cladding(const PatchDistanceMaps& maps, Family family, double alphaBar) {
  const auto quad = *planarQuad(maps.sides, alphaBar);
  const auto& m = maps.map(family);
  return claddingFunction(m, planarDistanceMap(quad, family, m.n1, m.n2), family, meanSide(maps));
}

TEST(Cladding, ParallelogramPairsEqualParameters) {
  // Opposite sides equal: |c1-c0 + t(c3-c0)| = |c1_bar-c0_bar + t(c3_bar-c0_bar)| only at t = u2-u1
  // = 0 for alpha_bar != alpha, so F is exactly the identity (parallel members, Figure 2.2 top).
  const auto maps = planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {2.6, 1.1}, {0.6, 1.1}}, 41);
  // The piecewise-linear intersection is exact to O(h^2) in position and O(h) in slope.
  const double h = 1.0 / 40;
  for (double shift : {-0.3, 0.2}) {
    for (Family family : {Family::U, Family::V}) {
      const auto f = cladding(maps, family, maps.alphaSpatial + shift);
      ASSERT_TRUE(f.bijective());
      EXPECT_FALSE(f.degenerate);
      for (const auto& p : f.points) EXPECT_NEAR(p.x(), p.y(), h * h);
      for (double s : segmentSlopes(f, 1e4)) EXPECT_NEAR(s, 1.0, 6 * h);
      EXPECT_LT(slopeViolation(f, 0.1, 10.0), 0.0);
    }
  }
}

TEST(Cladding, CoincidingMapsAreDegenerateIdentity) {
  // Developable patch at its unrolled angle: D == D_bar everywhere. No crash, no NaN.
  const auto maps = planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {1.8, 1.2}, {0.3, 1.0}}, 31);
  for (Family family : {Family::U, Family::V}) {
    const auto f = cladding(maps, family, maps.alphaSpatial);
    EXPECT_TRUE(f.degenerate);
    ASSERT_TRUE(f.bijective());
    for (size_t k = 0; k < f.points.size(); ++k) {
      EXPECT_DOUBLE_EQ(f.points[k].x(), f.points[k].y());
      EXPECT_TRUE(std::isfinite(f.lengths[k]));
    }
    EXPECT_NEAR(f.evaluate(0.37), 0.37, 1e-14);
  }
}

TEST(Cladding, PointsHaveEqualLengthsOnSurfaceAndPlane) {
  // Sphere patch: every point of F pairs boundary points whose great-circle distance equals the
  // planar distance (up to the O(h^2) error of the piecewise-linear intersection).
  const double radius = 5.0;
  const auto corners = testing::capCorners(0.5, {0.1, 1.7, 3.3, 4.8});
  const int n = 81;
  const auto maps = spherePatchMaps(corners, radius, n);
  const double alphaBar = maps.alphaSpatial - 0.6;  // inside the lower feasible interval
  const auto quad = *planarQuad(maps.sides, alphaBar);
  std::array<Eigen::Vector3d, 4> unit = corners;
  for (auto& c : unit) c.normalize();
  for (Family family : {Family::U, Family::V}) {
    const auto f = cladding(maps, family, alphaBar);
    ASSERT_TRUE(f.connectsCorners);
    const auto k = familyCorners(family);
    for (size_t i = 0; i < f.points.size(); ++i) {
      const double x1 = f.points[i].x(), x2 = f.points[i].y();
      const double surface =
          testing::greatCircle(testing::slerp(unit[k[0]], unit[k[1]], x1),
                               testing::slerp(unit[k[2]], unit[k[3]], x2), radius);
      const double plane = planarDistance(quad, family, x1, x2);
      EXPECT_NEAR(surface, plane, 2e-4 * radius) << i;
      EXPECT_NEAR(f.lengths[i], surface, 2e-4 * radius) << i;
    }
  }
}

TEST(Cladding, ConvergesUnderRefinement) {
  // The intersection of the interpolants converges to the exact curve at second order: compare
  // F(0.5) on coarse and fine grids against a very fine one.
  const auto corners = testing::capCorners(0.6, {0.0, 1.5, 3.2, 4.6});
  const auto at = [&](int n) {
    const auto maps = spherePatchMaps(corners, 1.0, n);
    return cladding(maps, Family::U, maps.alphaSpatial - 0.6).evaluate(0.3);
  };
  const double reference = at(641), coarse = std::abs(at(21) - reference),
               fine = std::abs(at(41) - reference);
  EXPECT_LT(fine, coarse);
  EXPECT_LT(fine, 1e-3);
}

TEST(Cladding, MissingIntersectionIsCompletedAlongTheBoundary) {
  // Far from the feasible angle the intersection does not link the corners; F is still a curve
  // from (0,0) to (1,1) but not bijective, and its slopes violate the bounds.
  const auto maps = planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {1.8, 1.2}, {0.3, 1.0}}, 31);
  DistanceMap shifted = maps.u;
  for (int i = 0; i < shifted.n1; ++i)
    for (int j = 0; j < shifted.n2; ++j)
      shifted.at(i, j) += 0.5 * std::sin(M_PI * i / 30.0) * std::sin(M_PI * j / 30.0);
  const auto quad = *planarQuad(maps.sides, maps.alphaSpatial);
  const auto f =
      claddingFunction(shifted, planarDistanceMap(quad, Family::U, 31, 31), Family::U, 1.0);
  EXPECT_FALSE(f.connectsCorners);
  EXPECT_FALSE(f.bijective());
  EXPECT_EQ(f.points.front(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(f.points.back(), Eigen::Vector2d(1, 1));
  EXPECT_GT(slopeViolation(f, 0.1, 10.0), 0.0);
  const auto slopes = segmentSlopes(f, 1e4);
  const bool outOfBounds =
      std::any_of(slopes.begin(), slopes.end(), [](double s) { return s <= 0.1 || s >= 10.0; });
  EXPECT_TRUE(outOfBounds);
}

TEST(Cladding, ClosedFormPlanarMapGivesTheSameCurveAsTheSampledOne) {
  // Problem 2.3 intersects against the planar map node by node (only where the zero set passes);
  // the curve must be the one the full sampled map gives, bit for bit, at angles with and
  // without a corner-to-corner intersection.
  const auto maps = spherePatchMaps(testing::capCorners(0.5, {0.1, 1.7, 3.3, 4.8}), 5.0, 61);
  int withArc = 0, withoutArc = 0;
  for (double shift : {-0.9, -0.6, -0.2, 0.0, 0.3, 0.7}) {
    const auto quad = planarQuad(maps.sides, maps.alphaSpatial + shift);
    if (!quad) continue;
    for (Family family : {Family::U, Family::V}) {
      const DistanceMap& m = maps.map(family);
      const auto sampled =
          claddingFunction(m, planarDistanceMap(*quad, family, m.n1, m.n2), family, 1.0);
      const auto closed = claddingFunction(m, *quad, family, 1.0);
      (sampled.connectsCorners ? withArc : withoutArc)++;
      EXPECT_EQ(closed.connectsCorners, sampled.connectsCorners);
      ASSERT_EQ(closed.points.size(), sampled.points.size());
      for (size_t k = 0; k < closed.points.size(); ++k) {
        EXPECT_EQ(closed.points[k], sampled.points[k]) << k;
        EXPECT_EQ(closed.lengths[k], sampled.lengths[k]) << k;
      }
    }
  }
  EXPECT_GT(withArc, 0);
  EXPECT_GT(withoutArc, 0);
}

TEST(Cladding, VerticalSegmentGetsTheThesisValue) {
  CladdingFunction f;
  f.points = {{0, 0}, {0, 0.5}, {1, 1}};
  const auto slopes = segmentSlopes(f, 1e4);
  ASSERT_EQ(slopes.size(), 2u);
  EXPECT_DOUBLE_EQ(slopes[0], 1e4 * 0.5);
  EXPECT_DOUBLE_EQ(slopes[1], 0.5);
  EXPECT_NEAR(slopeViolation(f, 0.1, 10.0), 1.0, 1e-15);  // vertical: dx2 - k_max dx1 = |segment|
}

}  // namespace
}  // namespace egg
