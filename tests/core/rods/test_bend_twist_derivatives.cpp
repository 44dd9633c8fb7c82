// The closed-form bending/twisting derivatives against the HyperDual<8> evaluation of the same
// energy (the reference: exact forward-mode AD of bendTwistEnergyOfEdges) and against finite
// differences.
#include "core/rods/bend_twist_derivatives.hpp"

#include "tests/core/rods/rod_test_references.hpp"

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <random>

namespace egg::rods {
namespace {

const RodStiffness kStiffness{2.0e4, 3.0, 70.0, 1.7};

struct Stencil {
  Eigen::Vector3d e0, e1;
  double theta0 = 0.0, theta1 = 0.0;
  EdgeReference r0, r1;
};

using testing::referenceNear;

Stencil randomStencil(std::mt19937& rng, double bend, double thetaSpread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Stencil s;
  s.e0 = Eigen::Vector3d(1.0 + 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
  s.e1 = Eigen::Vector3d(0.8 + 0.3 * u(rng), bend * u(rng), bend * u(rng));
  s.theta0 = thetaSpread * u(rng);
  s.theta1 = thetaSpread * u(rng);
  s.r0 = referenceNear(s.e0, rng, 0.2);
  s.r1 = referenceNear(s.e1, rng, 0.2);
  return s;
}

BendTwistDerivatives closedForm(const Stencil& s, double voronoiLength) {
  return bendTwistDerivatives(edgeFrameDerivatives(s.e0, s.theta0, s.r0),
                              edgeFrameDerivatives(s.e1, s.theta1, s.r1), kStiffness,
                              voronoiLength);
}

// The reference: HyperDual<8> over (e0, e1, theta0, theta1), frames differentiated in place.
HyperDual<8> automatic(const Stencil& s, double voronoiLength) {
  using D = HyperDual<8>;
  const V3<D> e0{D::variable(s.e0.x(), 0), D::variable(s.e0.y(), 1), D::variable(s.e0.z(), 2)};
  const V3<D> e1{D::variable(s.e1.x(), 3), D::variable(s.e1.y(), 4), D::variable(s.e1.z(), 5)};
  const D theta0 = D::variable(s.theta0, 6), theta1 = D::variable(s.theta1, 7);
  return bendTwistEnergyOfEdges(e0, e1, materialFrame(e0, theta0, s.r0),
                                materialFrame(e1, theta1, s.r1), kStiffness, voronoiLength);
}

double energyAt(const Stencil& s, double voronoiLength) {
  const V3<double> e0 = constant<double>(s.e0), e1 = constant<double>(s.e1);
  return bendTwistEnergyOfEdges(e0, e1, materialFrame(e0, s.theta0, s.r0),
                                materialFrame(e1, s.theta1, s.r1), kStiffness, voronoiLength);
}

Stencil moved(const Stencil& s, int variable, double step) {
  Stencil m = s;
  if (variable < 3)
    m.e0[variable] += step;
  else if (variable < 6)
    m.e1[variable - 3] += step;
  else if (variable == 6)
    m.theta0 += step;
  else
    m.theta1 += step;
  return m;
}

void expectMatchesAutomatic(const Stencil& s, double voronoiLength) {
  const BendTwistDerivatives d = closedForm(s, voronoiLength);
  const HyperDual<8> a = automatic(s, voronoiLength);
  EXPECT_NEAR(d.energy, a.v, 1e-12 * std::abs(a.v));
  const double gradientScale = a.g.cwiseAbs().maxCoeff();
  double hessianScale = 0.0;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j <= i; ++j) hessianScale = std::max(hessianScale, std::abs(a.hessian(i, j)));
  }
  ASSERT_GT(gradientScale, 0.0);
  ASSERT_GT(hessianScale, 0.0);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(d.gradient[i], a.g[i], 1e-9 * gradientScale) << "gradient " << i;
    for (int j = 0; j < 8; ++j) {
      EXPECT_NEAR(d.hessian(i, j), a.hessian(i, j), 1e-9 * hessianScale)
          << "Hessian " << i << "," << j;
    }
  }
}

void expectSame(const HyperDual<4>& a, const HyperDual<4>& b, const char* what) {
  EXPECT_NEAR(a.v, b.v, 1e-14) << what;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(a.g[i], b.g[i], 1e-12) << what << " gradient " << i;
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(a.hessian(i, j), b.hessian(i, j), 1e-12) << what << " " << i << "," << j;
  }
}

