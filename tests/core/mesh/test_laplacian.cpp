#include "core/mesh/laplacian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace egg {
namespace {

// A planar mesh on [0, 2] x [0, 1] with jittered interior vertices (irregular, not equilateral).
TriMesh jitteredPlane(int n, double jitter, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= 2 * n; ++i) {
      const bool inside = i > 0 && i < 2 * n && j > 0 && j < n;
      soup.vertices.push_back(
          {(i + (inside ? u(rng) : 0.0)) / n, (j + (inside ? u(rng) : 0.0)) / n, 0.0});
    }
  auto id = [n](int i, int j) { return j * (2 * n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return meshFromSoup(soup);
}

// A patch of the equilateral triangle lattice.
TriMesh equilateralPatch(int n) {
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      soup.vertices.push_back({i + 0.5 * j, std::sqrt(3.0) / 2.0 * j, 0.0});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      soup.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return meshFromSoup(soup);
}

Eigen::VectorXd coordinate(const TriMesh& mesh, int axis) {
  Eigen::VectorXd x(mesh.n_vertices());
  for (auto vh : mesh.vertices()) x(vh.idx()) = mesh.point(vh)[axis];
  return x;
}

TEST(Laplacian, CotanIsSymmetricWithZeroRowSums) {
  const TriMesh mesh = jitteredPlane(6, 0.3);
  const Eigen::SparseMatrix<double> L = cotanLaplacian(mesh);
  EXPECT_LT((Eigen::MatrixXd(L) - Eigen::MatrixXd(L).transpose()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((L * Eigen::VectorXd::Ones(mesh.n_vertices())).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Laplacian, LinearFunctionsAreHarmonicAndDirichletEnergyIsArea) {
  // Linear precision: L x = 0 at interior vertices of any planar mesh; x^T L x = int |grad x|^2 =
  // area.
  const TriMesh mesh = jitteredPlane(6, 0.3);
  const Eigen::SparseMatrix<double> L = cotanLaplacian(mesh);
  const Eigen::VectorXd x = coordinate(mesh, 0), y = coordinate(mesh, 1);
  const Eigen::VectorXd Lx = L * x;
  for (auto vh : mesh.vertices())
    if (!mesh.is_boundary(vh)) {
      EXPECT_NEAR(Lx(vh.idx()), 0.0, 1e-12);
    }
  EXPECT_NEAR(x.dot(L * x), 2.0, 1e-12);
  EXPECT_NEAR(y.dot(L * y), 2.0, 1e-12);
  EXPECT_NEAR(x.dot(L * y), 0.0, 1e-12);
  // The uniform operator lacks linear precision on the same mesh.
  const Eigen::VectorXd Ux = uniformLaplacian(mesh) * x;
  double worst = 0.0;
  for (auto vh : mesh.vertices())
    if (!mesh.is_boundary(vh)) worst = std::max(worst, std::abs(Ux(vh.idx())));
  EXPECT_GT(worst, 1e-3);
}

TEST(Laplacian, UniformEqualsCotanOnTheEquilateralLattice) {
  const TriMesh mesh = equilateralPatch(5);
  const Eigen::MatrixXd difference =
      Eigen::MatrixXd(cotanLaplacian(mesh)) - Eigen::MatrixXd(uniformLaplacian(mesh));
  EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Laplacian, BarycentricAreasSumToTheSurfaceArea) {
  const TriMesh mesh = jitteredPlane(5, 0.2);
  EXPECT_NEAR(barycentricVertexAreas(mesh).sum(), 2.0, 1e-12);
}

}  // namespace
}  // namespace egg
