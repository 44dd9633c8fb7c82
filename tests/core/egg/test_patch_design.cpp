#include "core/egg/patch_design.hpp"

#include "core/egg/solve_patch.hpp"
#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

// The bump patches of test_solve_patch.cpp: a 6 m quad over a Gaussian bump (sigma 1.5 m).
const std::array<Eigen::Vector3d, 4> kBumpCorners{
    Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}};

TriMesh bumpMesh(double height) {
  return samples::generateSample(
      "bump", {{"height", height}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.35);
}

EggOptions fastOptions() {
  EggOptions options;
  options.maps.resolution = 41;
  options.members.lamellaWidthM = 0.1;
  options.members.spacingFactor = 6.0;
  return options;
}

PatchDesign designBump(double height, const EggOptions& options,
                       const std::array<Eigen::Vector3d, 4>& corners = kBumpCorners) {
  return designPatch(makePatch(bumpMesh(height), corners, options.patch), options);
}

void expectSameMembers(const FamilyMembers& a, const FamilyMembers& b) {
  EXPECT_EQ(a.x1, b.x1);
  EXPECT_EQ(a.x2, b.x2);
  EXPECT_EQ(a.lengths, b.lengths);
  EXPECT_EQ(a.origin, b.origin);
}

TEST(PatchDesign, DesignThenGridEqualsSolveEggBitForBit) {
  const EggOptions options = fastOptions();
  const TriMesh mesh = bumpMesh(1.0);
  const EggResult whole = solveEgg(mesh, kBumpCorners, options);
  const PatchDesign design = designPatch(makePatch(mesh, kBumpCorners, options.patch), options);
  ASSERT_TRUE(design.feasible) << design.failure.message;
  EXPECT_EQ(design.maps.u.values, whole.maps.u.values);
  EXPECT_EQ(design.maps.v.values, whole.maps.v.values);
  EXPECT_EQ(design.alphaBar.alphaBar, whole.alphaBar.alphaBar);
  EXPECT_EQ(design.uniqueness.etaU, whole.uniqueness.etaU);
  EXPECT_EQ(design.uniqueness.etaV, whole.uniqueness.etaV);
  const FamilyMembers u = placeDesignMembers(design, Family::U, options.members);
  const FamilyMembers v = placeDesignMembers(design, Family::V, options.members);
  expectSameMembers(u, whole.membersU);
  expectSameMembers(v, whole.membersV);
  const EggGrid grid = traceDesignGrid(design, u, v, options.grid);
  ASSERT_EQ(grid.connections.size(), whole.grid.connections.size());
  for (size_t k = 0; k < grid.connections.size(); ++k) {
    const auto &a = grid.connections[k], &b = whole.grid.connections[k];
    EXPECT_EQ(a.spatial, b.spatial) << k;
    EXPECT_EQ(a.planar, b.planar) << k;
    EXPECT_EQ(a.notchU, b.notchU) << k;
    EXPECT_EQ(a.notchV, b.notchV) << k;
  }
  EXPECT_EQ(grid.maxNotch, whole.grid.maxNotch);
  EXPECT_EQ(grid.maxLengthMismatch, whole.grid.maxLengthMismatch);
  EXPECT_EQ(design.propagations + design.patch.propagations + grid.propagations,
            whole.propagations);
}

TEST(PatchDesign, MembersAtGivenCoordinatesFollowFAndMeetCriterionOne) {
  const EggOptions options = fastOptions();
  const PatchDesign design = designBump(1.0, options);
  ASSERT_TRUE(design.feasible) << design.failure.message;
  const std::vector<double> x1{0.0, 0.15, 0.4, 0.5, 0.72, 0.9, 1.0};
  const FamilyMembers u = membersAt(design, Family::U, x1);
  const FamilyMembers v = membersAt(design, Family::V, x1);
  for (const FamilyMembers* m : {&u, &v}) {
    ASSERT_EQ(m->x1, x1);
    EXPECT_EQ(m->x2.front(), 0.0);
    EXPECT_EQ(m->x2.back(), 1.0);
    EXPECT_EQ(m->origin.front(), MemberOrigin::Boundary);
    EXPECT_EQ(m->origin[1], MemberOrigin::Given);
    for (size_t k = 1; k + 1 < x1.size(); ++k) {
      EXPECT_EQ(m->x2[k], claddingValue(design, m->family, x1[k]));
      EXPECT_GT(m->lengths[k], 0.0);
    }
  }
  const EggGrid grid = traceDesignGrid(design, u, v, options.grid);
  ASSERT_EQ(grid.u.size(), x1.size());
  ASSERT_EQ(grid.v.size(), x1.size());
  EXPECT_LE(grid.maxLengthMismatch, 1e-9);  // criterion (i), as in test_solve_patch.cpp
  for (const auto* family : {&grid.u, &grid.v})
    for (size_t k = 0; k < x1.size(); ++k) {
      const GridMember& m = (*family)[k];
      EXPECT_EQ(m.x1, x1[k]);
      EXPECT_NEAR(m.spatialLength, m.planarLength, 1e-9 * m.planarLength) << k;
      // Tracing refines x2 to criterion (i) on the fine patch; F (from the maps) is its guess.
      EXPECT_NEAR(m.x2, claddingValue(design, m.family, x1[k]), 2e-3) << k;
    }
  EXPECT_GT(grid.maxNotch, 1e-3);  // a doubly curved patch has notches
  EXPECT_THROW(membersAt(design, Family::U, {0.0, 0.5, 0.5, 1.0}), InvalidInput);
  EXPECT_THROW(membersAt(design, Family::U, {0.1, 0.5, 1.0}), InvalidInput);
  EXPECT_THROW(traceDesignGrid(design, v, u, options.grid), InvalidInput);
}

TEST(PatchDesign, CladdingSlopeIsTheDerivativeOfTheCladdingValue) {
  const EggOptions options = fastOptions();
  const PatchDesign design = designBump(1.0, options);
  ASSERT_TRUE(design.feasible) << design.failure.message;
  for (Family family : {Family::U, Family::V}) {
    const auto& points =
        (family == Family::U ? design.alphaBar.claddingU : design.alphaBar.claddingV).points;
    ASSERT_GT(points.size(), 10u);
    const double h = 1e-7;
    int checked = 0;
    for (int k = 1; k < 200; ++k) {
      const double x = k / 200.0;
      bool nearKink = false;
      for (const auto& p : points) nearKink = nearKink || std::abs(p.x() - x) < 2 * h;
      if (nearKink) continue;
      const double fd =
          (claddingValue(design, family, x + h) - claddingValue(design, family, x - h)) / (2 * h);
      EXPECT_NEAR(claddingSlope(design, family, x), fd, 1e-6 * std::max(1.0, std::abs(fd))) << x;
      EXPECT_NEAR(claddingInverse(design, family, claddingValue(design, family, x)), x, 1e-12) << x;
      ++checked;
    }
    EXPECT_GT(checked, 150);
    // At a kink the slope is the next segment's (right-continuous); at x1 = 1 the last one's.
    const size_t k = points.size() / 2;
    const Eigen::Vector2d next = points[k + 1] - points[k];
    EXPECT_DOUBLE_EQ(claddingSlope(design, family, points[k].x()), next.y() / next.x());
    const Eigen::Vector2d last = points.back() - points[points.size() - 2];
    EXPECT_DOUBLE_EQ(claddingSlope(design, family, 1.0), last.y() / last.x());
    // Slopes inside (k_min, k_max) at a feasible alpha_bar (Problem 2.3).
    EXPECT_GT(claddingSlope(design, family, 0.5), options.alphaBar.slopeMin);
    EXPECT_LT(claddingSlope(design, family, 0.5), options.alphaBar.slopeMax);
  }
}

TEST(PatchDesign, CladdingAtTheChosenAngleIsTheDesignsAndMovesWithTheAngle) {
  const EggOptions options = fastOptions();
  const PatchDesign design = designBump(1.0, options);
  ASSERT_TRUE(design.feasible) << design.failure.message;
  const CladdingFunction u = claddingAt(design, Family::U, design.alphaBar.alphaBar);
  EXPECT_EQ(u.points, design.alphaBar.claddingU.points);
  EXPECT_EQ(u.lengths, design.alphaBar.claddingU.lengths);
  EXPECT_EQ(claddingAt(design, Family::V, design.alphaBar.alphaBar).points,
            design.alphaBar.claddingV.points);
  // Inside the feasible set, F stays bijective and moves with alpha_bar.
  const AngleInterval first = design.alphaBar.feasibleIntervals.front();
  const double inside = first.lo + 0.5 * (first.hi - first.lo);
  const CladdingFunction moved = claddingAt(design, Family::U, inside);
  EXPECT_TRUE(moved.bijective());
  EXPECT_NE(moved.evaluate(0.3), u.evaluate(0.3));
  EXPECT_LT(slopeViolation(moved, options.alphaBar.slopeMin, options.alphaBar.slopeMax), 0.0);
  EXPECT_GT(claddingSlope(moved, 0.3), 0.0);
  EXPECT_THROW(claddingAt(design, Family::U, 1e-3), InvalidInput);  // no convex quad that flat
}

TEST(PatchDesign, TallBumpWithoutSmoothingReportsAnEtaFailureAtThePeak) {
  EggOptions options = fastOptions();
  options.uniqueness.smooth = false;
  const PatchDesign design = designBump(2.0, options);
  ASSERT_FALSE(design.feasible);
  EXPECT_EQ(design.failure.kind, DesignFailureKind::Eta);
  // Symmetric bump in a symmetric quad: both families fail.
  EXPECT_TRUE(design.failure.familyU);
  EXPECT_TRUE(design.failure.familyV);
  EXPECT_LT((design.failure.peak - Eigen::Vector3d(0, 0, 2)).norm(), 0.3)
      << design.failure.peak.transpose();
  EXPECT_EQ(design.uniqueness.smoothingRounds, 0);
  EXPECT_THROW(requireFeasible(design), InfeasiblePatch);
  EXPECT_THROW(claddingValue(design, Family::U, 0.5), InvalidInput);
  // solveEgg throws the same message.
  try {
    solveEgg(bumpMesh(2.0), kBumpCorners, options);
    ADD_FAILURE() << "the tall bump passed without smoothing";
  } catch (const InfeasiblePatch& e) {
    EXPECT_EQ(std::string(e.what()), design.failure.message);
  }
}

TEST(PatchDesign, NarrowPatchOverATallBumpFailsEtaInTheLongFamilyOnly) {
  // u members run c0c3 -> c1c2 (along x, 6 m over the bump), v members along y (2 m, off-peak
  // height changes are gentle): only u leaves a gap at the peak.
  EggOptions options = fastOptions();
  options.uniqueness.smooth = false;
  const PatchDesign design =
      designBump(2.0, options, {Eigen::Vector3d(-3, -1, 0), {3, -1, 0}, {3, 1, 0}, {-3, 1, 0}});
  ASSERT_FALSE(design.feasible);
  EXPECT_EQ(design.failure.kind, DesignFailureKind::Eta);
  EXPECT_TRUE(design.failure.familyU) << design.uniqueness.etaU;
  EXPECT_FALSE(design.failure.familyV) << design.uniqueness.etaV;
  EXPECT_LT(design.failure.peak.head<2>().norm(), 0.3) << design.failure.peak.transpose();
}

TEST(PatchDesign, SlopeBoundsNoAlphaBarMeetsReportASlopeFailure) {
  // k_min, k_max so tight around 1 that F of the curved patch cannot keep its slopes inside at
  // any alpha_bar (Problem 2.3 infeasible): kind Slopes, the strongest K peak (the bump top).
  EggOptions options = fastOptions();
  options.alphaBar.slopeMin = 0.98;
  options.alphaBar.slopeMax = 1.02;
  const PatchDesign design = designBump(1.0, options);
  ASSERT_FALSE(design.feasible);
  EXPECT_EQ(design.failure.kind, DesignFailureKind::Slopes);
  EXPECT_TRUE(design.failure.familyU || design.failure.familyV);
  EXPECT_LT((design.failure.peak - Eigen::Vector3d(0, 0, 1)).norm(), 0.3)
      << design.failure.peak.transpose();
  try {
    solveEgg(bumpMesh(1.0), kBumpCorners, options);
    ADD_FAILURE() << "no feasible alpha_bar, yet solveEgg returned";
  } catch (const InfeasiblePatch& e) {
    EXPECT_EQ(std::string(e.what()), design.failure.message);
    EXPECT_NE(design.failure.message.find("no feasible alpha_bar"), std::string::npos) << e.what();
  }
}

TEST(PatchDesign, NarrowPatchWithTightSlopeBoundsFailsTheSlopesOfOneFamily) {
  // 6 m x 2.4 m over the 1 m bump, slopes in (0.8, 1.25): F_v leaves the bounds at every alpha_bar
  // of the convex range, F_u does not (measured: F_u's violation is negative at the best sample),
  // so Workflow 1 would split this patch by one new side, not by a corner.
  EggOptions options = fastOptions();
  options.alphaBar.slopeMin = 0.8;
  options.alphaBar.slopeMax = 1.25;
  const PatchDesign design = designBump(
      1.0, options, {Eigen::Vector3d(-3, -1.2, 0), {3, -1.2, 0}, {3, 1.2, 0}, {-3, 1.2, 0}});
  ASSERT_FALSE(design.feasible);
  EXPECT_EQ(design.failure.kind, DesignFailureKind::Slopes);
  EXPECT_FALSE(design.failure.familyU);
  EXPECT_TRUE(design.failure.familyV);
  EXPECT_LT(design.failure.peak.head<2>().norm(), 0.3) << design.failure.peak.transpose();
  // The flags agree with the constraints over the whole convex range.
  const auto range = convexAlphaRange(design.maps.sides, 1e-9, options.alphaBar.minPlanarAngle);
  ASSERT_TRUE(range);
  double leastU = 1e300, leastV = 1e300;
  for (int k = 0; k <= 60; ++k) {
    const auto e = evaluateAlphaBar(design.maps, range->lo + (range->hi - range->lo) * k / 60,
                                    options.alphaBar);
    if (!e.closable) continue;
    leastU = std::min(leastU, e.violationU);
    leastV = std::min(leastV, e.violationV);
  }
  EXPECT_LT(leastU, 0.0);
  EXPECT_GT(leastV, 0.0);
}

}  // namespace
}  // namespace egg
