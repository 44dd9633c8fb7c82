// The goal-directed propagation (goal_bound.hpp): the chord bound is a true lower bound of the
// distance to the nearest target over a window's interval, and a propagation directed at a target
// gives the full field's distance there while creating far fewer windows.
#include "core/geodesic/goal_bound.hpp"
#include "core/geodesic/window_propagation.hpp"

#include "samples/generators/samples.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace egg::geodesic::detail {
namespace {

TEST(GoalBound, SegmentBoundIsTheClosestPointOfTheSubSegment) {
  GoalBound goal;
  goal.targets = {{0.0, 2.0, 0.0}, {5.0, -1.0, 1.0}};
  const Eigen::Vector3d a(0, 0, 0), b(4, 0, 0);
  // Sub-segment [1, 3] on the x axis: nearest to the first target at x = 1 (distance sqrt(5)),
  // to the second at x = 3 (distance sqrt(6)).
  EXPECT_NEAR(goal.toSegment(a, b, 0.25, 0.75), std::sqrt(5.0), 1e-15);
  // Whole segment: the second target is sqrt(3) from its end x = 4 (the first 2 from x = 0).
  EXPECT_NEAR(goal.toSegment(a, b, 0.0, 1.0), std::sqrt(3.0), 1e-15);
  // Never above the bound at any point of the sub-segment (sampled), and attained at one.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    double f0 = u(rng), f1 = u(rng);
    if (f0 > f1) std::swap(f0, f1);
    const double bound = goal.toSegment(a, b, f0, f1);
    double smallest = 1e300;
    for (int i = 0; i <= 1000; ++i) {
      const double f = f0 + (f1 - f0) * i / 1000.0;
      const double h = goal.toPoint(a + f * (b - a));
      EXPECT_LE(bound, h + 1e-12);
      smallest = std::min(smallest, h);
    }
    EXPECT_NEAR(bound, smallest, 1e-5);
  }
  EXPECT_EQ(GoalBound{}.toPoint(a), 0.0);  // no targets: a plain field
}

// Windows of a full field and of one directed at a far point, and their distances there.
TEST(GoalBound, DirectedPropagationSweepsLessForTheSameDistance) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.15);
  for (const double tolerance : {0.0, 7e-4}) {
    DistanceSolverOptions options;
    options.saddleAngleTolerance = tolerance;
    const MeshTables tables = buildTables(mesh, options);
    const SurfacePoint from = snapToSurface(mesh, {-3.0, -2.5, 0.0}),
                       to = snapToSurface(mesh, {3.0, 2.0, 0.0});
    Propagation full, directed;
    propagate(tables, options, from, {to}, full, false);
    propagate(tables, options, from, {to}, directed, true);
    EXPECT_NEAR(directed.targetDistance[0], full.targetDistance[0], 1e-12 * full.targetDistance[0])
        << tolerance;
    // Nearly corner to corner across an 8 m bump: the ellipse of the chord bound is a sliver of it.
    // Measured 0.061 (exact) / 0.070 (default) of the full field's windows.
    EXPECT_LT(directed.windows.size(), 0.2 * full.windows.size()) << tolerance;
    RecordProperty(
        tolerance == 0.0 ? "window_ratio_exact" : "window_ratio_default",
        std::to_string(static_cast<double>(directed.windows.size()) / full.windows.size()));
  }
}

}  // namespace
}  // namespace egg::geodesic::detail
