// Joined patches: indices are offset per patch, joins become plain bolts, and two stacked
// lamellas of adjacent patches bolted together carry their self-weight between the bounds of
// beam theory (no composite action: wL^4/8EI; full composite action: a quarter of it).
#include "core/rods/joined_network.hpp"

#include "core/errors.hpp"
#include "core/rods/rod_solver.hpp"
#include "core/rods/sample_grids.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::rods {
namespace {

Rod lamella(int layer, double length) {
  Rod rod;
  rod.lengthM = length;
  rod.section = {0.02, 0.002};
  rod.material = {10.0e9, 3.8e9, 600.0};
  rod.layer = layer;
  rod.guess = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(length, 0, 0)};
  rod.guessNormals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  return rod;
}

TEST(JoinedNetwork, OffsetsRodIndicesAndAddsJoinBolts) {
  RodNetwork a, b;
  a.rods = {lamella(0, 1.0), lamella(1, 1.0)};
  a.connections.push_back(Connection{0, 0.5, 1, 0.5, {}, {}, {}, {}});
  b.rods = {lamella(1, 1.0)};
  Anchor anchor;
  anchor.rod = 0;
  anchor.sM = 0.2;
  anchor.position = Eigen::Vector3d(0.2, 0, 0);
  anchor.normal = Eigen::Vector3d::UnitZ();
  b.anchors.push_back(anchor);
  const JoinedNetwork joined = joinPatches({a, b}, {PatchJoin{0, 0, 0.9, 1, 0, 0.9}});
  ASSERT_EQ(joined.network.rods.size(), 3u);
  EXPECT_EQ(joined.firstRod, (std::vector<int>{0, 2}));
  ASSERT_EQ(joined.network.connections.size(), 2u);
  EXPECT_EQ(joined.network.connections[1].rodA, 0);
  EXPECT_EQ(joined.network.connections[1].rodB, 2);
  EXPECT_EQ(joined.network.anchors[0].rod, 2);
  // Same layer cannot be bolted face to face; unknown rods are named.
  EXPECT_THROW(joinPatches({a, b}, {PatchJoin{0, 1, 0.9, 1, 0, 0.9}}), InvalidInput);
  EXPECT_THROW(joinPatches({a, b}, {PatchJoin{0, 0, 0.9, 1, 3, 0.9}}), InvalidInput);
}

TEST(JoinedNetwork, StackedBoundaryLamellasCarryTheirWeightBetweenTheBeamBounds) {
  const double length = 1.0;
  RodNetwork first, second;
  first.rods = {lamella(0, length)};
  for (double s : {0.0, 0.025}) {  // two anchors close together: a clamp
    Anchor a;
    a.rod = 0;
    a.sM = s;
    a.position = Eigen::Vector3d(s, 0, 0);
    a.normal = Eigen::Vector3d::UnitZ();
    first.anchors.push_back(a);
  }
  second.rods = {lamella(1, length)};  // no supports of its own: carried by the join
  std::vector<PatchJoin> joins;
  for (double s : {0.025, 0.5, 1.0}) joins.push_back(PatchJoin{0, 0, s, 1, 0, s});
  const JoinedNetwork joined = joinPatches({first, second}, joins);

  ModelOptions options;
  options.minEdgesPerRod = 40;
  options.maxEdgesPerRod = 40;
  options.gravity = true;
  RodModel model(joined.network, options);
  const SolverResult result = minimiseEnergy(model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;

  const Rod& rod = joined.network.rods[0];
  const double w = rod.material.densityKgM3 * rod.section.widthM * rod.section.thicknessM * 9.81;
  const double ei = model.stiffness(0).bendingWeak;
  const double independent = w * std::pow(length, 4) / (8.0 * ei);  // each lamella on its own
  const double composite = independent / 4.0;  // one beam of twice the thickness
  for (int r = 0; r < 2; ++r) {
    const double sag = -model.contactPoint(r, 40).z();
    EXPECT_GT(sag, composite * 0.98) << "rod " << r;
    EXPECT_LT(sag, independent * 1.02) << "rod " << r;
  }
  // The bolts hold the lamellas face to face: centrelines one thickness apart at the tip.
  EXPECT_NEAR((model.vertex(1, 40) - model.vertex(0, 40)).norm(), 0.002, 2e-4);
}

TEST(JoinedNetwork, WithoutJoinsTheJoinedRunIsThePatchByPatchRun) {
  // Two vaults on the same cylinder, side by side along its axis (the second shifted by 3 m).
  CylinderGridParameters parameters;
  parameters.radiusM = 3.0;
  parameters.halfAngleRad = 0.6;
  parameters.lengthM = 6.0;
  parameters.spacingM = 0.75;
  parameters.notchFraction = 0.0;
  parameters.meshEdgeM = 0.1;
  const SampleGrid whole = cylinderGrid(parameters);
  parameters.lengthM = 3.0;
  SampleGrid first = cylinderGrid(parameters), second = cylinderGrid(parameters);
  const Eigen::Vector3d shift(0, 3.0, 0);
  for (Rod& rod : second.network.rods) {
    for (auto& p : rod.guess) p += shift;
  }
  for (Anchor& a : second.network.anchors) a.position += shift;
  const JoinedSimulation result = simulateJoinedPatches({first.network, second.network}, {},
                                                        whole.surface, SimulationOptions{});
  ASSERT_TRUE(result.converged);
  ASSERT_EQ(result.perPatch.size(), 2u);
  EXPECT_EQ(result.patchByPatch.points, result.perPatch[0].vertices + result.perPatch[1].vertices);
  EXPECT_NEAR(result.joined.deviation->rmseM, result.patchByPatch.rmseM,
              1e-6 * result.patchByPatch.rmseM + 1e-9);
  EXPECT_NEAR(result.joined.deviation->maxM, result.patchByPatch.maxM, 1e-6);
}

}  // namespace
}  // namespace egg::rods
