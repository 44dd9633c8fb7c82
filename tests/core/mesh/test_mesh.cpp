#include "core/mesh/mesh.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TriangleSoup unitSquare() {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  return soup;
}

TEST(Mesh, SquareHasKnownAreaBoxAndEdges) {
  const TriMesh mesh = meshFromSoup(unitSquare());
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(mesh.n_faces(), 2u);
  EXPECT_DOUBLE_EQ(surfaceArea(mesh), 1.0);
  EXPECT_DOUBLE_EQ(boundingBox(mesh).size().x(), 1.0);
  EXPECT_NEAR(meanEdgeLength(mesh), (4.0 + std::sqrt(2.0)) / 5.0, 1e-15);
}

TEST(Mesh, SurfacePointPositionIsBarycentric) {
  const TriMesh mesh = meshFromSoup(unitSquare());
  SurfacePoint p{0, Eigen::Vector3d(0.2, 0.3, 0.5)};
  const auto ids = faceVertices(mesh, 0);
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    expected += p.barycentric[i] * toEigen(mesh.point(TriMesh::VertexHandle(ids[i])));
  EXPECT_TRUE(position(mesh, p).isApprox(expected));
  EXPECT_NEAR(position(mesh, p).z(), 0.0, 1e-15);
}

TEST(Mesh, SoupRoundTripKeepsTriangles) {
  const TriangleSoup back = soupFromMesh(meshFromSoup(unitSquare()));
  ASSERT_EQ(back.triangles.size(), 2u);
  EXPECT_EQ(back.triangles[1], (std::array<int, 3>{0, 2, 3}));
}

TEST(Mesh, BadIndexNamesTheTriangle) {
  TriangleSoup soup = unitSquare();
  soup.triangles.push_back({0, 3, 7});
  try {
    meshFromSoup(soup);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 2"), std::string::npos) << e.what();
  }
}

TEST(Mesh, ThirdTriangleOnAnEdgeIsRejected) {
  TriangleSoup soup = unitSquare();
  soup.vertices.push_back({0.5, 0.5, 1.0});
  soup.triangles.push_back({0, 2, 4});  // edge 0-2 is already shared by two triangles
  EXPECT_THROW(meshFromSoup(soup), InvalidInput);
}

}  // namespace
}  // namespace egg

namespace egg {
namespace {

TEST(Mesh, ClosestPointBarycentricCoversInteriorEdgesAndCorners) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(closestPointBarycentric({0.2, 0.3, 5.0}, a, b, c)
                  .isApprox(Eigen::Vector3d(0.5, 0.2, 0.3)));  // above the face
  EXPECT_TRUE(closestPointBarycentric({-1, -1, 0}, a, b, c)
                  .isApprox(Eigen::Vector3d(1, 0, 0)));  // corner a
  EXPECT_TRUE(closestPointBarycentric({0.5, -2, 0}, a, b, c)
                  .isApprox(Eigen::Vector3d(0.5, 0.5, 0)));  // edge ab
  EXPECT_TRUE(closestPointBarycentric({1, 1, 0}, a, b, c)
                  .isApprox(Eigen::Vector3d(0, 0.5, 0.5)));  // edge bc
}

// An L of three unit squares: the vertex (1, 1) is reflex (270 degrees inside).
TriMesh lShape() {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0},
                   {1, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}};
  soup.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 7}, {3, 7, 6}};
  return meshFromSoup(soup);
}

TEST(Mesh, ATautStringRoundAReflexCornerTurnsByItsExcess) {
  const TriMesh mesh = lShape();
  // (2, 1) -> (1, 1) -> (1, 2) hugs the reflex corner: 270 degrees through the faces, less pi.
  EXPECT_NEAR(geodesicTurningAtBoundary(mesh, TriMesh::VertexHandle(4), {2, 1, 0}, {1, 2, 0}),
              M_PI / 2, 1e-12);
  // Along the straight bottom edge through (1, 0): no turn.
  EXPECT_NEAR(geodesicTurningAtBoundary(mesh, TriMesh::VertexHandle(1), {0, 0, 0}, {2, 0, 0}), 0.0,
              1e-12);
  // From inside the faces: (1.5, 0.5) -> (1, 1) -> (0.5, 1.5) is a straight line, 180 degrees
  // through them.
  EXPECT_NEAR(
      geodesicTurningAtBoundary(mesh, TriMesh::VertexHandle(4), {1.5, 0.5, 0}, {0.5, 1.5, 0}), 0.0,
      1e-12);
  // At the convex corner (2, 0), 90 degrees inside: a polyline through it turns the other way.
  EXPECT_NEAR(geodesicTurningAtBoundary(mesh, TriMesh::VertexHandle(2), {1.5, 0, 0}, {2, 0.5, 0}),
              -M_PI / 2, 1e-12);
  const std::vector<Eigen::Vector3d> wrap{{2, 1, 0}, {1, 1, 0}, {1, 2, 0}};
  EXPECT_NEAR(boundaryWrapTurning(mesh, wrap, {4}), M_PI / 2, 1e-12);
  EXPECT_EQ(boundaryWrapTurning(mesh, wrap, {5, 7}), 0.0);  // the ends do not count
  const std::vector<Eigen::Vector3d> straight{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_NEAR(boundaryWrapTurning(mesh, straight, {1}), 0.0, 1e-12);
}

}  // namespace
}  // namespace egg
