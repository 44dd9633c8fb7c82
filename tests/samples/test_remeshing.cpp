#include "samples/generators/remeshing.hpp"

#include "tests/samples/mesh_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::samples::detail {
namespace {

// A structured grid of n x m right triangles over [0, width] x [0, height]; all boundary vertices
// free except the four corners.
DomainMesh grid(int n, int m, double width, double height) {
  DomainMesh mesh;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.domain.emplace_back(width * i / n, height * j / m);
      mesh.locked.push_back((i == 0 || i == n) && (j == 0 || j == m));
    }
  }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

TEST(Remeshing, FlatSquareBecomesNearEquilateral) {
  SurfaceSpec spec;
  spec.position = [](const Vec2& u) { return Vec3(u.x(), u.y(), 0.0); };
  RemeshOptions options;
  options.targetEdge = 0.5;
  const TriMesh mesh = meshFromSoup(remeshInDomain(spec, grid(20, 20, 5.0, 5.0), options));
  const auto report = testing::inspect(mesh);
  EXPECT_EQ(report.components, 1);
  EXPECT_GT(report.minAngleDeg, 25.0);  // the grid started at 45 degrees, with valence 4 and 8
  EXPECT_NEAR(report.meanEdge, 0.5, 0.12 * 0.5);
  EXPECT_NEAR(surfaceArea(mesh), 25.0, 1e-9);  // the boundary did not move
  for (auto f : mesh.faces()) EXPECT_GT(testing::faceNormal(mesh, f).z(), 0.0);
}

TEST(Remeshing, EdgesAreMeasuredOnTheSurfaceNotInTheDomain) {
  // The domain [0, 3] x [0, 1] maps onto a 3 x 3 m square (y stretched 3 times): the domain grid
  // is isotropic, the 3D triangles are not until remeshed.
  SurfaceSpec spec;
  spec.position = [](const Vec2& u) { return Vec3(u.x(), 3 * u.y(), 0.0); };
  spec.reverseOrientation = true;
  RemeshOptions options;
  options.targetEdge = 0.3;
  const TriMesh mesh = meshFromSoup(remeshInDomain(spec, grid(30, 10, 3.0, 1.0), options));
  const auto report = testing::inspect(mesh);
  EXPECT_GT(report.minAngleDeg, 25.0);
  EXPECT_NEAR(report.meanEdge, 0.3, 0.12 * 0.3);
  EXPECT_NEAR(surfaceArea(mesh), 9.0, 1e-9);
  for (auto f : mesh.faces()) EXPECT_LT(testing::faceNormal(mesh, f).z(), 0.0);  // reversed
}

TEST(Remeshing, LockedVerticesStayAndCurvedMapsAreExact) {
  SurfaceSpec spec;
  spec.position = [](const Vec2& u) {
    return Vec3(u.x(), u.y(), std::sin(u.x()) * std::cos(u.y()));
  };
  DomainMesh input = grid(12, 12, 3.0, 3.0);
  input.locked[6 * 13 + 6] = true;  // the centre (1.5, 1.5)
  RemeshOptions options;
  options.targetEdge = 0.2;
  const TriangleSoup soup = remeshInDomain(spec, input, options);
  bool centre = false;
  for (const Vec3& p : soup.vertices) {
    EXPECT_NEAR(p.z(), std::sin(p.x()) * std::cos(p.y()), 1e-14);
    centre = centre || (p.head<2>() - Vec2(1.5, 1.5)).norm() < 1e-15;
  }
  EXPECT_TRUE(centre);
}

}  // namespace
}  // namespace egg::samples::detail
