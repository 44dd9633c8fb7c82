// Known answers for the Newton solver on single rods: large-deflection cantilever (elastica
// tables), pinned elastica, a rod rolled into a circle by an end moment, and self-weight.
#include "core/rods/rod_solver.hpp"

#include "core/errors.hpp"
#include "tests/core/rods/rod_test_networks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace egg::rods {
namespace {

// Thin lamella (t/L = 1e-3, so stretching is negligible against bending) along a polyline.
RodNetwork singleRod(const std::vector<Eigen::Vector3d>& polyline,
                     const std::vector<Eigen::Vector3d>& normals, double length) {
  RodNetwork network;
  Rod rod;
  rod.lengthM = length;
  rod.section = {0.01, 0.001};
  rod.material = {10.0e9, 0.6e9, 500.0};
  rod.guess = polyline;
  rod.guessNormals = normals;
  network.rods.push_back(rod);
  return network;
}

RodNetwork straightRod(double length) {
  return singleRod({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(length, 0, 0)},
                   {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()}, length);
}

RodNetwork withShearModulus(RodNetwork network, double g) {
  network.rods[0].material.shearModulusPa = g;
  return network;
}

using testing::edges;

SolverOptions tight() {
  SolverOptions options;
  options.tolerance = 1e-13;
  options.maxIterations = 200;
  return options;
}

// A clamp fixes the first edge; the elastic rod starts at the middle of that edge, so a
// cantilever of free length L is a rod of n edges with h = L / (n - 1/2).
struct Cantilever {
  double freeLength = 1.0;
  int n = 80;
  double h = freeLength / (n - 0.5);
  RodModel model;
  explicit Cantilever(double shearModulus = 0.6e9)
      : model(withShearModulus(straightRod(n * h), shearModulus), edges(n)) {
    model.fixVertex(0, 0);
    model.fixVertex(0, 1);
    model.fixTwist(0, 0);
  }
  Eigen::Vector3d root() const { return 0.5 * (model.vertex(0, 0) + model.vertex(0, 1)); }
  Eigen::Vector3d tip() const { return model.vertex(0, n); }
};

TEST(RodSolver, CantileverTipLoadMatchesElasticaTable) {
  // alpha = P L^2 / EI -> tip deflection v/L (docs/architecture.md "Validation references").
  const std::vector<std::pair<double, double>> table{
      {1.0, 0.30172}, {2.0, 0.49346}, {5.0, 0.71379}, {10.0, 0.81061}};
  for (const auto& [alpha, expected] : table) {
    Cantilever c;
    const double ei = c.model.stiffness(0).bendingWeak;
    c.model.addPointLoad(0, c.n,
                         Eigen::Vector3d(0, 0, -alpha * ei / (c.freeLength * c.freeLength)));
    const SolverResult result = minimiseEnergy(c.model, tight());
    ASSERT_TRUE(result.converged) << result.reason;
    const Eigen::Vector3d d = c.tip() - c.root();
    EXPECT_NEAR(-d.z() / c.freeLength, expected, 0.005 * expected) << "alpha " << alpha;
    if (alpha == 1.0) {
      EXPECT_NEAR(1.0 - d.x() / c.freeLength, 0.05643, 0.005 * 0.05643);
    }
    if (alpha == 2.0) {
      EXPECT_NEAR(1.0 - d.x() / c.freeLength, 0.16064, 0.005 * 0.16064);
    }
  }
}

TEST(RodSolver, PinnedElasticaWithSixtyDegreeEndSlope) {
  // Pinned-pinned elastica, k = sin(30 deg): chord 2E(k)/K(k) - 1 = 0.741050 L,
  // P / P_E = (2 K / pi)^2 = 1.1517, y_max / L = k / K = 0.2966.
  const double length = 1.0, chord = 0.741050;
  const int n = 100;
  std::vector<Eigen::Vector3d> polyline, normals;
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    polyline.emplace_back(chord * s, 0.0, 0.3 * std::sin(M_PI * s));
    const Eigen::Vector3d tangent(chord, 0.0, 0.3 * M_PI * std::cos(M_PI * s));
    normals.push_back(Eigen::Vector3d(-tangent.z(), 0.0, tangent.x()).normalized());
  }
  RodModel model(singleRod(polyline, normals, length), edges(n));
  model.setVertex(0, 0, Eigen::Vector3d::Zero());
  model.setVertex(0, n, Eigen::Vector3d(chord, 0, 0));
  model.fixVertex(0, 0);
  model.fixVertex(0, n);
  model.fixTwist(0, 0);
  const SolverResult result = minimiseEnergy(model, tight());
  ASSERT_TRUE(result.converged) << result.reason;

