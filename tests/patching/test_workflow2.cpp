#include "patching/workflow2.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "patching/layout.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace egg::patching {
namespace {

TEST(Workflow2, APlaneGetsOnePatchPerMaxSizeCell) {
  // 12 x 6 m, cells no larger than 5 m across: the 12 m direction needs 3 cells, the 6 m one 2
  // (a 4 x 3 m cell is 5 m across), so 3 x 2 = 6 patches covering the plane exactly.
  const TriMesh plane = samples::generateSample("plane", {{"length", 12}, {"width", 6}}, 0.5);
  Workflow2Options options;
  options.maxPatchSizeM = 5.0;
  const Workflow2Layout layout = proposeLayout(plane, options);
  EXPECT_EQ(layout.blocks, 1);
  EXPECT_EQ(layout.holes, 0);
  ASSERT_EQ(layout.quads.size(), 6u);
  EXPECT_EQ(layout.corners.size(), 12u);  // a 4 x 3 grid of corners
  for (const auto& q : layout.quads) {
    // Counter-clockwise seen from above, and within the size.
    const auto& a = layout.corners[q[0]];
    const auto& b = layout.corners[q[1]];
    const auto& c = layout.corners[q[2]];
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);
    EXPECT_LE((c - a).norm(), 5.0 + 1e-9);
    EXPECT_LE((layout.corners[q[3]] - b).norm(), 5.0 + 1e-9);
  }
  // The outer corners are the plane's corners.
  double minX = 1e9, maxX = -1e9;
  for (const auto& c : layout.corners) minX = std::min(minX, c.x()), maxX = std::max(maxX, c.x());
  EXPECT_NEAR(maxX - minX, 12.0, 1e-9);
}

TEST(Workflow2, AHoleIsNeverInsideAPatch) {
  // The Great Court: a rectangle with the Reading Room cut out. Every patch is cut without error
  // (a hole inside a patch, or a side wrapping round it, would throw) and none holds the hole's centre.
  const TriMesh surface = samples::generateSample("great_court", {}, 2.0);
  Workflow2Options options;
  options.maxPatchSizeM = 80.0;
  const Workflow2Layout proposal = proposeLayout(surface, options);
  EXPECT_EQ(proposal.holes, 1);
  EXPECT_EQ(proposal.blocks, 4);
  EXPECT_EQ(proposal.quads.size(), 4u);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout = makeLayout(surface, solver, proposal.corners, proposal.quads);
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    const LayoutPatch cut = cutLayoutPatch(layout, static_cast<int>(p));
    for (auto vh : cut.patch.mesh.vertices()) {
      const Eigen::Vector3d x = toEigen(cut.patch.mesh.point(vh));
      EXPECT_GT(std::hypot(x.x(), x.y()), 22.245 - 1e-6) << "patch " << p;  // outside the Reading Room
    }
  }
}

TEST(Workflow2, ACornerMovesOntoAPeak) {
  // A bump off the centre of a 3 x 3 grid of 2 m cells: the interior grid node nearest to it moves
  // onto p_max (Algorithm 2: a corner at p_max).
  const TriMesh bump = samples::generateSample("bump", {{"length", 6}, {"width", 6}, {"height", 0.8}, {"sigma", 0.8}}, 0.2);
  Workflow2Options options;
  options.maxPatchSizeM = 2.9;  // 3 x 3 cells of 2 x 2 m
  const Workflow2Layout layout = proposeLayout(bump, options);
  EXPECT_EQ(layout.quads.size(), 9u);
  // The bump is centred: no interior node of a 3 x 3 grid is near it, none moves.
  EXPECT_EQ(layout.peaksSnapped, 0);
  options.maxPatchSizeM = 4.4;  // 2 x 2 cells (4.32 m across in space): the centre node is a grid node at the peak
  const Workflow2Layout two = proposeLayout(bump, options);
  EXPECT_EQ(two.quads.size(), 4u);
  EXPECT_EQ(two.peaksSnapped, 1);
  double nearest = 1e9;
  for (const auto& c : two.corners) nearest = std::min(nearest, c.head<2>().norm());
  EXPECT_LT(nearest, 0.25);
}

TEST(Workflow2, TheSameLayoutOnAnyThreadCount) {
  const TriMesh surface = samples::generateSample("great_court", {}, 2.0);
  Workflow2Options options;
  options.maxPatchSizeM = 50.0;
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return proposeLayout(surface, options);
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.corners.size(), two.corners.size());
  for (size_t i = 0; i < one.corners.size(); ++i) EXPECT_EQ(one.corners[i], two.corners[i]);
  EXPECT_EQ(one.quads, two.quads);
  EXPECT_GT(one.quads.size(), 4u);  // 50 m cells: the ring's blocks are subdivided
}

TEST(Workflow2, BadInputIsNamed) {
  const TriMesh plane = samples::generateSample("plane", {{"length", 4}, {"width", 4}}, 0.5);
  Workflow2Options options;
  options.maxPatchSizeM = -1.0;
  EXPECT_THROW(proposeLayout(plane, options), InvalidInput);
}

}  // namespace
}  // namespace egg::patching
