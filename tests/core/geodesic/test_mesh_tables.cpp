// The propagation's per-mesh tables (mesh_tables.cpp): each halfedge's unfolded face against the
// 3D triangle, and the per-vertex saddle classification with its shadow cones.
#include "core/geodesic/window_propagation.hpp"

#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace egg::geodesic::detail {
namespace {

TEST(MeshTables, EachHalfedgeFrameUnfoldsItsTriangleWithTheEdgeLengths) {
  const TriMesh mesh = testing::gridMesh(12, 9, 2.0, 1.5, testing::bump(1.0, 0.75, 0.4, 0.5), 0.2);
  const MeshTables t = buildTables(mesh, DistanceSolverOptions{});
  int faces = 0;
  for (int h = 0; h < t.halfedgeCount; ++h) {
    const auto& e = t.he[h];
    const Eigen::Vector3d a = t.positions[e.fromVertex], b = t.positions[e.toVertex];
    EXPECT_NEAR(e.length, (b - a).norm(), 1e-14) << h;
    EXPECT_EQ(t.he[t.twin(h)].fromVertex, e.toVertex) << h;
    if (e.face < 0) {
      EXPECT_EQ(e.oppositeVertex, -1) << h;
      continue;
    }
    ++faces;
    // The opposite vertex C at (oppositeX, oppositeY): |A C| and |B C| as in 3D, on the y > 0 side.
    const Eigen::Vector3d c = t.positions[e.oppositeVertex];
    EXPECT_NEAR(std::hypot(e.oppositeX, e.oppositeY), (c - a).norm(), 1e-12) << h;
    EXPECT_NEAR(std::hypot(e.length - e.oppositeX, e.oppositeY), (c - b).norm(), 1e-12) << h;
    EXPECT_GT(e.oppositeY, 0.0) << h;
    EXPECT_EQ(t.he[t.he[e.next].next].next, h) << h;
    EXPECT_EQ(t.he[e.next].fromVertex, e.toVertex) << h;
    EXPECT_EQ(t.he[e.prev].toVertex, e.fromVertex) << h;
  }
  EXPECT_EQ(faces, 3 * t.faceCount);
}

TEST(MeshTables, ShadowConesOnlyAtSkippedSaddlesAndTheirFlagsAgree) {
  // A bump's flank has saddles; by default the near-flat ones are skipped (a cone, not a
  // pseudo-source), in exact mode none is.
  const TriMesh mesh = testing::gridMesh(30, 30, 3.0, 3.0, testing::bump(1.5, 1.5, 0.5, 0.6), 0.25);
  for (const double tolerance : {0.0, DistanceSolverOptions{}.saddleAngleTolerance}) {
    DistanceSolverOptions options;
    options.saddleAngleTolerance = tolerance;
    const MeshTables t = buildTables(mesh, options);
    int cones = 0, saddles = 0;
    for (int v = 0; v < t.vertexCount; ++v) {
      EXPECT_EQ(t.hasShadowCone[v] != 0, t.shadowCone[v] > 0.0)
          << v;  // the byte the hot loop reads
      if (t.shadowCone[v] > 0.0) {
        ++cones;
        const double excess = t.angleSum[v] - 2.0 * std::numbers::pi;
        EXPECT_FALSE(t.pseudoSource[v]) << v;
        EXPECT_FALSE(t.boundaryVertex[v]) << v;
        EXPECT_GT(excess, 0.0) << v;
        EXPECT_LE(excess, tolerance) << v;
        EXPECT_DOUBLE_EQ(t.shadowCone[v], excess + tolerance) << v;
      }
      if (!t.boundaryVertex[v] && t.angleSum[v] > 2.0 * std::numbers::pi) ++saddles;
    }
    EXPECT_GT(saddles, 0);
    if (tolerance == 0.0)
      EXPECT_EQ(cones, 0);
    else
      EXPECT_GT(cones, 0);
  }
}

}  // namespace
}  // namespace egg::geodesic::detail