  Eigen::VectorXd gradient;
  std::vector<Eigen::Triplet<double>> hessian;
  model.derivatives(model.state(), gradient, hessian);
  const double ei = model.stiffness(0).bendingWeak;
  const double eulerLoad = M_PI * M_PI * ei / (length * length);
  const double reaction = std::abs(gradient[model.vertexDof(0, n)]);
  EXPECT_NEAR(reaction / eulerLoad, 1.1517, 0.005 * 1.1517);
  double yMax = 0.0;
  for (int i = 0; i <= n; ++i) yMax = std::max(yMax, std::abs(model.vertex(0, i).z()));
  EXPECT_NEAR(yMax / length, 0.2966, 0.005 * 0.2966);
  const Eigen::Vector3d firstEdge = model.vertex(0, 1) - model.vertex(0, 0);
  EXPECT_NEAR(std::atan2(std::abs(firstEdge.z()), firstEdge.x()), M_PI / 3.0, 0.01 * M_PI / 3.0);
}

TEST(RodSolver, EndMomentRollsTheRodIntoACircle) {
  // G = E / 2.6 keeps the dead end moment well below lateral-torsional buckling
  // (M_cr = pi / 2L sqrt(EI_strong GJ)), near which Newton only converges linearly.
  Cantilever c(10.0e9 / 2.6);
  const double ei = c.model.stiffness(0).bendingWeak;
  c.model.addEndMoment(0, Eigen::Vector3d::UnitY(), 2.0 * M_PI * ei / c.freeLength);
  SolverResult result;
  for (int step = 1; step <= 8; ++step) {  // load stepping: a full turn in eighths
    c.model.setLoadFactor(step / 8.0);
    result = minimiseEnergy(c.model, SolverOptions{});
    ASSERT_TRUE(result.converged) << "step " << step << ": " << result.reason;
  }
  // The tip comes back to the root (to within half an edge: the moment acts on the straight last
  // edge) and every vertex lies on the circle of radius L / 2 pi above or below the root.
  EXPECT_LT((c.tip() - c.root()).norm(), 0.5 * c.h);
  const double radius = c.freeLength / (2.0 * M_PI);
  const double side = c.model.vertex(0, c.n / 2).z() > c.root().z() ? 1.0 : -1.0;
  const Eigen::Vector3d centre = c.root() + Eigen::Vector3d(0, 0, side * radius);
  EXPECT_NEAR(std::abs(c.model.vertex(0, c.n / 2).z() - c.root().z()), 2.0 * radius, 0.01 * radius);
  for (int i = 1; i <= c.n; ++i) {
    EXPECT_NEAR((c.model.vertex(0, i) - centre).norm(), radius, 0.005 * radius) << "vertex " << i;
    EXPECT_NEAR(c.model.vertex(0, i).y(), 0.0, 1e-9);
  }
}

TEST(RodSolver, HorizontalCantileverUnderSelfWeightMatchesBeamTheory) {
  Cantilever c;
  ModelOptions options = edges(c.n);
  options.gravity = true;
  RodNetwork network = straightRod(c.n * c.h);
  network.rods[0].material.densityKgM3 = 0.02;  // light: linear range (tip ~ 5e-4 L)
  RodModel model(network, options);
  model.fixVertex(0, 0);
  model.fixVertex(0, 1);
  model.fixTwist(0, 0);
  const SolverResult result = minimiseEnergy(model, tight());
  ASSERT_TRUE(result.converged) << result.reason;
  const Rod& rod = network.rods[0];
  const double w = rod.material.densityKgM3 * rod.section.widthM * rod.section.thicknessM * 9.81;
  const double expected = w * std::pow(c.freeLength, 4) / (8.0 * model.stiffness(0).bendingWeak);
  const Eigen::Vector3d root = 0.5 * (model.vertex(0, 0) + model.vertex(0, 1));
  const double deflection = root.z() - model.vertex(0, c.n).z();
  EXPECT_LT(expected, 1e-3 * c.freeLength);
  EXPECT_NEAR(deflection, expected, 0.01 * expected);
}

