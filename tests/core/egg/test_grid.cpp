#include "core/egg/grid.hpp"

#include "core/egg/solve_patch.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TEST(Grid, SegmentIntersection) {
  double t = 0, s = 0;
  ASSERT_TRUE(intersectSegments({0, 0}, {2, 0}, {0.5, -1}, {0.5, 1}, t, s));
  EXPECT_NEAR(t, 0.25, 1e-15);
  EXPECT_NEAR(s, 0.5, 1e-15);
  EXPECT_FALSE(intersectSegments({0, 0}, {1, 0}, {0, 1}, {1, 1}, t, s));   // parallel
  EXPECT_FALSE(intersectSegments({0, 0}, {1, 0}, {2, -1}, {2, 1}, t, s));  // misses
}

TEST(Grid, PlanePatchGridIsExactAndNotchFree) {
  // A flat patch at alpha_bar = alpha: members are straight lines, the planar grid is the patch
  // itself moved rigidly, connections agree and every normal is +z.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  EggOptions options;
  options.maps.resolution = 21;
  options.members.count = 4;
  parseAlphaBarChoice("unrolled", options.alphaBar);
  const auto r =
      solveEgg(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3.4, 3, 0}, {-3, 3, 0}}, options);
  ASSERT_EQ(r.grid.u.size(), 4u);
  ASSERT_EQ(r.grid.v.size(), 4u);
  ASSERT_EQ(r.grid.connections.size(), 16u);
  EXPECT_LT(r.grid.maxNotch, 1e-9);
  EXPECT_LT(r.grid.maxLengthMismatch, 1e-9);
  for (const auto& c : r.grid.connections) {
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
    // Planar coordinates are the spatial ones relative to c0 (c0c1 is along +x already).
    EXPECT_NEAR((c.planar - (c.spatial - Eigen::Vector3d(-3, -3, 0)).head<2>()).norm(), 0.0, 1e-9);
  }
  for (const auto* family : {&r.grid.u, &r.grid.v})
    for (const auto& m : *family) {
      ASSERT_EQ(m.normals.size(), m.spatial.size());
      EXPECT_NEAR((m.spatial.back() - m.spatial.front()).norm(), m.spatialLength,
                  1e-9);  // straight
    }
  EXPECT_EQ(r.grid.anchors.size(), 4u);  // straight sides: only the corners
  EXPECT_EQ(countNotches(r.grid), 0);
}

TEST(Grid, CountNotchesCountsBothMembersAboveTheThreshold) {
  EggGrid grid;
  grid.connections.resize(3);
  grid.connections[0].notchU = 0.01;
  grid.connections[0].notchV = -0.02;
  grid.connections[1].notchU = 5e-5;
  grid.connections[2].notchV = -0.2;
  EXPECT_EQ(countNotches(grid, 1e-4), 3);
  EXPECT_EQ(countNotches(grid, 0.05), 1);
}

}  // namespace
}  // namespace egg
