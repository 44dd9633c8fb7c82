#include "core/egg/alpha_bar.hpp"

#include "core/errors.hpp"
#include "synthetic_maps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace egg {
namespace {

using testing::planarPatchMaps;
using testing::spherePatchMaps;

const std::array<Eigen::Vector2d, 4> kTrapezoid{
    Eigen::Vector2d(0, 0), {2, 0}, {1.8, 1.2}, {0.3, 1.0}};

void expectSlopesInside(const AlphaBarResult& r, const AlphaBarOptions& o) {
  EXPECT_GE(r.slopeMin, o.slopeMin - 1e-5);
  EXPECT_LE(r.slopeMax, o.slopeMax + 1e-4);
  EXPECT_TRUE(r.claddingU.bijective());
  EXPECT_TRUE(r.claddingV.bijective());
}

TEST(AlphaBar, ParallelogramIsFeasibleOverTheWholeConvexRange) {
  // F is the identity at every alpha_bar != alpha and (2.2) holds everywhere but at alpha, so the
  // feasible range is the convex range: the planar quad collapses flat (Section 3.4.2).
  const auto maps = planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {2.6, 1.1}, {0.6, 1.1}}, 21);
  const auto r = solveAlphaBar(maps);
  ASSERT_TRUE(r.rangeFound);
  EXPECT_NEAR(r.alphaMin, r.convexRange.lo, 1e-7);
  EXPECT_NEAR(r.alphaMax, r.convexRange.hi, 1e-7);
  EXPECT_NEAR(r.alphaBar, r.alphaMin, 0.0);
  // The only gap is the single angle alpha, where (2.2) gives exactly 0: too thin for the scan.
  EXPECT_EQ(r.feasibleIntervals.size(), 1u);
  const auto atAlpha = evaluateAlphaBar(maps, maps.alphaSpatial, {});
  EXPECT_TRUE(atAlpha.bijective);
  EXPECT_FALSE(atAlpha.feasible);
  // Identity up to the O(h) slope error of the piecewise-linear intersection (h = 1/20).
  EXPECT_NEAR(r.slopeMin, 1.0, 0.3);
  EXPECT_NEAR(r.slopeMax, 1.0, 0.3);
}

TEST(AlphaBar, DevelopablePatchBoundsBracketTheUnrolledAngle) {
  // A cylinder/cone patch in its unrolled plane (a general convex quad).
  const auto maps = planarPatchMaps(kTrapezoid, 41);
  AlphaBarOptions options;
  const auto r = solveAlphaBar(maps, options);
  ASSERT_TRUE(r.rangeFound);
  EXPECT_LT(r.alphaMin, maps.alphaSpatial);
  EXPECT_GT(r.alphaMax, maps.alphaSpatial);
  expectSlopesInside(r, options);
  // Known answer of the bound: feasible just inside, infeasible just outside.
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMin + 1e-6, options).feasible);
  const auto outside = evaluateAlphaBar(maps, r.alphaMin - 1e-5, options);
  EXPECT_FALSE(outside.feasible);
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMax - 1e-6, options).feasible);
  EXPECT_FALSE(evaluateAlphaBar(maps, r.alphaMax + 1e-5, options).feasible);
  // At alpha_bar_min a slope bound (or the convex range) is active.
  const bool active = std::abs(r.slopeMin - options.slopeMin) < 1e-3 ||
                      std::abs(r.slopeMax - options.slopeMax) < 1e-2 ||
                      std::abs(r.alphaMin - r.convexRange.lo) < 1e-6;
  EXPECT_TRUE(active) << r.slopeMin << " " << r.slopeMax;
}

TEST(AlphaBar, UnrolledChoiceOnDevelopableIsDegenerateAndFinite) {
  const auto maps = planarPatchMaps(kTrapezoid, 41);
  AlphaBarOptions options;
  parseAlphaBarChoice("unrolled", options);
  const auto r = solveAlphaBar(maps, options);
  EXPECT_DOUBLE_EQ(r.alphaBar, maps.alphaSpatial);
  EXPECT_TRUE(r.degenerate);
  EXPECT_TRUE(std::isfinite(r.slopeMin) && std::isfinite(r.slopeMax));
  // The planar quad is the unrolled patch itself.
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR((r.quad.corners[k] - kTrapezoid[k]).norm(), 0.0, 1e-12) << k;
}