TEST(RodSolver, AStateAlreadyInEquilibriumConvergesAtOnce) {
  // Every unknown held: the gradient over the free unknowns is exactly zero and no descent
  // direction exists; that is equilibrium, not a stall.
  Cantilever c;
  for (int i = 0; i <= c.n; ++i) c.model.fixVertex(0, i);
  for (int j = 0; j < c.n; ++j) c.model.fixTwist(0, j);
  const SolverResult result = minimiseEnergy(c.model, SolverOptions{});
  EXPECT_TRUE(result.converged) << result.reason;
  EXPECT_EQ(result.status, SolverStatus::Converged);
  EXPECT_EQ(result.iterations, 0);
}

TEST(RodSolver, IterationLimitIsReportedWithAReason) {
  Cantilever c;
  c.model.addPointLoad(0, c.n, Eigen::Vector3d(0, 0, -10.0 * c.model.stiffness(0).bendingWeak));
  SolverOptions options;
  options.maxIterations = 2;
  const SolverResult result = minimiseEnergy(c.model, options);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.status, SolverStatus::IterationLimit);
  EXPECT_FALSE(result.reason.empty());
  EXPECT_TRUE(c.model.state().allFinite());
}

// The observer sees the start, every observeEvery-th state a step leaves, and the state returned
// with, each once and in order, and watching does not change the solve. A tip-loaded cantilever
// through the stiffness continuation (several Newton stages, one iteration count).
TEST(RodSolver, ObserverSeesEveryNthIterationAndTheFinalStateOnce) {
  auto loaded = []() {
    auto c = std::make_unique<Cantilever>();
    c->model.addPointLoad(0, c->n, Eigen::Vector3d(0, 0, -2.0 * c->model.stiffness(0).bendingWeak));
    return c;
  };
  auto plain = loaded();
  const SolverResult reference = minimiseEnergy(plain->model, tight());
  ASSERT_TRUE(reference.converged) << reference.reason;
  ASSERT_GE(reference.iterations, 6);  // enough iterations for sampling to matter
  EXPECT_EQ(reference.observations, 0);

  for (int every : {1, 3}) {
    auto watched = loaded();
    SolverOptions options = tight();
    options.observeEvery = every;
    std::vector<SolverProgress> seen;
    std::vector<Eigen::Vector3d> tips;
    options.observer = [&](const SolverProgress& p, const RodModel& m) {
      seen.push_back(p);
      tips.push_back(m.vertex(0, watched->n));
    };
    const SolverResult result = minimiseEnergy(watched->model, options);
    // Bit-identical to the run nobody watched.
    EXPECT_EQ(result.iterations, reference.iterations);
    EXPECT_EQ(result.energy, reference.energy);
    EXPECT_EQ(watched->tip(), plain->tip());
    // Steps leave the states of iterations 0 .. K-1; those divisible by `every`, then the final
    // one.
    const int k = result.iterations;
    const int expected = (k - 1) / every + 1 + 1;
    ASSERT_EQ(static_cast<int>(seen.size()), expected)
        << "every " << every << ", " << k << " iterations";
    EXPECT_EQ(result.observations, expected);
    EXPECT_GE(result.observerSeconds, 0.0);
    for (size_t i = 0; i + 1 < seen.size(); ++i) {
      EXPECT_EQ(seen[i].iteration, static_cast<int>(i) * every);
      EXPECT_FALSE(seen[i].last);
      EXPECT_LE(seen[i].seconds, seen[i + 1].seconds);
    }
    EXPECT_EQ(seen.front().iteration, 0);
    EXPECT_EQ(tips.front(), loaded()->tip());  // the start, before any step
    EXPECT_TRUE(seen.back().last);
    EXPECT_EQ(seen.back().iteration, k);
    EXPECT_EQ(seen.back().energy, result.energy);
    EXPECT_EQ(tips.back(), watched->tip());  // the state returned with
  }
  SolverOptions bad;
  bad.observeEvery = 0;
  EXPECT_THROW(bad.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg::rods
