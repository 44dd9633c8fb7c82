// Exact point-to-triangle distances against closed forms.
#include "core/rods/surface_distance.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::rods {
namespace {

// The unit square in z = 0, two triangles.
TriMesh unitSquare() {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  return meshFromSoup(soup);
}

TEST(SurfaceDistance, PointsAboveInsideAndBesideTheSquare) {
  const SurfaceDistance surface(unitSquare());
  EXPECT_NEAR(surface.distance({0.3, 0.6, 0.25}), 0.25, 1e-15);  // above the interior
  EXPECT_NEAR(surface.distance({0.5, 0.5, -0.1}), 0.1, 1e-15);   // below, across the diagonal
  EXPECT_NEAR(surface.distance({2.0, 0.5, 0.0}), 1.0, 1e-15);    // beside an edge
  EXPECT_NEAR(surface.distance({2.0, 2.0, 1.0}), std::sqrt(3.0), 1e-15);  // beyond a corner
  const Eigen::Vector3d c = surface.closestPoint({2.0, 0.5, 0.3});
  EXPECT_NEAR((c - Eigen::Vector3d(1.0, 0.5, 0.0)).norm(), 0.0, 1e-15);
}

TEST(SurfaceDistance, DeviationStatsAreRmsMaxAndNormalisedRms) {
  const SurfaceDistance surface(unitSquare());
  const std::vector<Eigen::Vector3d> points{{0.2, 0.2, 0.3}, {0.7, 0.4, -0.4}};
  const DeviationStats stats = measureDeviation(points, surface, 5.0);
  EXPECT_EQ(stats.points, 2);
  EXPECT_NEAR(stats.rmseM, std::sqrt((0.09 + 0.16) / 2.0), 1e-15);
  EXPECT_NEAR(stats.maxM, 0.4, 1e-15);
  EXPECT_NEAR(stats.nrmse, stats.rmseM / 5.0, 1e-15);
  EXPECT_THROW(measureDeviation(points, surface, 0.0), InvalidInput);
}

TEST(SurfaceDistance, EmptyMeshIsInvalidInput) {
  EXPECT_THROW(SurfaceDistance(TriMesh{}), InvalidInput);
}

}  // namespace
}  // namespace egg::rods