TEST(AlphaBar, SpherePatchHasAFeasibleRangeWithSlopesInsideBounds) {
  const auto maps = spherePatchMaps(testing::capCorners(0.5, {0.1, 1.7, 3.3, 4.8}), 5.0, 61);
  AlphaBarOptions options;
  const auto r = solveAlphaBar(maps, options);
  ASSERT_TRUE(r.rangeFound);
  EXPECT_LT(r.alphaMin, r.alphaMax);
  expectSlopesInside(r, options);
  EXPECT_FALSE(evaluateAlphaBar(maps, r.alphaMin - 1e-5, options).feasible);
  // Positive curvature: the maps barely meet near alpha, so the feasible set is two intervals
  // with alpha in the gap; each interval is feasible inside and infeasible just outside.
  ASSERT_EQ(r.feasibleIntervals.size(), 2u);
  EXPECT_DOUBLE_EQ(r.feasibleIntervals.front().lo, r.alphaMin);
  EXPECT_DOUBLE_EQ(r.feasibleIntervals.back().hi, r.alphaMax);
  EXPECT_LT(r.feasibleIntervals[0].hi, maps.alphaSpatial);
  EXPECT_GT(r.feasibleIntervals[1].lo, maps.alphaSpatial);
  EXPECT_FALSE(evaluateAlphaBar(maps, maps.alphaSpatial, options).feasible);
  for (const auto& interval : r.feasibleIntervals) {
    EXPECT_TRUE(evaluateAlphaBar(maps, 0.5 * (interval.lo + interval.hi), options).feasible);
    EXPECT_TRUE(evaluateAlphaBar(maps, interval.hi - 1e-6, options).feasible);
    if (interval.hi < r.convexRange.hi - 1e-6) {
      EXPECT_FALSE(evaluateAlphaBar(maps, interval.hi + 1e-5, options).feasible);
    }
  }
  options.choice = AlphaBarChoice::Max;
  const auto rmax = solveAlphaBar(maps, options);
  EXPECT_DOUBLE_EQ(rmax.alphaBar, rmax.alphaMax);
  expectSlopesInside(rmax, options);
}

TEST(AlphaBar, NarrowFeasibleIntervalBetweenScanSamplesIsFound) {
  // The feasible set is made narrow on purpose, between two samples of the uniform scan: on the
  // developable trapezoid the smallest slope of the cladding functions grows with alpha_bar (0.78
  // at the low end of the convex range, 0.96 near the top), so with k_min set to that slope at
  // a_star the slope constraint holds exactly for alpha_bar > a_star; and with f far above every
  // planar f_bar, (e - e_bar)(f - f_bar) < 0 holds exactly where e_bar(alpha_bar) > e, i.e. for
  // alpha_bar < a_star + w when e = e_bar(a_star + w). Feasible set: (a_star, a_star + w) with
  // w = 0.4 of the scan spacing, so no scan sample is feasible.
  auto maps = planarPatchMaps(kTrapezoid, 41);
  AlphaBarOptions options;
  const auto range = convexAlphaRange(maps.sides, 1e-9, options.minPlanarAngle);
  ASSERT_TRUE(range);
  const double spacing = (range->hi - range->lo) / (options.scanSamples - 1);
  const double aStar = range->lo + 20.3 * spacing, width = 0.4 * spacing;
  const double scale = 0.25 * (maps.sides[0] + maps.sides[1] + maps.sides[2] + maps.sides[3]);
  double kStar = 1e300;
  for (Family family : {Family::U, Family::V}) {
    const auto f = claddingFunction(
        maps.map(family), *planarQuad(maps.sides, aStar, options.minPlanarAngle), family, scale);
    for (double slope : segmentSlopes(f, options.cladding.infiniteSlopeFactor))
      kStar = std::min(kStar, slope);
  }
  ASSERT_GT(kStar, 0.85);
  ASSERT_LT(kStar, 0.93);
  options.slopeMin = kStar;
  maps.diagonalE = planarDiagonalE(*planarQuad(maps.sides, aStar + width, options.minPlanarAngle));
  maps.diagonalF = 100.0;
  // The uniform scan alone (the former method's seeds) sees no feasible angle at all.
  for (int k = 0; k < options.scanSamples; ++k)
    EXPECT_FALSE(evaluateAlphaBar(maps, range->lo + k * spacing, options).feasible) << k;

  const auto r = solveAlphaBar(maps, options);
  ASSERT_TRUE(r.rangeFound) << r.status;
  ASSERT_EQ(r.feasibleIntervals.size(), 1u) << r.status;
  // Known ends: a_star (slope bound, located to the solver's tolerance) and a_star + w (closed
  // form).
  EXPECT_NEAR(r.alphaMin, aStar, 1e-6);
  EXPECT_NEAR(r.alphaMax, aStar + width, 1e-7);
  EXPECT_DOUBLE_EQ(r.alphaBar, r.alphaMin);
  EXPECT_TRUE(evaluateAlphaBar(maps, aStar + 0.5 * width, options).feasible);
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMin, options).feasible);
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMax, options).feasible);
  EXPECT_FALSE(evaluateAlphaBar(maps, aStar - 1e-5, options).feasible);
  EXPECT_FALSE(evaluateAlphaBar(maps, aStar + width + 1e-5, options).feasible);
  EXPECT_NE(r.status.find("limited by slopes"), std::string::npos) << r.status;
}

