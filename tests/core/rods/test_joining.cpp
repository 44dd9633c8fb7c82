// Joining deployed patches (deployment.hpp, joinDeployedPatches): two boundary lamellas of
// adjacent patches, one on the other, each standing on its own supports, take their weight, are
// bolted together and let go of their temporary supports. Beam theory gives the open joint before
// the bolts (the difference of two clamped beams' sags), statics the supports' forces, and the end
// is the joined structure's own equilibrium.
#include "core/errors.hpp"
#include "core/rods/deployment.hpp"
#include "core/rods/joined_network.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace egg::rods {
namespace joining_test {

constexpr double kLength = 0.8;
constexpr int kEdges = 80;

Rod lamella(int layer, double thickness) {
  Rod rod;
  rod.lengthM = kLength;
  rod.section = {0.02, thickness};
  rod.material = {10.0e9, 3.8e9, 600.0};
  rod.layer = layer;
  rod.guess = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(kLength, 0, 0)};
  rod.guessNormals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  return rod;
}

Anchor anchorAt(double s) {
  Anchor a;
  a.rod = 0;
  a.sM = s;
  a.position = Eigen::Vector3d(s, 0, 0);
  a.normal = Eigen::Vector3d::UnitZ();
  return a;
}

struct TwoPatches {
  JoinedNetwork joined;
  std::vector<bool> temporary;
};

// Patch 0: a 6 mm lamella clamped at x = 0 for good and propped at x = L for the joining; patch 1:
// a 4.5 mm lamella on it, clamped at both ends by temporary supports only. Joints at both ends and
// mid-span.
TwoPatches twoPatches() {
  RodNetwork first, second;
  first.rods = {lamella(0, 0.006)};
  first.anchors = {anchorAt(0.0), anchorAt(kLength)};
  second.rods = {lamella(1, 0.0045)};
  second.anchors = {anchorAt(0.0), anchorAt(kLength)};
  std::vector<PatchJoin> joins;
  for (double s : {0.0, 0.5 * kLength, kLength}) joins.push_back(PatchJoin{0, 0, s, 1, 0, s});
  TwoPatches out{joinPatches({first, second}, joins), {false, true, true, true}};
  return out;
}

JoiningOptions joiningOptions() {
  JoiningOptions o;
  o.deployment.model.minEdgesPerRod = kEdges;
  o.deployment.model.maxEdgesPerRod = kEdges;
  return o;
}

double weightPerMetre(const Rod& rod) {
  return rod.material.densityKgM3 * rod.section.widthM * rod.section.thicknessM * 9.81;
}

TEST(Joining, TwoPatchesBoltedAndLetGoEndWhereTheJoinedStructureStands) {
  const TwoPatches patches = twoPatches();
  const RodNetwork& network = patches.joined.network;
  ASSERT_EQ(patches.joined.firstJoin, 0);  // neither patch has bolts of its own
  const DeploymentResult result =
      joinDeployedPatches(network, patches.joined.firstJoin, patches.temporary, joiningOptions());
  ASSERT_TRUE(result.completed) << result.reason;
  const auto at = [&](double t) {
    const auto it =
        std::find_if(result.steps.begin(), result.steps.end(),
                     [&](const DeploymentStep& s) { return std::abs(s.t - t) < 1e-12; });
    EXPECT_NE(it, result.steps.end()) << "no step at t = " << t;
    return *it;
  };
  EXPECT_EQ(result.steps.back().t, 3.0);
  EXPECT_LT(at(0.0).maxJoinGapM, 1e-9);  // weightless and straight: nothing to close

  // t = 1: both carry their weight, clamped at both ends, the joints still open. Mid-span sag of
  // a clamped beam under its weight, w l^4 / (384 E I); the thinner lamella sags further. A clamp
  // holds the rod's end edge, and DER's curvature lives at the vertices over their Voronoi
  // lengths: the span that bends is l = L - h (half an edge held at each end).
  const auto sag = [&](int rod) {
    const Rod& r = network.rods[rod];
    const double ei =
        r.material.youngsModulusPa * r.section.widthM * std::pow(r.section.thicknessM, 3) / 12.0;
    return weightPerMetre(r) * std::pow(kLength - kLength / kEdges, 4) / (384.0 * ei);
  };
  const double gap = sag(1) - sag(0);
  ASSERT_GT(gap, 1e-4);
  EXPECT_NEAR(at(1.0).maxJoinGapM, gap, 0.03 * gap);

  // t = 2: the joints are bolted shut; their pull is what the crew's clamps held.
  EXPECT_LT(at(2.0).maxJoinGapM, 1e-6);
  EXPECT_GT(at(2.0).maxJoinForceN, 0.0);

  // t = 3: the temporary supports hold nothing, the clamp at x = 0 carries both lamellas.
  const DeploymentStep& end = result.steps.back();
  ASSERT_EQ(end.supportForcesN.size(), 4u);
  const double weight =
      (weightPerMetre(network.rods[0]) + weightPerMetre(network.rods[1])) * kLength;
  double carried = 0.0;
  for (size_t a = 0; a < end.supportForcesN.size(); ++a) {
    if (patches.temporary[a]) EXPECT_EQ(end.supportForcesN[a].norm(), 0.0) << "support " << a;
    carried += end.supportForcesN[a].z();
  }
  EXPECT_NEAR(carried, weight, 1e-3 * weight);
  // The last state records every bolt's gap and force as the step measured them.
  ASSERT_EQ(result.last.boltGapsM.size(), network.connections.size());
  ASSERT_EQ(result.last.boltForcesN.size(), network.connections.size());
  EXPECT_DOUBLE_EQ(*std::max_element(result.last.boltGapsM.begin(), result.last.boltGapsM.end()),
                   end.maxJoinGapM);
  EXPECT_DOUBLE_EQ(
      *std::max_element(result.last.boltForcesN.begin(), result.last.boltForcesN.end()),
      end.maxJoinForceN);

  // The joined structure solved at once, from straight, without the temporary supports: the same
  // cantilever.
  RodNetwork finished = network;
  finished.anchors.resize(1);
  ModelOptions model = joiningOptions().deployment.model;
  model.gravity = true;
  RodModel direct(finished, model);
  ASSERT_TRUE(minimiseEnergy(direct, SolverOptions{}).converged);
  double sum = 0.0;
  int count = 0;
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i <= kEdges; ++i, ++count)
      sum += (direct.contactPoint(r, i) - result.last.contactPoints[r][i]).squaredNorm();
  EXPECT_LT(std::sqrt(sum / count), 1e-5);
  EXPECT_GT(-result.last.contactPoints[1][kEdges].z(), 1e-3);  // it did sag as a cantilever
}

TEST(Joining, WithoutSelfWeightThePhasesAreTheJointsAndTheRelease) {
  const TwoPatches patches = twoPatches();
  JoiningOptions options = joiningOptions();
  options.selfWeight = false;
  const DeploymentResult result = joinDeployedPatches(
      patches.joined.network, patches.joined.firstJoin, patches.temporary, options);
  ASSERT_TRUE(result.completed) << result.reason;
  EXPECT_EQ(result.steps.back().t, 2.0);
  // Weightless and straight: nothing moves, nothing is loaded.
  EXPECT_LT(result.steps.back().maxBendingStressPa, 1.0);
}

TEST(Joining, InputsThatDoNotMatchTheNetworkAreNamed) {
  const TwoPatches patches = twoPatches();
  const RodNetwork& network = patches.joined.network;
  EXPECT_THROW(joinDeployedPatches(network, 7, patches.temporary, joiningOptions()), InvalidInput);
  EXPECT_THROW(joinDeployedPatches(network, 0, {true}, joiningOptions()), InvalidInput);
  JoiningOptions bad = joiningOptions();
  bad.minWeightFactor = 1.0;
  EXPECT_THROW(joinDeployedPatches(network, 0, patches.temporary, bad), InvalidInput);
  bad = joiningOptions();
  bad.joinSteps = 0;
  EXPECT_THROW(joinDeployedPatches(network, 0, patches.temporary, bad), InvalidInput);
}

}  // namespace joining_test
}  // namespace egg::rods