TEST(BendTwistDerivatives, EdgeFramesMatchHyperDualOfTheMaterialFrame) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Stencil s = randomStencil(rng, 0.5, 3.0);
    using D = HyperDual<4>;
    const V3<D> e{D::variable(s.e1.x(), 0), D::variable(s.e1.y(), 1), D::variable(s.e1.z(), 2)};
    V3<D> director;
    const Frame<D> reference = materialFrame(e, D::variable(s.theta1, 3), s.r1, &director);
    const EdgeFrameDerivatives f = edgeFrameDerivatives(s.e1, s.theta1, s.r1);
    const V3<D>* expected[3] = {&reference.tangent, &reference.normal, &reference.side};
    const V3<D>* actual[3] = {&f.frame.tangent, &f.frame.normal, &f.frame.side};
    for (int k = 0; k < 3; ++k) {
      expectSame(actual[k]->x, expected[k]->x, "x");
      expectSame(actual[k]->y, expected[k]->y, "y");
      expectSame(actual[k]->z, expected[k]->z, "z");
    }
    // The edge-vector-only quantities: t, u and t x u (no theta dependence).
    const V3<D> binormal = cross(reference.tangent, director);
    const V3<D>* expectedEdge[3] = {&reference.tangent, &director, &binormal};
    const V3<HyperDual<3>>* actualEdge[3] = {&f.tangent, &f.director, &f.binormal};
    for (int k = 0; k < 3; ++k) {
      const HyperDual<4>* e[3] = {&expectedEdge[k]->x, &expectedEdge[k]->y, &expectedEdge[k]->z};
      const HyperDual<3>* a[3] = {&actualEdge[k]->x, &actualEdge[k]->y, &actualEdge[k]->z};
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(a[c]->v, e[c]->v, 1e-14);
        EXPECT_NEAR(e[c]->g[3], 0.0, 1e-14);
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(a[c]->g[i], e[c]->g[i], 1e-12);
          for (int j = 0; j < 3; ++j) EXPECT_NEAR(a[c]->hessian(i, j), e[c]->hessian(i, j), 1e-12);
        }
      }
    }
  }
}

TEST(BendTwistDerivatives, MatchHyperDualOnRandomStencils) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 40; ++trial)
    expectMatchesAutomatic(randomStencil(rng, 0.5, 1.0), 0.9);
}

TEST(BendTwistDerivatives, MatchHyperDualNearlyStraightAndStronglyTwisted) {
  std::mt19937 rng(23);
  // Nearly straight (the converged grids) and twists up to ~3 rad (value from atan2 wraps there).
  for (int trial = 0; trial < 20; ++trial)
    expectMatchesAutomatic(randomStencil(rng, 1e-3, 1.4), 1.3);
}

TEST(BendTwistDerivatives, OnVerticesMatchHyperDualOverTheVertices) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 10; ++trial) {
    const Stencil s = randomStencil(rng, 0.5, 1.0);
    const Eigen::Vector3d x0(0.3, -0.2, 0.1), x1 = x0 + s.e0, x2 = x1 + s.e1;
    using D = HyperDual<11>;
    std::array<D, 11> v;
    const double values[11] = {x0.x(), x0.y(), x0.z(), x1.x(),   x1.y(),  x1.z(),
                               x2.x(), x2.y(), x2.z(), s.theta0, s.theta1};
    for (int i = 0; i < 11; ++i) v[i] = D::variable(values[i], i);
    const D reference =
        bendTwistEnergy(V3<D>{v[0], v[1], v[2]}, V3<D>{v[3], v[4], v[5]}, V3<D>{v[6], v[7], v[8]},
                        v[9], v[10], s.r0, s.r1, kStiffness, 0.9);
    const BendTwistVertexDerivatives d = onVertices(closedForm(s, 0.9));
    EXPECT_NEAR(d.energy, reference.v, 1e-12 * std::abs(reference.v));
    const double gradientScale = reference.g.cwiseAbs().maxCoeff();
    double hessianScale = 0.0;
    for (int i = 0; i < 11; ++i) {
      for (int j = 0; j <= i; ++j)
        hessianScale = std::max(hessianScale, std::abs(reference.hessian(i, j)));
    }
    for (int i = 0; i < 11; ++i) {
      EXPECT_NEAR(d.gradient[i], reference.g[i], 1e-9 * gradientScale) << "gradient " << i;
      for (int j = 0; j < 11; ++j) {
        EXPECT_NEAR(d.hessian(i, j), reference.hessian(i, j), 1e-9 * hessianScale)
            << "Hessian " << i << "," << j;
      }
    }
  }
}

