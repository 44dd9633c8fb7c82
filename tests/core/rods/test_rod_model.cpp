// The discretised grid: sliding bolts settle where the sliding force vanishes (reprojection
// across edges); notch limits hold bolts in their slots; anchors place rods on their supports.
#include "core/rods/rod_model.hpp"
#include "core/rods/rod_solver.hpp"

#include "core/errors.hpp"

#include "tests/core/rods/rod_test_networks.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>

namespace egg::rods {
namespace {

using testing::crossing;
using testing::edges;
using testing::straight;

// The guesses cross at s = 0.5 on rod 0, where the bolt was drilled and where it starts; then
// rod 1 is moved to x = 0.3 and held fixed, rod 0 pinned at the origin. With a notch reaching
// s = 0.3 the bolt slides there, where rod 0 is straight and the sliding force is zero.
struct SlidingCase {
  RodModel model;
  explicit SlidingCase(Notch notch, bool notches = true, double mu = 0.1)
      : model(crossing(0.5, 0.5, notch), [&] {
          ModelOptions o = edges(20);
          o.notches = notches;
          o.frictionMu = mu;
          return o;
        }()) {
    for (int i = 0; i < model.vertexCount(1); ++i) {
      model.setVertex(1, i, model.vertex(1, i) - Eigen::Vector3d(0.2, 0, 0));
      model.fixVertex(1, i);
    }
    for (int j = 0; j + 1 < model.vertexCount(1); ++j) model.fixTwist(1, j);
    model.fixVertex(0, 0);
  }
};

TEST(RodModel, SlidingBoltSettlesWhereTheSlidingForceVanishes) {
  for (double mu : {0.1, 0.01}) {
    SlidingCase c(Notch{0.3, 0.1}, true, mu);
    const SolverResult result = minimiseEnergy(c.model, SolverOptions{});
    ASSERT_TRUE(result.converged) << result.reason;
    EXPECT_GE(result.boltEdgeSwitches, 3);  // from s = 0.5 to 0.3 over edges of 0.05
    EXPECT_NEAR(c.model.boltPosition(0, 0), 0.3, 1e-3) << "mu " << mu;
    // Rod 0 ends up straight along x (its far end at x = 1), one thickness below rod 1.
    EXPECT_NEAR(c.model.vertex(0, 20).x(), 1.0, 1e-3);
    EXPECT_NEAR(c.model.vertex(0, 10).z(), -0.001, 5e-4);  // friction leaves a little compression
  }
}

TEST(RodModel, SlidingSolveIsBitIdenticalOnOneAndTwoThreads) {
  // Two threads assemble in fixed parts and factorise two trial shifts at once, taking the same
  // shift as one after the other: the whole solve, bolt edge switches (new patterns, new symbolic
  // analyses) included, must not depend on the thread count.
  SlidingCase one(Notch{0.3, 0.1}), two(Notch{0.3, 0.1});
  SolverOptions single, dual;
  single.threads = 1;
  dual.threads = 2;
  const SolverResult a = minimiseEnergy(one.model, single), b = minimiseEnergy(two.model, dual);
  ASSERT_TRUE(a.converged) << a.reason;
  ASSERT_TRUE(b.converged) << b.reason;
  EXPECT_GE(a.boltEdgeSwitches, 3);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_EQ(a.boltEdgeSwitches, b.boltEdgeSwitches);
  EXPECT_EQ(one.model.boltPosition(0, 0), two.model.boltPosition(0, 0));
  for (int i = 0; i < one.model.vertexCount(0); ++i)
    EXPECT_EQ(one.model.vertex(0, i), two.model.vertex(0, i)) << i;
}

TEST(RodModel, NotchLimitHoldsTheBoltInItsSlot) {
  SlidingCase c(Notch{0.1, 0.1});  // slot [0.4, 0.6]: cannot reach 0.3
  const SolverResult result = minimiseEnergy(c.model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;
  const double s = c.model.boltPosition(0, 0);
  EXPECT_GT(s, 0.4);
  EXPECT_LT(s, 0.41);
}

// Rod 0, held only by the bolt, pulled along its axis by 10 N at its start: it slides until the
// bolt reaches the notch end, which then takes the whole pull (the tension keeps the rod straight
// and stable about the bolt).
TEST(RodModel, NotchEndForceIsThePullTheNotchEndHolds) {
  ModelOptions options = edges(20);
  options.frictionMu = 0.01;
  // Slot [0.4, 0.625]: its end mid-edge, where pseudo-friction does not push.
  RodModel model(crossing(0.5, 0.5, Notch{0.1, 0.125}), options);
  for (int i = 0; i < model.vertexCount(1); ++i) model.fixVertex(1, i);
  for (int j = 0; j + 1 < model.vertexCount(1); ++j) model.fixTwist(1, j);
  model.addPointLoad(0, 0, Eigen::Vector3d(-10.0, 0.0, 0.0));
  const SolverResult result = minimiseEnergy(model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_GT(model.boltPosition(0, 0), 0.62);
  EXPECT_NEAR(model.notchEndForce(0, 0), 10.0, 0.05);
  EXPECT_EQ(model.notchEndForce(0, 1), 0.0);  // rod 1's hole is plain
}

// A notch shorter than two edges keeps the bolt within one edge of both ends; unloaded, the bolt
// presses on neither (each barrier alone pushes with thousands of newtons there). The bolt sits
// mid-edge, where pseudo-friction does not push either.
TEST(RodModel, NotchEndForceOfAnUnloadedBoltInAShortNotchIsZero) {
  RodModel model(crossing(0.525, 0.525, Notch{0.001, 0.001}), edges(20));
  model.fixVertex(1, 0);
  model.fixVertex(0, 0);
  const SolverResult result = minimiseEnergy(model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_NEAR(model.boltPosition(0, 0), 0.525, 1e-6);
  EXPECT_LT(model.notchEndForce(0, 0), 1e-6);
}

TEST(RodModel, PlainHoleKeepsTheBoltWhereItWasDrilled) {
  SlidingCase c(Notch{0.3, 0.1}, /*notches=*/false);
  EXPECT_EQ(c.model.slidingSideCount(), 0);
  const SolverResult result = minimiseEnergy(c.model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_DOUBLE_EQ(c.model.boltPosition(0, 0), 0.5);
  // The bolt point of rod 0 (s = 0.5) sits under the crossing at x = 0.3: rod 0 buckled.
  const Eigen::Vector3d bolt = c.model.vertex(0, 10);
  EXPECT_NEAR(bolt.x(), 0.3, 1e-3);
  EXPECT_NEAR(bolt.y(), 0.0, 1e-3);
}

TEST(RodModel, AnchorsPlaceTheRodHalfAThicknessOffTheSurface) {
  RodNetwork network;
  network.rods.push_back(straight({0, 0, 0}, {1, 0.2, 0}, 1));  // guess off the anchors
  network.rods[0].lengthM = 1.0;
  for (double s : {0.0, 1.0}) {
    Anchor a;
    a.rod = 0;
    a.sM = s;
    a.position = {s, 0, 0};
    a.normal = Eigen::Vector3d::UnitZ();
    network.anchors.push_back(a);
  }
  RodModel model(network, edges(10));
  const SolverResult result = minimiseEnergy(model, SolverOptions{});
  ASSERT_TRUE(result.converged) << result.reason;
  for (int i = 0; i <= 10; ++i) {
    const Eigen::Vector3d p = model.vertex(0, i);
    EXPECT_NEAR(p.x(), i / 10.0, 1e-6);
    EXPECT_NEAR(p.y(), 0.0, 1e-6);
    EXPECT_NEAR(p.z(), 0.001, 1e-6);  // layer 1: t/2 above the surface
  }
  EXPECT_NEAR(model.edgeNormal(0, 4).z(), 1.0, 1e-9);
}

TEST(RodModel, InvalidInputNamesTheField) {
  RodNetwork network = crossing(0.5, 0.3, Notch{0.6, 0.0});  // notch runs past the rod start
  EXPECT_THROW(RodModel(network, ModelOptions{}), InvalidInput);
  network = crossing(0.5, 0.3, Notch{});
  network.rods[1].layer = 0;
  EXPECT_THROW(RodModel(network, ModelOptions{}), InvalidInput);
  ModelOptions bad;
  bad.frictionEpsilon = 0.0;
  EXPECT_THROW(bad.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg::rods