TEST(AlphaBar, NarrowDipOfOneConstraintBetweenScanSamplesIsFoundByRefinement) {
  // One constraint alone dipping below zero between two scan samples: no sign change at the
  // samples, only the refinement can see it. On a kite (symmetric about c0c2, so F_u = F_v) the
  // smallest cladding slope has a smooth maximum over alpha_bar (0.9396826 near 1.405 rad); with
  // k_min 2e-6 below that maximum the slope constraint holds on a window about 0.024 rad wide, less
  // than half the scan spacing (0.059 rad) and clear of every scan sample.
  const auto maps = planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {2.6, 2.6}, {0, 2}}, 41);
  AlphaBarOptions options;
  const double scale = 0.25 * (maps.sides[0] + maps.sides[1] + maps.sides[2] + maps.sides[3]);
  double peak = -1.0, peakAngle = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double a = 1.30 + 0.25 * k / 2000;
    const auto f = claddingFunction(maps.u, *planarQuad(maps.sides, a, options.minPlanarAngle),
                                    Family::U, scale);
    const auto slopes = segmentSlopes(f, options.cladding.infiniteSlopeFactor);
    const double smallest = *std::min_element(slopes.begin(), slopes.end());
    if (smallest > peak) peak = smallest, peakAngle = a;
  }
  ASSERT_GT(peakAngle, 1.35);
  ASSERT_LT(peakAngle, 1.5);
  options.slopeMin = peak - 2e-6;
  const auto range = convexAlphaRange(maps.sides, 1e-9, options.minPlanarAngle);
  const double spacing = (range->hi - range->lo) / (options.scanSamples - 1);
  for (int k = 0; k < options.scanSamples; ++k)
    EXPECT_FALSE(evaluateAlphaBar(maps, range->lo + k * spacing, options).feasible) << k;
  EXPECT_TRUE(evaluateAlphaBar(maps, peakAngle, options).feasible);

  const auto r = solveAlphaBar(maps, options);
  ASSERT_TRUE(r.rangeFound) << r.status;
  ASSERT_EQ(r.feasibleIntervals.size(), 1u) << r.status;
  EXPECT_LT(r.alphaMin, peakAngle);
  EXPECT_GT(r.alphaMax, peakAngle);
  EXPECT_LT(r.alphaMax - r.alphaMin, 0.5 * spacing);
  EXPECT_GT(r.alphaMax - r.alphaMin, 0.01);
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMin, options).feasible);
  EXPECT_TRUE(evaluateAlphaBar(maps, r.alphaMax, options).feasible);
  EXPECT_FALSE(evaluateAlphaBar(maps, r.alphaMin - 1e-5, options).feasible);
  EXPECT_FALSE(evaluateAlphaBar(maps, r.alphaMax + 1e-5, options).feasible);
  EXPECT_NE(r.status.find("added by refinement"), std::string::npos);
}

TEST(AlphaBar, NoFeasibleAngleThrowsInfeasiblePatch) {
  // Both surface diagonals longer than any planar diagonal: (e - e_bar)(f - f_bar) > 0 everywhere.
  auto maps = planarPatchMaps(kTrapezoid, 21);
  const double lift = 3.0;
  for (DistanceMap* m : {&maps.u, &maps.v})
    for (int i = 0; i < m->n1; ++i)
      for (int j = 0; j < m->n2; ++j) {
        const double x1 = double(i) / (m->n1 - 1), x2 = double(j) / (m->n2 - 1);
        m->at(i, j) += lift * (x1 * (1 - x2) + x2 * (1 - x1));
      }
  maps.diagonalE += lift;
  maps.diagonalF += lift;
  EXPECT_THROW(solveAlphaBar(maps), InfeasiblePatch);
}

TEST(AlphaBar, GivenAngleOutsideConvexRangeIsInfeasible) {
  const auto maps = planarPatchMaps(kTrapezoid, 21);
  AlphaBarOptions options;
  parseAlphaBarChoice("0.05", options);
  EXPECT_EQ(options.choice, AlphaBarChoice::Given);
  EXPECT_THROW(solveAlphaBar(maps, options), InfeasiblePatch);
}

TEST(AlphaBar, ParseRejectsNonsense) {
  AlphaBarOptions options;
  EXPECT_THROW(parseAlphaBarChoice("minimum", options), InvalidInput);
  EXPECT_THROW(parseAlphaBarChoice("4.0", options), InvalidInput);
  EXPECT_THROW(parseAlphaBarChoice("1.2x", options), InvalidInput);
  parseAlphaBarChoice("max", options);
  EXPECT_EQ(options.choice, AlphaBarChoice::Max);
  options.slopeMax = 0.05;
  EXPECT_THROW(options.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg
