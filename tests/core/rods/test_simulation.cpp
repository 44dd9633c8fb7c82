// The simulation stage on the notch-free cylinder grid: the guess lies on the surface, the
// deployed grid stays close to it, every bolt holds, runs with and without notches both report.
#include "core/rods/simulation.hpp"

#include "core/errors.hpp"
#include "core/rods/sample_grids.hpp"
#include "tests/core/rods/rod_test_networks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace egg::rods {
namespace {

using testing::smallVault;

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
  EXPECT_LT(measureDeviation(contact, surface).maxM, 0.05 * 0.05 / (8.0 * 3.0) * 1.01);
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
  EXPECT_LT(plain.deviation->rmseM, 0.005);
  EXPECT_LT(plain.deviation->maxM, 0.02);
  EXPECT_NEAR(plain.deviation->nrmse, plain.deviation->rmseM / 2.0, 1e-15);
  // Plain holes: bolts stay where they were drilled.
  for (size_t c = 0; c < grid.network.connections.size(); ++c) {
    EXPECT_DOUBLE_EQ(plain.boltPositionsM[c][0], grid.network.connections[c].sAM);
  }
  // With notches the bolts may slide, but only within their slots.
  const SimulationRun& notched = result.deployed;
  ASSERT_TRUE(notched.deviation.has_value());
  EXPECT_LT(notched.deviation->rmseM, 0.05);
  for (size_t c = 0; c < grid.network.connections.size(); ++c) {
    const Connection& con = grid.network.connections[c];
    EXPECT_GE(notched.boltPositionsM[c][0], con.sAM - con.notchA.beforeM - 1e-12);
    EXPECT_LE(notched.boltPositionsM[c][0], con.sAM + con.notchA.afterM + 1e-12);
  }
  EXPECT_GT(notched.unknowns, plain.unknowns);  // one unknown per sliding bolt side
  for (const auto& line : notched.centrelines) {
    for (const auto& p : line) ASSERT_TRUE(p.allFinite());
  }
}

// A vault whose grid maps onto itself under the half turn about the vertical axis through its
// centre, (x, y, z) -> (-x, L - y, z): the lines v = +-u + c of the development map to lines of the
// same family when (L + 2 R phi) / (spacing sqrt 2) is an integer (here 6). The turn keeps each
// family in its layer, reverses the rods (notches are symmetric, E_p is symmetric in beta <-> 1 -
// beta) and keeps gravity, so the equilibrium must be symmetric too.
CylinderGridParameters symmetricVault() {
  CylinderGridParameters parameters;
  parameters.radiusM = 3.0;
  parameters.halfAngleRad = 0.6;
  parameters.lengthM = 3.0;
  parameters.spacingM = (3.0 + 2.0 * 3.0 * 0.6) / (6.0 * std::sqrt(2.0));
  parameters.section = {0.05, 0.005};
  parameters.notchFraction = 0.2;
  parameters.meshEdgeM = 0.05;
  return parameters;
}

TEST(Simulation, NotchedVaultUnderSelfWeightConvergesSymmetricAndLinear) {
  const SampleGrid grid = cylinderGrid(symmetricVault());
  const SurfaceDistance surface(grid.surface);
  const double length = symmetricVault().lengthM;
  double sag[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    SimulationOptions options;
    options.model.gravity = true;
    options.model.gravityMPerS2 = k == 0 ? 9.81 : 0.5 * 9.81;
    const SimulationRun run = simulateRods(grid.network, &surface, options);
    ASSERT_TRUE(run.solver.converged) << run.solver.reason;
    ASSERT_GT(run.solver.iterations, 0);
    sag[k] = run.maxSagM;
    // Half-turn symmetry of every rod with its partner (found from the guess), vertex by vertex.
    int partners = 0;
    double asymmetry = 0.0;
    const auto& rods = grid.network.rods;
    auto turn = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(-p.x(), length - p.y(), p.z());
    };
    for (size_t a = 0; a < rods.size(); ++a) {
      for (size_t b = 0; b < rods.size(); ++b) {
        if ((rods[b].guess.front() - turn(rods[a].guess.back())).norm() > 1e-9) continue;
        ASSERT_EQ(rods[a].layer, rods[b].layer);
        const auto& ca = run.centrelines[a];
        const auto& cb = run.centrelines[b];
        ASSERT_EQ(ca.size(), cb.size());
        ++partners;
        for (size_t i = 0; i < ca.size(); ++i)
          asymmetry = std::max(asymmetry, (ca[i] - turn(cb[cb.size() - 1 - i])).norm());
      }
    }
    EXPECT_EQ(partners, static_cast<int>(rods.size()));
    EXPECT_LT(asymmetry, 1e-9);  // measured: ~3e-15 m (round-off), against a sag of ~2.5 mm
  }
  // 50 x 5 mm plywood strips over a 3 m vault sag ~2.5 mm (0.08 % of the span): the linear range,
  // where half the weight gives half the sag (measured ratio 2.011; sliding bolts and the
  // friction barrier keep the response smooth).
  EXPECT_GT(sag[0], 1e-4);
  EXPECT_LT(sag[0], 0.01);
  EXPECT_NEAR(sag[0] / sag[1], 2.0, 0.03);
}

// The 8 m vault of `egg bench sim --gravity`: lamellas 50 x 5 mm weigh 1.2 N/m while a lone
// strip arch of radius 5 m buckles near 6 mN/m (~14 EI/R^3), so the vault stands only as a shell
// of bolted strips. With plain holes it does (a few cm of sag); with sliding bolts the shell
// action is gone and it falls through (its collapsed equilibrium, ~1.7 m down, takes ~760
// iterations). Within a small budget the notched run must say so, not just "no convergence".
TEST(Simulation, SlowSlidingBoltsLetAThinLargeVaultCollapseUnderItsWeight) {
  CylinderGridParameters parameters;  // R 5 m, 8 m long, 1 m spacing: the bench vault
  parameters.meshEdgeM = 0.1;
  const SampleGrid grid = cylinderGrid(parameters);
  SimulationOptions options;
  options.model.gravity = true;
  options.collapseFraction = 0.01;  // ~11 cm of the ~10.9 m extent
  options.solver.maxIterations = 200;
  options.model.notches = false;
  const SimulationRun plain = simulateRods(grid.network, nullptr, options);
  ASSERT_TRUE(plain.solver.converged) << plain.solver.reason;
  EXPECT_LT(plain.maxSagM, 0.1);
  options.model.notches = true;
  const SimulationRun notched = simulateRods(grid.network, nullptr, options);
  EXPECT_FALSE(notched.solver.converged);
  EXPECT_EQ(notched.solver.status, SolverStatus::Collapsed) << notched.solver.reason;
  EXPECT_NE(notched.solver.reason.find("collapses under its own weight"), std::string::npos);
  EXPECT_GT(notched.maxSagM, 0.11);  // measured 0.35 m after 200 iterations
  for (const auto& line : notched.centrelines) {
    for (const auto& p : line) ASSERT_TRUE(p.allFinite());
  }
}

TEST(Simulation, FasteningTheBoltsBeforeLoadingHoldsTheVaultThatCollapsesWithLooseOnes) {
  // The same vault whose sliding bolts let it fall through (above): tightened at the weightless
  // equilibrium, the scissor grid can no longer shear nor slide, and it carries its weight.
  CylinderGridParameters parameters;
  parameters.meshEdgeM = 0.1;
  const SampleGrid grid = cylinderGrid(parameters);
  SimulationOptions options;
  options.model.gravity = true;
  options.collapseFraction = 0.01;
  options.solver.maxIterations = 200;
  options.fastenBoltsUnderLoad = true;
  const SimulationRun fastened = simulateRods(grid.network, nullptr, options);
  ASSERT_TRUE(fastened.solver.converged) << fastened.solver.reason;
  EXPECT_LT(fastened.maxSagM, 0.05);
  // Fastened bolts do not slide under load: each bolt is where the weightless run left it.
  options.model.gravity = false;
  const SimulationRun weightless = simulateRods(grid.network, nullptr, options);
  ASSERT_TRUE(weightless.solver.converged) << weightless.solver.reason;
  ASSERT_EQ(fastened.boltPositionsM.size(), weightless.boltPositionsM.size());
  for (size_t b = 0; b < fastened.boltPositionsM.size(); ++b)
    for (int side = 0; side < 2; ++side)
      EXPECT_NEAR(fastened.boltPositionsM[b][side], weightless.boltPositionsM[b][side], 1e-9) << b;
}

// The joined run's warm start (startFrom, gravitySteps = 0): a run started from an equilibrium
// under self-weight is at that equilibrium already, with the rods in either layer order.
TEST(Simulation, AWarmStartFromAnEquilibriumUnderSelfWeightStaysThere) {
  const SampleGrid grid = cylinderGrid(symmetricVault());
  SimulationOptions options;
  options.model.gravity = true;
  const SimulationRun first = simulateRods(grid.network, nullptr, options);
  ASSERT_TRUE(first.solver.converged) << first.solver.reason;
  ASSERT_GT(first.maxSagM, 1e-4);  // ~2.5 mm: the start really carries its weight
  RodNetwork warm = grid.network;
  startFrom(warm, first);
  SimulationOptions again = options;
  again.gravitySteps = 0;
  again.solver.stiffnessContinuation = false;
  const SimulationRun second = simulateRods(warm, nullptr, again);
  ASSERT_TRUE(second.solver.converged) << second.solver.reason;
  // The sliding bolts restart where the guess curves cross, found by sampling each notch (64
  // samples), not exactly where they were: a few Newton steps remain (measured 9, against 40 for
  // the cold start), and the state moves by a fraction of the sag (measured 0.13 mm of 2.5 mm).
  // A wrong guess (a centreline on the wrong side of the contact surface, a lost twist) would
  // move it by a thickness (5 mm) or more.
  EXPECT_LT(2 * second.solver.iterations, first.solver.iterations) << first.solver.iterations;
  EXPECT_LT(second.maxSagM, 0.1 * first.maxSagM);
  double moved = 0.0;
  for (size_t r = 0; r < first.centrelines.size(); ++r)
    for (size_t i = 0; i < first.centrelines[r].size(); ++i)
      moved = std::max(moved, (second.centrelines[r][i] - first.centrelines[r][i]).norm());
  EXPECT_LT(moved, 0.1 * first.maxSagM);
  // Same equilibrium: the same energy to the solver's tolerance.
  EXPECT_NEAR(second.solver.energy, first.solver.energy, 1e-6 * std::abs(first.solver.energy));
  // Mismatched runs are refused, naming the counts.
  RodNetwork other = grid.network;
  other.rods.pop_back();
  EXPECT_THROW(startFrom(other, first), InvalidInput);
}

