// The simulation stage on the notch-free cylinder grid: the guess lies on the surface, the
// deployed grid stays close to it, every bolt holds, runs with and without notches both report.
#include "core/rods/simulation.hpp"

#include "core/rods/sample_grids.hpp"

#include <gtest/gtest.h>

namespace egg::rods {
namespace {

SampleGrid smallVault() {
  CylinderGridParameters parameters;
  parameters.radius_m = 3.0;
  parameters.halfAngle_rad = 0.6;
  parameters.length_m = 3.0;
  parameters.spacing_m = 0.75;
  parameters.section = {0.05, 0.005};
  parameters.meshEdge_m = 0.05;  // chordal error 0.05^2 / (8 R) = 0.1 mm, well below t/2
  return cylinderGrid(parameters);
}

TEST(Simulation, ContactPointsOfTheGuessLieOnTheSurface) {
  const SampleGrid grid = smallVault();
  const RodModel model(grid.network, ModelOptions{});
  const SurfaceDistance surface(grid.surface);
  std::vector<Eigen::Vector3d> contact;
  for (int r = 0; r < model.rodCount(); ++r) {
    for (int i = 0; i < model.vertexCount(r); ++i) {
      contact.push_back(model.contactPoint(r, i));
      // Centrelines sit half a thickness off the surface, on their layer's side.
      EXPECT_NEAR(surface.distance(model.vertex(r, i)), 0.0025, 2e-4);
    }
  }
  // Only the chordal error of the 0.05 m triangulation of a radius-3 m cylinder remains.
  EXPECT_LT(measureDeviation(contact, surface).max_m, 0.05 * 0.05 / (8.0 * 3.0) * 1.01);
}

TEST(Simulation, NotchFreeCylinderGridDeploysOntoTheCylinder) {
  const SampleGrid grid = smallVault();
  SimulationOptions options;
  options.compareWithoutNotches = true;
  options.scaleFactor = 2.0;
  const SimulationResult result = simulateGrid(grid.network, grid.surface, options);
  ASSERT_TRUE(result.converged) << result.reason;
  ASSERT_TRUE(result.withoutNotches.has_value());
  const SimulationRun& plain = *result.withoutNotches;
  ASSERT_TRUE(plain.deviation.has_value());
  // A notch-free geodesic grid supported at every member end: within a thickness of the surface.
  EXPECT_LT(plain.deviation->rmse_m, 0.005);
  EXPECT_LT(plain.deviation->max_m, 0.02);
  EXPECT_NEAR(plain.deviation->nrmse, plain.deviation->rmse_m / 2.0, 1e-15);
  // Plain holes: bolts stay where they were drilled.
  for (size_t c = 0; c < grid.network.connections.size(); ++c) {
    EXPECT_DOUBLE_EQ(plain.boltPositions_m[c][0], grid.network.connections[c].sA_m);
  }
  // With notches the bolts may slide, but only within their slots.
  const SimulationRun& notched = result.deployed;
  ASSERT_TRUE(notched.deviation.has_value());
  EXPECT_LT(notched.deviation->rmse_m, 0.05);
  for (size_t c = 0; c < grid.network.connections.size(); ++c) {
    const Connection& con = grid.network.connections[c];
    EXPECT_GE(notched.boltPositions_m[c][0], con.sA_m - con.notchA.before_m - 1e-12);
    EXPECT_LE(notched.boltPositions_m[c][0], con.sA_m + con.notchA.after_m + 1e-12);
  }
  EXPECT_GT(notched.unknowns, plain.unknowns);  // one unknown per sliding bolt side
  for (const auto& line : notched.centrelines) {
    for (const auto& p : line) ASSERT_TRUE(p.allFinite());
  }
}

TEST(Simulation, TimeLimitIsAResultWithAReason) {
  const SampleGrid grid = smallVault();
  SimulationOptions options;
  options.solver.timeLimit_s = 1e-4;
  const SimulationRun run = simulateRods(grid.network, nullptr, options);
  EXPECT_FALSE(run.solver.converged);
  EXPECT_FALSE(run.solver.reason.empty());
  for (const auto& line : run.centrelines) {
    for (const auto& p : line) ASSERT_TRUE(p.allFinite());
  }
}

}  // namespace
}  // namespace egg::rods
