// The closed-form connection derivatives against the HyperDual<16> evaluation of the same energy
// (the reference: exact forward-mode AD of connectionEnergy with the frames differentiated in
// place) and against finite differences.
#include "core/rods/connection_derivatives.hpp"

#include "tests/core/rods/rod_test_references.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace egg::rods {
namespace {

using testing::referenceNear;

// Variables as in the model's bolt stencil: g0, g1, theta_g, beta_g, h0, h1, theta_h, beta_h.
struct Bolt {
  std::array<double, 16> x;
  EdgeReference rg, rh;
};

Bolt randomBolt(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Bolt b;
  b.x = {u(rng),       u(rng), u(rng), 1 + u(rng),   u(rng), u(rng), u(rng), 0.4 + u(rng),
         0.5 + u(rng), -0.5,   0.05,   0.4 + u(rng), 0.6,    0.1,    u(rng), 0.6 + u(rng)};
  b.rg = referenceNear(Eigen::Vector3d(b.x[3] - b.x[0], b.x[4] - b.x[1], b.x[5] - b.x[2]), rng);
  b.rh = referenceNear(Eigen::Vector3d(b.x[11] - b.x[8], b.x[12] - b.x[9], b.x[13] - b.x[10]), rng);
  return b;
}

constexpr double kOffset = 0.04, kPosition = 1.0e3, kAngle = 20.0;

ConnectionDerivatives closedForm(const Bolt& b) {
  auto at = [&](int i) { return Eigen::Vector3d(b.x[i], b.x[i + 1], b.x[i + 2]); };
  return connectionDerivatives(
      at(0), at(3), edgeFrameDerivatives(at(3) - at(0), b.x[6], b.rg), b.x[7], at(8), at(11),
      edgeFrameDerivatives(at(11) - at(8), b.x[14], b.rh), b.x[15], kOffset, kPosition, kAngle);
}

template <class S, class A>
S energyOf(const A& v, const Bolt& b) {
  auto p = [&](int i) { return V3<S>{v[i], v[i + 1], v[i + 2]}; };
  return connectionEnergy(p(0), p(3), v[6], v[7], b.rg, p(8), p(11), v[14], v[15], b.rh, kOffset,
                          kPosition, kAngle);
}

TEST(ConnectionDerivatives, MatchHyperDualOnRandomBolts) {
  std::mt19937 rng(41);
  for (int trial = 0; trial < 20; ++trial) {
    const Bolt b = randomBolt(rng);
    using D = HyperDual<16>;
    std::array<D, 16> v;
    for (int i = 0; i < 16; ++i) v[i] = D::variable(b.x[i], i);
    const D reference = energyOf<D>(v, b);
    const ConnectionDerivatives d = closedForm(b);
    EXPECT_NEAR(d.energy, reference.v, 1e-12 * std::abs(reference.v));
    const double gradientScale = reference.g.cwiseAbs().maxCoeff();
    double hessianScale = 0.0;
    for (int i = 0; i < 16; ++i) {
      for (int j = 0; j <= i; ++j)
        hessianScale = std::max(hessianScale, std::abs(reference.hessian(i, j)));
    }
    ASSERT_GT(gradientScale, 0.0);
    for (int i = 0; i < 16; ++i) {
      EXPECT_NEAR(d.gradient[i], reference.g[i], 1e-9 * gradientScale) << "gradient " << i;
      for (int j = 0; j < 16; ++j) {
        EXPECT_NEAR(d.hessian(i, j), reference.hessian(i, j), 1e-9 * hessianScale)
            << "Hessian " << i << "," << j;
      }
    }
  }
}

TEST(ConnectionDerivatives, MatchFiniteDifferences) {
  std::mt19937 rng(43);
  for (int trial = 0; trial < 3; ++trial) {
    const Bolt b = randomBolt(rng);
    const ConnectionDerivatives d = closedForm(b);
    EXPECT_NEAR(d.energy, energyOf<double>(b.x, b), 1e-12 * d.energy);
    const double gradientScale = d.gradient.cwiseAbs().maxCoeff();
    const double hessianScale = d.hessian.cwiseAbs().maxCoeff();
    for (int i = 0; i < 16; ++i) {
      const double step = 1e-6;
      Bolt plus = b, minus = b;
      plus.x[i] += step;
      minus.x[i] -= step;
      const double fd = (energyOf<double>(plus.x, b) - energyOf<double>(minus.x, b)) / (2.0 * step);
      EXPECT_NEAR(d.gradient[i], fd, 1e-6 * gradientScale) << i;
      const Eigen::Matrix<double, 16, 1> column =
          (closedForm(plus).gradient - closedForm(minus).gradient) / (2.0 * step);
      for (int j = 0; j < 16; ++j)
        EXPECT_NEAR(d.hessian(j, i), column[j], 1e-6 * hessianScale) << j << "," << i;
    }
  }
}

TEST(ConnectionDerivatives, VanishForStackedRodsWithParallelNormals) {
  // Lower rod along x, upper along y one offset above the crossing, normals both +z: E = 0, grad 0.
  const EdgeReference rg{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  const EdgeReference rh{Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const Eigen::Vector3d g0(-1, 0, 0), g1(1, 0, 0), h0(0, -1, kOffset), h1(0, 1, kOffset);
  const ConnectionDerivatives d = connectionDerivatives(
      g0, g1, edgeFrameDerivatives(g1 - g0, 0.0, rg), 0.5, h0, h1,
      edgeFrameDerivatives(h1 - h0, 0.0, rh), 0.5, kOffset, kPosition, kAngle);
  EXPECT_NEAR(d.energy, 0.0, 1e-20);
  EXPECT_LT(d.gradient.cwiseAbs().maxCoeff(), 1e-12);
  // Moving the upper bolt point along y costs 2 w dy^2: d^2E/d beta_h^2 = 4 w |h1 - h0|^2.
  EXPECT_NEAR(d.hessian(15, 15), 4.0 * kPosition * 4.0, 1e-9);
}

}  // namespace
}  // namespace egg::rods
