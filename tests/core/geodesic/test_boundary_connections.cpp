// Non-convex boundaries (Section 4.5.3): on a flat L-shaped domain the shortest connections that
// are blocked by the notch run around its reflex corner; on a square there are none.
#include "core/geodesic/boundary_connections.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace egg::geodesic {
namespace {

// [0,2]^2, minus (1,2]x(1,2] when `notch`.
TriMesh squareDomain(int n, bool notch) {
  return testing::squareDomainMesh(n, testing::flat, notch);
}

struct LoopData {
  std::vector<int> vertices;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> arc;
  double length = 0.0;
  Eigen::MatrixXd distances;
};

LoopData loopData(const TriMesh& mesh) {
  LoopData data;
  const auto loops = boundaryLoops(mesh);
  EXPECT_EQ(loops.size(), 1u);
  data.vertices = loops.at(0);
  const int n = static_cast<int>(data.vertices.size());
  for (int v : data.vertices) data.points.push_back(toEigen(mesh.point(TriMesh::VertexHandle(v))));
  for (int i = 0; i < n; ++i) {
    data.arc.push_back(data.length);
    data.length += (data.points[(i + 1) % n] - data.points[i]).norm();
  }
  const DistanceSolver solver(mesh);
  std::vector<SurfacePoint> sources;
  for (int v : data.vertices) sources.push_back(vertexPoint(mesh, v));
  const auto fields = solver.distances(sources);
  data.distances.resize(n, n);
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) data.distances(x, y) = fields[x].vertexDistances[data.vertices[y]];
  }
  return data;
}

TEST(BoundaryConnections, SquareHasNone) {
  const TriMesh mesh = squareDomain(4, false);
  const LoopData data = loopData(mesh);
  const auto bends = boundaryBendsInward(mesh, data.vertices);
  for (char b : bends) EXPECT_EQ(b, 0);
  const auto result = findBoundaryConnections(data.distances, data.arc, data.length, bends);
  EXPECT_TRUE(result.nonConvexSegments.empty());
  EXPECT_EQ(result.invalid.count(), 0);
  // Eq. (4.6) without geometry flags the straight sides (their connections are geodesics, though).
  const auto literal = findBoundaryConnections(data.distances, data.arc, data.length);
  EXPECT_GT(literal.alongBoundary.count(), 0);
}

TEST(BoundaryConnections, NotchCornerMakesBlockedConnectionsInvalid) {
  const TriMesh mesh = squareDomain(5, true);
  const LoopData data = loopData(mesh);
  const int n = static_cast<int>(data.vertices.size());
  const auto bends = boundaryBendsInward(mesh, data.vertices);
  int reflex = -1;
  for (int i = 0; i < n; ++i) {
    if (bends[i]) {
      EXPECT_EQ(reflex, -1) << "only the notch corner bends inwards";
      reflex = i;
    }
  }
  ASSERT_GE(reflex, 0);
  EXPECT_LT((data.points[reflex] - Eigen::Vector3d(1, 1, 0)).norm(), 1e-15);
  const auto result = findBoundaryConnections(data.distances, data.arc, data.length, bends);
  ASSERT_EQ(result.nonConvexSegments.size(), 1u);
  const auto [first, last] = result.nonConvexSegments[0];
  // The segment runs over the corner: from the notch's side x = 1 to its side y = 1.
  bool containsCorner = false;
  for (int i = first;; i = (i + 1) % n) {
    containsCorner = containsCorner || i == reflex;
    if (i == last) break;
  }
  EXPECT_TRUE(containsCorner);
  // Known answer: a connection is blocked iff the straight segment enters the removed square.
  int blocked = 0, blockedFlagged = 0, clearFlagged = 0;
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      if (x == y) continue;
      const Eigen::Vector3d a = data.points[x], b = data.points[y];
      bool hidden = false;
      double cornerDistance = 1e9;
      for (int k = 0; k <= 400; ++k) {
        const Eigen::Vector3d p = a + (b - a) * (k / 400.0);
        hidden = hidden || (p.x() > 1.0 + 1e-9 && p.y() > 1.0 + 1e-9);
        cornerDistance = std::min(cornerDistance, (p - Eigen::Vector3d(1, 1, 0)).norm());
      }
      if (hidden) {
        ++blocked;
        blockedFlagged += result.invalid(x, y);
      } else if (cornerDistance > 0.05) {
        clearFlagged += result.invalid(x, y);
      }
    }
  }
  EXPECT_GT(blocked, 50);
  EXPECT_GE(blockedFlagged, 0.95 * blocked) << blockedFlagged << " of " << blocked;
  EXPECT_EQ(clearFlagged, 0);
}

TEST(BoundaryConnections, RejectsBadInput) {
  const Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_THROW(findBoundaryConnections(d, {0.0, 1.0}, 3.0), InvalidInput);
  EXPECT_THROW(findBoundaryConnections(d, {0.0, 2.0, 1.0}, 3.0), InvalidInput);
  EXPECT_THROW(findBoundaryConnections(d, {0.0, 1.0, 2.0}, 0.0), InvalidInput);
  BoundaryConnectionOptions options;
  options.tolerance = std::numeric_limits<double>::infinity();
  EXPECT_THROW(findBoundaryConnections(d, {0.0, 1.0, 2.0}, 3.0, options), InvalidInput);
  EXPECT_THROW(findBoundaryConnections(d, {0.0, 1.0, 2.0}, 3.0, std::vector<char>(2, 0)),
               InvalidInput);
}

}  // namespace
}  // namespace egg::geodesic