// Error against run time (SimulationOptions::historyEvery): the start (the guess on the surface),
// every n-th iteration and the final state, whose sample is the run's own deviation; watching
// changes nothing of the run.
TEST(Simulation, HistoryRecordsTheErrorFromTheGuessToTheFinalState) {
  const SampleGrid grid = smallVault();
  const SurfaceDistance surface(grid.surface);
  SimulationOptions options;
  options.scaleFactor = 2.0;
  const SimulationRun reference = simulateRods(grid.network, &surface, options);
  ASSERT_TRUE(reference.solver.converged) << reference.solver.reason;
  EXPECT_TRUE(reference.history.empty());
  EXPECT_EQ(reference.solver.observations, 0);
  options.historyEvery = 3;
  int userCalls = 0, lastIteration = -1;
  options.solver.observer = [&](const SolverProgress& p, const RodModel&) {
    ++userCalls;
    EXPECT_GT(p.iteration, lastIteration);  // the run's count, each state once
    lastIteration = p.iteration;
  };
  const SimulationRun run = simulateRods(grid.network, &surface, options);
  ASSERT_TRUE(run.deviation.has_value());
  EXPECT_EQ(run.solver.iterations, reference.solver.iterations);
  EXPECT_EQ(run.deviation->rmseM, reference.deviation->rmseM);
  const int k = run.solver.iterations;
  ASSERT_GE(k, 4);
  // One load step (no gravity): iterations 0, 3, 6, ... below k, then the final state.
  ASSERT_EQ(static_cast<int>(run.history.size()), (k - 1) / 3 + 2);
  EXPECT_EQ(userCalls, static_cast<int>(run.history.size()));
  for (size_t i = 0; i + 1 < run.history.size(); ++i) {
    EXPECT_EQ(run.history[i].iteration, 3 * static_cast<int>(i));
    EXPECT_LE(run.history[i].seconds, run.history[i + 1].seconds);
  }
  // The start is the guess: only the chordal error of the mesh
  // (ContactPointsOfTheGuessLieOnTheSurface).
  EXPECT_LT(run.history.front().maxM, 0.05 * 0.05 / (8.0 * 3.0) * 1.01);
  EXPECT_EQ(run.history.back().iteration, k);
  EXPECT_EQ(run.history.back().rmseM, run.deviation->rmseM);
  EXPECT_EQ(run.history.back().maxM, run.deviation->maxM);
  EXPECT_GT(run.history.back().rmseM, 10.0 * run.history.front().rmseM);  // the deployment moved it
  EXPECT_LE(run.history.back().seconds, run.solver.seconds);
  EXPECT_GT(run.historySeconds, 0.0);
  EXPECT_LT(run.historySeconds, run.solver.seconds);
}

// The stage keeps the history of the deployed run only: the run without notches is a comparison of
// ends.
TEST(Simulation, HistoryIsTheDeployedRunsOnly) {
  const SampleGrid grid = smallVault();
  SimulationOptions options;
  options.compareWithoutNotches = true;
  options.historyEvery = 5;
  const SimulationResult result = simulateGrid(grid.network, grid.surface, options);
  ASSERT_TRUE(result.withoutNotches.has_value());
  ASSERT_GE(result.deployed.history.size(), 2u);
  EXPECT_EQ(result.deployed.history.back().rmseM, result.deployed.deviation->rmseM);
  EXPECT_TRUE(result.withoutNotches->history.empty());
  EXPECT_EQ(result.withoutNotches->solver.observations, 0);
}

// Under self-weight in two load steps: the load steps' ends are sampled, a step's start (the state
// the previous one ended with) is not sampled twice, and the last sample is still the final state.
TEST(Simulation, HistoryAcrossLoadStepsSamplesEachStateOnce) {
  const SampleGrid grid = cylinderGrid(symmetricVault());
  const SurfaceDistance surface(grid.surface);
  SimulationOptions options;
  options.model.gravity = true;
  options.historyEvery = 1000;  // only the start and the ends of the load steps
  const SimulationRun run = simulateRods(grid.network, &surface, options);
  ASSERT_TRUE(run.solver.converged) << run.solver.reason;
  ASSERT_EQ(run.history.size(), 4u);  // start, end of the weightless solve, of load step 1, of 2
  for (int step = 0; step <= 2; ++step) EXPECT_EQ(run.history[step + 1].loadStep, step);
  EXPECT_EQ(run.history[0].iteration, 0);
  for (size_t i = 0; i + 1 < run.history.size(); ++i)
    EXPECT_LT(run.history[i].iteration, run.history[i + 1].iteration);
  EXPECT_EQ(run.history.back().iteration, run.solver.iterations);
  EXPECT_EQ(run.history.back().rmseM, run.deviation->rmseM);
}

TEST(Simulation, TimeLimitIsAResultWithAReason) {
  const SampleGrid grid = smallVault();
  SimulationOptions options;
  options.solver.timeLimitS = 1e-4;
  const SimulationRun run = simulateRods(grid.network, nullptr, options);
  EXPECT_FALSE(run.solver.converged);
  EXPECT_FALSE(run.solver.reason.empty());
  for (const auto& line : run.centrelines) {
    for (const auto& p : line) ASSERT_TRUE(p.allFinite());
  }
}

}  // namespace
}  // namespace egg::rods
