// The assembled grid energy: exact gradient and Hessian of the whole model (bolts with sliding
// sides, notches, anchors, gravity, point load, end moment) against finite differences.
#include "core/rods/rod_model.hpp"

#include "tests/core/rods/rod_test_networks.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <random>

namespace egg::rods {
namespace {

using testing::crossing;
using testing::edges;
using testing::straight;

TEST(RodModelEnergy, WholeModelDerivativesMatchFiniteDifferences) {
  // Bolts start where the guesses cross, clamped into their notches: both mid-edge here, so the
  // random perturbation keeps beta inside (-eps, 1 + eps).
  RodNetwork network = crossing(0.45, 0.42, Notch{0.2, 0.3});
  network.connections[0].notchB = Notch{0.0, 0.1};
  network.connections[0].sBM = 0.57;
  Anchor anchor;
  anchor.rod = 0;
  anchor.sM = 0.1;
  anchor.position = {0.1, 0.01, 0.02};
  anchor.normal = Eigen::Vector3d(0.1, 0, 1).normalized();
  network.anchors.push_back(anchor);
  ModelOptions options = edges(6);
  options.gravity = true;
  RodModel model(network, options);
  ASSERT_EQ(model.slidingSideCount(), 2);
  model.addEndMoment(1, Eigen::Vector3d::UnitX(), 0.3);
  model.addPointLoad(0, 6, Eigen::Vector3d(0.1, 0.2, -0.3));

  // Loose bolts, then fastened ones (RodModel::fastenBolts: their joint term on top).
  for (const bool fastened : {false, true}) {
    if (fastened) model.fastenBolts();
    // A perturbed state (reference frames stay those of the unperturbed one, as within a step).
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(-0.01, 0.01);
    Eigen::VectorXd z = model.state();
    for (int i = 0; i < z.size(); ++i) z[i] += noise(rng);
    const int n = model.dofCount();
    Eigen::VectorXd gradient;
    std::vector<Eigen::Triplet<double>> triplets;
    const double energy = model.derivatives(z, gradient, triplets, 2);
    EXPECT_NEAR(energy, model.energy(z), 1e-10 * std::abs(energy));
    Eigen::SparseMatrix<double> lower(n, n);
    lower.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::MatrixXd hessian = Eigen::MatrixXd(lower).selfadjointView<Eigen::Lower>();

    const double gradientScale = gradient.cwiseAbs().maxCoeff();
    const double hessianScale = hessian.cwiseAbs().maxCoeff();
    for (int i = 0; i < n; ++i) {
      const double step = 1e-6;
      Eigen::VectorXd plus = z, minus = z;
      plus[i] += step;
      minus[i] -= step;
      const double fd = (model.energy(plus) - model.energy(minus)) / (2.0 * step);
      EXPECT_NEAR(gradient[i], fd, 1e-5 * gradientScale) << "dof " << i;
      Eigen::VectorXd gp, gm;
      model.derivatives(plus, gp, triplets);
      model.derivatives(minus, gm, triplets);
      const Eigen::VectorXd column = (gp - gm) / (2.0 * step);
      for (int j = 0; j < n; ++j) {
        // Round-off in the differenced gradient (entries up to EA/h) limits the attainable
        // accuracy.
        EXPECT_NEAR(hessian(j, i), column[j], 1e-8 * hessianScale + 1e-5 * std::abs(hessian(j, i)))
            << j << "," << i;
      }
    }
  }
}

// The assembly is split into fixed parts reduced in a fixed order: the energy, gradient and
// Hessian triplets are the same bits on 1, 2 or 3 threads (the solver's path, and so its
// iteration count and result, cannot depend on the machine's core count or load).
TEST(RodModelEnergy, DerivativesAreBitIdenticalOnAnyThreadCount) {
  RodNetwork network = crossing(0.45, 0.42, Notch{0.2, 0.3});
  network.rods.push_back(straight({0, 0.3, 0}, {1, 0.3, 0}, 0));
  Connection c;
  c.rodA = 2;
  c.sAM = 0.42;
  c.rodB = 1;
  c.sBM = 0.8;
  c.notchA = Notch{0.1, 0.1};
  network.connections.push_back(c);
  ModelOptions options = edges(9);
  options.gravity = true;
  const RodModel model(network, options);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.01, 0.01);
  Eigen::VectorXd z = model.state();
  for (int i = 0; i < z.size(); ++i) z[i] += noise(rng);
  Eigen::VectorXd g1, g;
  std::vector<Eigen::Triplet<double>> t1, t;
  const double e1 = model.derivatives(z, g1, t1, 1);
  for (int threads : {2, 3}) {
    const double e = model.derivatives(z, g, t, threads);
    EXPECT_EQ(e, e1);
    EXPECT_EQ(g, g1);
    ASSERT_EQ(t.size(), t1.size());
    for (size_t k = 0; k < t.size(); ++k) {
      ASSERT_EQ(t[k].row(), t1[k].row());
      ASSERT_EQ(t[k].col(), t1[k].col());
      ASSERT_EQ(t[k].value(), t1[k].value());
    }
  }
}

}  // namespace
}  // namespace egg::rods
