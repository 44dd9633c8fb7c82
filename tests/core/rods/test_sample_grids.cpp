// The cylinder grid is an exact geodesic grid: member lengths equal the lengths of their curves on
// the surface, and both members of a bolt reach the same surface point at their arc lengths.
#include "core/rods/sample_grids.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg::rods {
namespace {

double polylineLength(const std::vector<Eigen::Vector3d>& p) {
  double length = 0.0;
  for (size_t i = 1; i < p.size(); ++i) length += (p[i] - p[i - 1]).norm();
  return length;
}

Eigen::Vector3d pointAt(const std::vector<Eigen::Vector3d>& p, double s) {
  double walked = 0.0;
  for (size_t i = 1; i < p.size(); ++i) {
    const double segment = (p[i] - p[i - 1]).norm();
    if (walked + segment >= s) return p[i - 1] + (s - walked) / segment * (p[i] - p[i - 1]);
    walked += segment;
  }
  return p.back();
}

TEST(SampleGrids, CylinderGridIsAnExactGeodesicGrid) {
  CylinderGridParameters parameters;
  parameters.radiusM = 3.0;
  parameters.lengthM = 4.0;
  parameters.spacingM = 0.7;
  const SampleGrid grid = cylinderGrid(parameters);
  ASSERT_GT(grid.network.rods.size(), 6u);
  ASSERT_GT(grid.network.connections.size(), 10u);
  EXPECT_NO_THROW(validateNetwork(grid.network));
  EXPECT_EQ(grid.network.anchors.size(), 2 * grid.network.rods.size());
  for (const Rod& rod : grid.network.rods) {
    // Helices sampled finely: chord length within 1e-4 of the exact geodesic length.
    EXPECT_NEAR(polylineLength(rod.guess), rod.lengthM, 1e-4 * rod.lengthM);
  }
  int notched = 0;
  for (const Connection& c : grid.network.connections) {
    const Eigen::Vector3d a = pointAt(grid.network.rods[c.rodA].guess, c.sAM);
    const Eigen::Vector3d b = pointAt(grid.network.rods[c.rodB].guess, c.sBM);
    EXPECT_LT((a - b).norm(), 1e-3 * parameters.spacingM);
    EXPECT_NE(grid.network.rods[c.rodA].layer, grid.network.rods[c.rodB].layer);
    notched += c.notchA.afterM > 0.0;
  }
  EXPECT_GT(notched, 0);
  EXPECT_GT(grid.surface.n_faces(), 100u);
}

TEST(SampleGrids, BadParametersAreInvalidInput) {
  CylinderGridParameters parameters;
  parameters.halfAngleRad = 2.0;
  EXPECT_THROW(cylinderGrid(parameters), InvalidInput);
}

}  // namespace
}  // namespace egg::rods
