// Finite-difference checks of the exact (HyperDual) gradients and Hessians of every energy term,
// and closed-form values of bending and twisting for simple configurations.
#include "core/rods/rod_energies.hpp"
#include "core/rods/stretching_derivatives.hpp"

#include "tests/core/rods/rod_test_references.hpp"

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <random>

namespace egg::rods {
namespace {

template <class A>
auto v3(const A& v, int i) {
  using S = std::decay_t<decltype(v[0])>;
  return V3<S>{v[i], v[i + 1], v[i + 2]};
}

// Compares the HyperDual gradient with central differences of the double energy and the
// HyperDual Hessian with central differences of the HyperDual gradient.
template <size_t N, class F>
void expectExactDerivatives(const std::array<double, N>& x, const F& f, double tolerance = 1e-6) {
  using D = HyperDual<static_cast<int>(N)>;
  auto derivatives = [&](const std::array<double, N>& at) {
    std::array<D, N> v;
    for (size_t i = 0; i < N; ++i) v[i] = D::variable(at[i], static_cast<int>(i));
    return f(v);
  };
  const D exact = derivatives(x);
  ASSERT_NEAR(exact.v, f(x), 1e-12 * (1.0 + std::abs(exact.v)));
  const double gradientScale = exact.g.cwiseAbs().maxCoeff() + 1e-12;
  const double hessianScale =
      exact.h.cwiseAbs().maxCoeff() + 1e-12;  // lower triangle holds all values
  for (size_t i = 0; i < N; ++i) {
    const double step = 1e-6 * std::max(1.0, std::abs(x[i]));
    std::array<double, N> plus = x, minus = x;
    plus[i] += step;
    minus[i] -= step;
    const double fd = (f(plus) - f(minus)) / (2.0 * step);
    EXPECT_NEAR(exact.g[i], fd, tolerance * gradientScale) << "gradient entry " << i;
    const D dp = derivatives(plus), dm = derivatives(minus);
    for (size_t j = 0; j < N; ++j) {
      const double fdh = (dp.g[j] - dm.g[j]) / (2.0 * step);
      EXPECT_NEAR(exact.hessian(j, i), fdh, tolerance * hessianScale)
          << "Hessian entry " << j << "," << i;
    }
  }
}

using testing::referenceNear;

const RodStiffness kEnergyStiffness{2.0e4, 3.0, 70.0, 1.7};

TEST(RodEnergies, ParallelTransportMapsFromToAndPreservesAngles) {
  const V3<double> from = constant<double>(Eigen::Vector3d(1, 2, 3).normalized());
  const V3<double> to = constant<double>(Eigen::Vector3d(-2, 1, 0.5).normalized());
  const V3<double> mapped = parallelTransport(from, to, from);
  EXPECT_NEAR(mapped.x, to.x, 1e-14);
  EXPECT_NEAR(mapped.y, to.y, 1e-14);
  EXPECT_NEAR(mapped.z, to.z, 1e-14);
  const V3<double> u = constant<double>(Eigen::Vector3d(0.3, -0.7, 0.2));
  const V3<double> pu = parallelTransport(from, to, u);
  EXPECT_NEAR(norm(pu), norm(u), 1e-14);
  EXPECT_NEAR(dot(pu, to), dot(u, from), 1e-14);
}

TEST(RodEnergies, StretchingGradientAndHessianMatchFiniteDifferences) {
  const std::array<double, 6> x{0.1, -0.2, 0.3, 1.2, 0.4, -0.1};
  expectExactDerivatives(
      x, [](const auto& v) { return stretchingEnergy(v3(v, 0), v3(v, 3), 5.0e3, 0.9); });
}

// The closed form the derivative pass uses, against the HyperDual<6> evaluation of the same
// energy (exact forward-mode AD), stretched and compressed.
TEST(RodEnergies, StretchingClosedFormMatchesHyperDual) {
  for (const double scale : {1.3, 0.7}) {
    const Eigen::Vector3d x0(0.1, -0.2, 0.3), x1 = x0 + scale * Eigen::Vector3d(0.8, 0.5, -0.3);
    const StretchingDerivatives d = stretchingDerivatives(x0, x1, 5.0e3, 0.9);
    using D = HyperDual<6>;
    std::array<D, 6> v;
    for (int i = 0; i < 6; ++i) v[i] = D::variable(i < 3 ? x0[i] : x1[i - 3], i);
    const D a = stretchingEnergy(v3(v, 0), v3(v, 3), 5.0e3, 0.9);
    EXPECT_NEAR(d.energy, a.v, 1e-13 * a.v);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(d.gradient[i], a.g[i], 1e-12 * a.g.cwiseAbs().maxCoeff());
      for (int j = 0; j < 6; ++j)
        EXPECT_NEAR(d.hessian(i, j), a.hessian(i, j), 1e-12 * 5.0e3 / 0.9) << i << " " << j;
    }
  }
}

// The projected fallback's stretching Hessian (rod_solver.hpp): the nearest positive
// semidefinite matrix, here in closed form, equals the eigen-projection (negative eigenvalues set
// to zero) of the exact Hessian; a stretched edge's Hessian is semidefinite and stays as it is.
TEST(RodEnergies, StretchingProjectedHessianIsTheNearestSemidefiniteOne) {
  for (const double scale : {1.3, 0.7}) {
    const Eigen::Vector3d x0(0.1, -0.2, 0.3), x1 = x0 + scale * Eigen::Vector3d(0.8, 0.5, -0.3);
    const StretchingDerivatives exact = stretchingDerivatives(x0, x1, 5.0e3, 0.9);
    const StretchingDerivatives projected = stretchingDerivatives(x0, x1, 5.0e3, 0.9, true);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(exact.hessian);
    const Eigen::Matrix<double, 6, 6> nearest = eigen.eigenvectors() *
                                                eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                                eigen.eigenvectors().transpose();
    EXPECT_EQ(eigen.eigenvalues().minCoeff() < -1.0, scale < 1.0);  // compressed: indefinite
    EXPECT_LT((projected.hessian - nearest).cwiseAbs().maxCoeff(), 1e-9 * 5.0e3 / 0.9);
    EXPECT_EQ(projected.energy, exact.energy);
    EXPECT_EQ(projected.gradient, exact.gradient);
    if (scale > 1.0) EXPECT_EQ(projected.hessian, exact.hessian);
  }
}

TEST(RodEnergies, BendTwistGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (int trial = 0; trial < 5; ++trial) {
    std::array<double, 11> x{0.0 + u(rng), u(rng),       u(rng), 1.0 + u(rng), u(rng), u(rng),
                             2.0 + u(rng), 0.5 + u(rng), u(rng), u(rng),       u(rng)};
    const EdgeReference r0 =
        referenceNear(Eigen::Vector3d(x[3] - x[0], x[4] - x[1], x[5] - x[2]), rng);
    const EdgeReference r1 =
        referenceNear(Eigen::Vector3d(x[6] - x[3], x[7] - x[4], x[8] - x[5]), rng);
    expectExactDerivatives(x, [&](const auto& v) {
      return bendTwistEnergy(v3(v, 0), v3(v, 3), v3(v, 6), v[9], v[10], r0, r1, kEnergyStiffness,
                             1.1);
    });
  }
}

TEST(RodEnergies, BendingOfAKinkMatchesTwoTanHalfAngleAboutEachAxis) {
  // Edges of length 1 turning by phi: |kappa b| = 2 tan(phi/2); energy EI kappa^2 / (2 l).
  const double phi = 0.4, l = 1.0;
  const double kappa = 2.0 * std::tan(phi / 2.0);
  const EdgeReference r0{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  const Eigen::Vector3d t1(std::cos(phi), 0.0, std::sin(phi));
  const EdgeReference r1{t1, Eigen::Vector3d(-std::sin(phi), 0.0, std::cos(phi))};
  const V3<double> x0{0, 0, 0}, x1{1, 0, 0}, x2{1 + t1.x(), 0, t1.z()};
  // Turning towards the normal m1 = z: weak-axis bending.
  EXPECT_NEAR(bendTwistEnergy(x0, x1, x2, 0.0, 0.0, r0, r1, kEnergyStiffness, l),
              0.5 * kEnergyStiffness.bendingWeak * kappa * kappa / l, 1e-12);
  // Same kink with the lamella normal along y (theta = -pi/2 rotates m1 from z to y): strong axis.
  const double quarter = -M_PI / 2.0;
  EXPECT_NEAR(bendTwistEnergy(x0, x1, x2, quarter, quarter, r0, r1, kEnergyStiffness, l),
              0.5 * kEnergyStiffness.bendingStrong * kappa * kappa / l, 1e-9);
}

TEST(RodEnergies, TwistOfAStraightRodIsTheAngleDifference) {
  const EdgeReference r{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  const V3<double> x0{0, 0, 0}, x1{1, 0, 0}, x2{2, 0, 0};
  const double twist = 0.3, l = 0.8;
  EXPECT_NEAR(bendTwistEnergy(x0, x1, x2, 0.1, 0.1 + twist, r, r, kEnergyStiffness, l),
              0.5 * kEnergyStiffness.twisting * twist * twist / l, 1e-14);
}

TEST(RodEnergies, ConnectionGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  const std::array<double, 16> x{0,          0,      0,
                                 1 + u(rng), u(rng), u(rng),
                                 u(rng),     0.4,    0.5 + u(rng),
                                 -0.5,       0.05,   0.4 + u(rng),
                                 0.6,        0.1,    u(rng),
                                 0.6};
  const EdgeReference rg =
      referenceNear(Eigen::Vector3d(x[3] - x[0], x[4] - x[1], x[5] - x[2]), rng);
  const EdgeReference rh =
      referenceNear(Eigen::Vector3d(x[11] - x[8], x[12] - x[9], x[13] - x[10]), rng);
  expectExactDerivatives(x, [&](const auto& v) {
    return connectionEnergy(v3(v, 0), v3(v, 3), v[6], v[7], rg, v3(v, 8), v3(v, 11), v[14], v[15],
                            rh, 0.04, 1.0e3, 20.0);
  });
}

TEST(RodEnergies, ConnectionIsZeroForStackedRodsWithParallelNormals) {
  const EdgeReference rg{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  const EdgeReference rh{Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const double t = 0.04;
  // Lower rod along x through the origin, upper rod along y, one thickness above the crossing.
  const V3<double> g0{-1, 0, 0}, g1{1, 0, 0}, h0{0, -1, t}, h1{0, 1, t};
  EXPECT_NEAR(connectionEnergy(g0, g1, 0.0, 0.5, rg, h0, h1, 0.0, 0.5, rh, t, 1e6, 1e3), 0.0,
              1e-20);
  // Moving the bolt along the upper rod by 0.1 (beta 0.55) costs 2 lambda 0.1^2.
  EXPECT_NEAR(connectionEnergy(g0, g1, 0.0, 0.5, rg, h0, h1, 0.0, 0.55, rh, t, 1e6, 1e3),
              2e6 * 0.01, 1e-6);
}

TEST(RodEnergies, FastenedJointGradientAndHessianMatchFiniteDifferences) {
  const std::array<double, 12> x{0.1, 0.0, 0.05, 1.1, 0.2, -0.1, 0.4, -0.6, 0.1, 0.7, 0.5, 0.0};
  expectExactDerivatives(x, [&](const auto& v) {
    return fastenedJointEnergy(v3(v, 0), v3(v, 3), v3(v, 6), v3(v, 9), std::cos(1.2), std::sin(1.2),
                               Eigen::Vector3d(0.0, 0.6, 0.8), 40.0);
  });
}

// The joints between two patches hold parallel lamellas (crossing angle 0): there the energy
// must be smooth. With the unsigned sine |e_g x e_h| its second derivative across alpha = 0 jumped
// from -2 weight to +2 weight (a cusp), which made Newton shift-bound on the joined structure.
TEST(RodEnergies, FastenedJointIsSmoothAcrossParallelLamellas) {
  const double weight = 3.0;
  const V3<double> g0{0, 0, 0}, g1{1, 0, 0}, h0{0, 0, 0.04};
  auto energy = [&](double alpha) {
    const V3<double> h1{h0.x + std::cos(alpha), h0.y + std::sin(alpha), h0.z};
    return fastenedJointEnergy(g0, g1, h0, h1, 1.0, 0.0, Eigen::Vector3d::UnitZ(), weight);
  };
  // Central second differences on both sides of 0 and at 0: 2 weight cos(alpha) everywhere.
  const double d = 1e-3;
  for (double alpha : {-0.01, 0.0, 0.01}) {
    const double second = (energy(alpha + d) - 2.0 * energy(alpha) + energy(alpha - d)) / (d * d);
    EXPECT_NEAR(second, 2.0 * weight * std::cos(alpha), 1e-5) << alpha;
  }
  const std::array<double, 12> x{0, 0, 0, 1, 0, 0, 0, 0, 0.04, 1, 1e-9, 0.04};
  expectExactDerivatives(x, [&](const auto& v) {
    return fastenedJointEnergy(v3(v, 0), v3(v, 3), v3(v, 6), v3(v, 9), 1.0, 0.0,
                               Eigen::Vector3d::UnitZ(), weight);
  });
}

TEST(RodEnergies, FastenedJointCostsTwoWeightOneMinusCosOfTheAngleTurned) {
  // Fastened at 1.1 rad between two edges in the xy plane; the upper one turned by delta (and
  // lengthened, which changes nothing): (cos - cos0)^2 + (sin - sin0)^2 = 2 (1 - cos delta).
  const double alpha0 = 1.1, weight = 7.0;
  const V3<double> g0{0, 0, 0}, g1{0.5, 0, 0}, h0{0.2, 0.1, 0.04};
  for (double delta : {0.0, 1e-3, 0.05, 0.4, -0.3}) {
    const double a = alpha0 + delta;
    const V3<double> h1{h0.x + 2.0 * std::cos(a), h0.y + 2.0 * std::sin(a), h0.z};
    EXPECT_NEAR(fastenedJointEnergy(g0, g1, h0, h1, std::cos(alpha0), std::sin(alpha0),
                                    Eigen::Vector3d::UnitZ(), weight),
                2.0 * weight * (1.0 - std::cos(delta)), 1e-12)
        << delta;
  }
}

TEST(RodEnergies, AnchorGradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(5);
  const std::array<double, 7> x{0.1, 0.2, -0.1, 0.9, 0.3, 0.2, 0.3};
  const EdgeReference r = referenceNear(Eigen::Vector3d(0.8, 0.1, 0.3), rng);
  expectExactDerivatives(x, [&](const auto& v) {
    return anchorEnergy(v3(v, 0), v3(v, 3), v[6], 0.3, r, Eigen::Vector3d(0.5, 0.1, 0.2),
                        Eigen::Vector3d(0, 0.6, 0.8), 500.0, 30.0);
  });
}

TEST(RodEnergies, SliderGradientAndHessianMatchFiniteDifferencesNearNotchEnds) {
  SliderParameters p;
  p.edgeStart = 2.0;
  p.edgeLength = 0.5;
  p.notchMin = 1.8;  // 0.4 edge lengths before the edge: lower barrier active
  p.notchMax = 2.3;  // inside the edge: upper barrier active
  p.unit = 3.0;
  for (double beta : {0.05, 0.3, 0.55}) {
    expectExactDerivatives(
        std::array<double, 1>{beta}, [&](const auto& v) { return sliderEnergy(v[0], p); }, 1e-5);
  }
  EXPECT_TRUE(std::isinf(sliderEnergy(0.61, p)));  // past the notch end at beta = 0.6
  EXPECT_TRUE(
      std::isinf(sliderEnergy(-0.001, SliderParameters{})));  // more than epsilon before the edge
}

TEST(RodEnergies, SliderFrictionMatchesTheThesisFormula) {
  SliderParameters p;  // notch far away: only E_p
  p.edgeStart = 10.0;
  p.edgeLength = 1.0;
  p.notchMin = 0.0;
  p.notchMax = 20.0;
  const double beta = 0.3;
  const double expected =
      std::pow(0.1 * std::log(1e-4 + beta), 2) + std::pow(0.1 * std::log(1e-4 + 1 - beta), 2);
  EXPECT_NEAR(sliderEnergy(beta, p), expected, 1e-15);
}

TEST(RodEnergies, EndMomentGradientAndHessianMatchFiniteDifferences) {
  const std::array<double, 6> x{0.1, 0.2, 0.0, 0.7, 0.9, 0.1};
  expectExactDerivatives(x, [](const auto& v) {
    return endMomentPotential(v3(v, 0), v3(v, 3), Eigen::Vector3d::UnitZ(), 2.5,
                              Eigen::Vector3d::UnitX(), 6.0);
  });
}

}  // namespace
}  // namespace egg::rods
