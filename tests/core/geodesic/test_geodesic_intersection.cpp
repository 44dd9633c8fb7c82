// Intersection of two geodesics from four distance fields (Section 4.5.2) against the crossing of
// the two traced paths; non-crossing geodesics are reported as such.
#include "core/geodesic/geodesic_intersection.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

namespace egg::geodesic {
namespace {

struct Member {
  SurfacePoint a, b;
};

GeodesicIntersection fieldIntersection(const TriMesh& mesh, const DistanceSolver& solver,
                                       const Member& m1, const Member& m2) {
  const auto fields = solver.distances({m1.a, m1.b, m2.a, m2.b}, {m1.b, m2.b});
  return intersectGeodesics(mesh, fields[0].vertexDistances, fields[1].vertexDistances,
                            fields[2].vertexDistances, fields[3].vertexDistances,
                            fields[0].targetDistances[0], fields[2].targetDistances[1]);
}

TEST(GeodesicIntersection, MatchesTheCrossingOfTracedPathsOnABump) {
  const TriMesh mesh =
      testing::gridMesh(30, 30, 1.0, 1.0, testing::bump(0.5, 0.5, 0.3, 0.25), 0.15);
  const DistanceSolver solver(mesh);
  const double h = solver.meanEdgeLength();
  const std::vector<std::pair<Member, Member>> cases = {
      {{snapToSurface(mesh, {0.0, 0.3, 0}), snapToSurface(mesh, {1.0, 0.65, 0})},
       {snapToSurface(mesh, {0.35, 0.0, 0}), snapToSurface(mesh, {0.6, 1.0, 0})}},
      {{snapToSurface(mesh, {0.0, 0.8, 0}), snapToSurface(mesh, {1.0, 0.2, 0})},
       {snapToSurface(mesh, {0.2, 0.0, 0}), snapToSurface(mesh, {0.9, 1.0, 0})}}};
  for (const auto& [m1, m2] : cases) {
    const auto p1 = solver.path(m1.a, m1.b), p2 = solver.path(m2.a, m2.b);
    const auto exact = intersectPolylines(p1.positions, p2.positions, 1e-9);
    ASSERT_TRUE(exact.found);
    const auto result = fieldIntersection(mesh, solver, m1, m2);
    ASSERT_TRUE(result.found);
    const double vertexError =
        (toEigen(mesh.point(TriMesh::VertexHandle(result.nearestVertex))) - exact.position).norm();
    const double refinedError = (result.position - exact.position).norm();
    EXPECT_LT(vertexError, 1.0 * h);
    // The second-order refinement lands well inside the vertex ring.
    EXPECT_LT(refinedError, 0.25 * h) << "vertex error " << vertexError / h << " h";
    EXPECT_GE(result.vertexExcess, -1e-12);
  }
}

TEST(GeodesicIntersection, ReportsNonCrossingGeodesics) {
  const TriMesh mesh = testing::gridMesh(24, 24, 1.0, 1.0, testing::bump(0.5, 0.5, 0.2, 0.3), 0.1);
  const DistanceSolver solver(mesh);
  const Member m1{snapToSurface(mesh, {0.0, 0.2, 0}), snapToSurface(mesh, {1.0, 0.25, 0})};
  const Member m2{snapToSurface(mesh, {0.0, 0.8, 0}), snapToSurface(mesh, {1.0, 0.75, 0})};
  const auto result = fieldIntersection(mesh, solver, m1, m2);
  EXPECT_FALSE(result.found);
  EXPECT_GT(result.vertexExcess, 0.1);  // about twice the gap between them
}

TEST(GeodesicIntersection, PolylinesThatDoNotMeet) {
  const std::vector<Eigen::Vector3d> a = {{0, 0, 0}, {1, 0, 0}}, b = {{0, 1, 0}, {1, 1, 0}};
  EXPECT_FALSE(intersectPolylines(a, b, 1e-9).found);
  const std::vector<Eigen::Vector3d> c = {{0.5, -1, 0}, {0.5, 1, 0}};
  const auto x = intersectPolylines(a, c, 1e-12);
  ASSERT_TRUE(x.found);
  EXPECT_NEAR(x.arcLengthFirst, 0.5, 1e-15);
  EXPECT_NEAR(x.arcLengthSecond, 1.0, 1e-15);
}

TEST(GeodesicIntersection, RejectsMismatchedFields) {
  const TriMesh mesh = testing::gridMesh(3, 3, 1.0, 1.0, testing::flat);
  const std::vector<double> good(mesh.n_vertices(), 1.0), bad(3, 1.0);
  EXPECT_THROW(intersectGeodesics(mesh, good, good, good, bad, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(intersectGeodesics(mesh, good, good, good, good, 0.0, 1.0), InvalidInput);
  GeodesicIntersectionOptions options;
  options.fitRings = 0;
  EXPECT_THROW(intersectGeodesics(mesh, good, good, good, good, 1.0, 1.0, options), InvalidInput);
}

}  // namespace
}  // namespace egg::geodesic