TEST(BendTwistDerivatives, WrappedTwistKeepsTheAtan2Value) {
  // theta1 - theta0 = 3.5 rad on a straight rod: the twist angle is 3.5 - 2 pi, as in the energy.
  Stencil s;
  s.e0 = Eigen::Vector3d(1, 0, 0);
  s.e1 = Eigen::Vector3d(1, 0, 0);
  s.r0 = s.r1 = EdgeReference{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  s.theta0 = -1.5;
  s.theta1 = 2.0;
  const double twist = 3.5 - 2.0 * M_PI;
  const BendTwistDerivatives d = closedForm(s, 1.0);
  EXPECT_NEAR(d.energy, 0.5 * kStiffness.twisting * twist * twist, 1e-12);
  EXPECT_NEAR(d.gradient[7], kStiffness.twisting * twist, 1e-12);
  EXPECT_NEAR(d.gradient[6], -kStiffness.twisting * twist, 1e-12);
  EXPECT_NEAR(d.hessian(7, 7), kStiffness.twisting, 1e-12);
  EXPECT_NEAR(d.hessian(6, 7), -kStiffness.twisting, 1e-12);
}

TEST(BendTwistDerivatives, MatchFiniteDifferences) {
  std::mt19937 rng(29);
  for (int trial = 0; trial < 5; ++trial) {
    const Stencil s = randomStencil(rng, 0.4, 0.8);
    const double l = 1.1;
    const BendTwistDerivatives d = closedForm(s, l);
    const double gradientScale = d.gradient.cwiseAbs().maxCoeff();
    const double hessianScale = d.hessian.cwiseAbs().maxCoeff();
    EXPECT_NEAR(d.energy, energyAt(s, l), 1e-12 * d.energy);
    for (int i = 0; i < 8; ++i) {
      const double step = 1e-6;
      const Stencil plus = moved(s, i, step), minus = moved(s, i, -step);
      EXPECT_NEAR(d.gradient[i], (energyAt(plus, l) - energyAt(minus, l)) / (2.0 * step),
                  1e-6 * gradientScale)
          << i;
      const Eigen::Matrix<double, 8, 1> column =
          (closedForm(plus, l).gradient - closedForm(minus, l).gradient) / (2.0 * step);
      for (int j = 0; j < 8; ++j)
        EXPECT_NEAR(d.hessian(j, i), column[j], 1e-6 * hessianScale) << j << "," << i;
    }
  }
}

// The Gauss-Newton Hessian (the projected fallback's): energy and gradient as the exact ones, a
// Hessian that is positive semidefinite where the exact one is not, and the exact one where the
// terms it leaves out vanish (they are weighted by the material curvatures and the twist: a
// straight, untwisted stencil).
TEST(BendTwistDerivatives, GaussNewtonHessianIsSemidefiniteAndExactWhereTheRodIsStraight) {
  std::mt19937 rng(11);
  int indefinite = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Stencil s = randomStencil(rng, 0.8, 1.0);
    const BendTwistDerivatives exact = closedForm(s, 0.9);
    const BendTwistDerivatives gn =
        bendTwistDerivatives(edgeFrameDerivatives(s.e0, s.theta0, s.r0),
                             edgeFrameDerivatives(s.e1, s.theta1, s.r1), kStiffness, 0.9, true);
    EXPECT_EQ(gn.energy, exact.energy);
    EXPECT_EQ(gn.gradient, exact.gradient);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 8, 8>> e(gn.hessian);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 8, 8>> x(exact.hessian);
    EXPECT_GT(e.eigenvalues().minCoeff(), -1e-12 * e.eigenvalues().maxCoeff());
    if (x.eigenvalues().minCoeff() < -1e-6 * x.eigenvalues().maxCoeff()) ++indefinite;
  }
  EXPECT_GT(indefinite, 10);  // the exact Hessians it replaces were often indefinite
  Stencil straight;
  straight.e0 = Eigen::Vector3d(1.0, 0.0, 0.0);
  straight.e1 = Eigen::Vector3d(0.8, 0.0, 0.0);
  straight.r0 = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()};
  straight.r1 = straight.r0;
  const BendTwistDerivatives exact = closedForm(straight, 0.9);
  const BendTwistDerivatives gn = bendTwistDerivatives(
      edgeFrameDerivatives(straight.e0, 0.0, straight.r0),
      edgeFrameDerivatives(straight.e1, 0.0, straight.r1), kStiffness, 0.9, true);
  EXPECT_LT((gn.hessian - exact.hessian).cwiseAbs().maxCoeff(),
            1e-12 * exact.hessian.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace egg::rods
