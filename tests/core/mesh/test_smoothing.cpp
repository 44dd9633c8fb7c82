#include "core/mesh/smoothing.hpp"

#include "core/errors.hpp"

#include "tests/support/analytic_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace egg {
namespace {

// (2n+1) x (n+1) grid on [0, 2] x [0, 1]; interior vertices jittered in the plane by `jitter`
// cells and lifted by uniform noise of amplitude `noise`.
TriMesh noisyPlane(int n, double jitter, double noise, unsigned seed = 11) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= 2 * n; ++i) {
      const bool inside = i > 0 && i < 2 * n && j > 0 && j < n;
      soup.vertices.push_back({(i + (inside ? jitter * u(rng) : 0.0)) / n,
                               (j + (inside ? jitter * u(rng) : 0.0)) / n,
                               inside ? noise * u(rng) : 0.0});
    }
  auto id = [n](int i, int j) { return j * (2 * n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < 2 * n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return meshFromSoup(soup);
}

using testing::icosphere;

double rmsHeight(const TriMesh& mesh) {
  double sum = 0.0;
  for (auto vh : mesh.vertices()) sum += mesh.point(vh)[2] * mesh.point(vh)[2];
  return std::sqrt(sum / mesh.n_vertices());
}

TEST(Smoothing, FlatIrregularMeshIsAFixedPointOfCotanButNotUniformFlow) {
  // Cotangent weights reproduce linear functions, so a planar mesh does not move at all, however
  // irregular; the umbrella operator slides its vertices within the plane.
  const TriMesh mesh = noisyPlane(8, 0.3, 0.0);
  SmoothingOptions options;
  options.strength = 5.0;
  const SmoothingResult cotan = smoothMeshStep(mesh, options);
  EXPECT_LT(cotan.maxDisplacementM, 1e-12);
  options.weights = LaplacianWeights::Uniform;
  const SmoothingResult uniform = smoothMeshStep(mesh, options);
  EXPECT_GT(uniform.maxDisplacementM, 0.01 / 8.0);
  for (auto vh : uniform.mesh.vertices()) EXPECT_NEAR(uniform.mesh.point(vh)[2], 0.0, 1e-14);
}

TEST(Smoothing, NoisyPlaneReturnsTowardsThePlaneWithTheBoundaryFixed) {
  const TriMesh mesh = noisyPlane(10, 0.2, 0.02);
  const double before = rmsHeight(mesh);
  TriMesh current = mesh;
  std::vector<double> rms;
  double lastMax = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 4; ++step) {
    const SmoothingResult result = smoothMeshStep(current, {});
    EXPECT_LT(result.maxDisplacementM, lastMax);  // the flow slows down as the noise goes
    EXPECT_GT(result.meanDisplacementM, 0.0);
    EXPECT_LE(result.meanDisplacementM, result.maxDisplacementM);
    lastMax = result.maxDisplacementM;
    current = result.mesh;
    rms.push_back(rmsHeight(current));
  }
  EXPECT_LT(rms[0], 0.5 * before);
  EXPECT_LT(rms[3], 0.1 * before);
  for (auto vh : mesh.vertices()) {
    if (mesh.is_boundary(vh)) {
      EXPECT_EQ(current.point(vh), mesh.point(vh));  // bit for bit
    }
  }
}

TEST(Smoothing, SphereShrinksLikeBackwardEulerMeanCurvatureFlow) {
  // For a sphere L X = M (2 / R) n with L and M of the current mesh, and L is linear in the
  // positions, so (M + t L) X' = M X has the solution X' = X / (1 + 2 t / R^2): a sphere of radius
  // R' = R / (1 + 2 t / R^2) (the linearised backward-Euler step of dR/dt = -2 / R).
  const double radius = 2.0;
  const TriMesh mesh = icosphere(radius, 3);
  SmoothingOptions options;
  options.strength = 0.05 * radius * radius / std::pow(meanEdgeLength(mesh), 2);  // t = 0.05 R^2
  const SmoothingResult result = smoothMeshStep(mesh, options);
  EXPECT_NEAR(result.timeStepM2, 0.05 * radius * radius, 1e-12);
  const double expected = radius / (1.0 + 2.0 * result.timeStepM2 / (radius * radius));
  double worst = 0.0;
  for (auto vh : result.mesh.vertices())
    worst = std::max(worst, std::abs(toEigen(result.mesh.point(vh)).norm() / expected - 1.0));
  std::cout << "sphere R' expected " << expected << ", worst relative deviation " << worst << "\n";
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(result.fixedVertices, 0);  // closed: nothing on a boundary
}

TEST(Smoothing, ConjugateGradientsAgreeWithCholesky) {
  const TriMesh mesh = noisyPlane(12, 0.25, 0.03);
  for (double strength : {0.3, 3.0, 30.0}) {
    SmoothingOptions options;
    options.strength = strength;
    options.solver = FairingSolver::Cholesky;
    const SmoothingResult direct = smoothMeshStep(mesh, options);
    options.solver = FairingSolver::ConjugateGradient;
    const SmoothingResult iterative = smoothMeshStep(mesh, options);
    EXPECT_TRUE(direct.usedCholesky);
    EXPECT_FALSE(iterative.usedCholesky);
    EXPECT_GT(iterative.iterations, 0);
    double worst = 0.0;
    for (auto vh : mesh.vertices())
      worst = std::max(worst,
                       (toEigen(direct.mesh.point(vh)) - toEigen(iterative.mesh.point(vh))).norm());
    EXPECT_LT(worst, 1e-9) << "strength " << strength;
    EXPECT_NEAR(direct.maxDisplacementM, iterative.maxDisplacementM, 1e-9);
  }
}

TEST(Smoothing, ExtraFixedVerticesStay) {
  const TriMesh mesh = noisyPlane(6, 0.2, 0.05);
  SmoothingOptions options;
  options.fixedVertices = {20, 30};
  const SmoothingResult result = smoothMeshStep(mesh, options);
  EXPECT_EQ(result.mesh.point(TriMesh::VertexHandle(20)), mesh.point(TriMesh::VertexHandle(20)));
  EXPECT_EQ(result.mesh.point(TriMesh::VertexHandle(30)), mesh.point(TriMesh::VertexHandle(30)));
  EXPECT_NE(result.mesh.point(TriMesh::VertexHandle(21)), mesh.point(TriMesh::VertexHandle(21)));
  EXPECT_EQ(result.fixedVertices, 2 * 13 + 2 * 5 + 2);
}

TEST(Smoothing, LoopStopsWhenTheCriterionHolds) {
  const TriMesh mesh = noisyPlane(10, 0.2, 0.02);
  const double target = 0.1 * rmsHeight(mesh);
  int checks = 0;
  const auto flatEnough = [&](const TriMesh& m) {
    ++checks;
    return rmsHeight(m) <= target;
  };
  const SmoothingLoopResult loop = smoothUntil(mesh, flatEnough, 20);
  EXPECT_TRUE(loop.satisfied);
  EXPECT_GE(loop.steps, 2);
  EXPECT_LT(loop.steps, 20);
  EXPECT_EQ(checks, loop.steps + 1);  // the input is checked too
  EXPECT_LE(rmsHeight(loop.mesh), target);
  EXPECT_EQ(static_cast<int>(loop.maxDisplacementM.size()), loop.steps);
  // Already satisfied: nothing runs, the mesh is returned unchanged.
  const SmoothingLoopResult none = smoothUntil(
      mesh, [](const TriMesh&) { return true; }, 5);
  EXPECT_EQ(none.steps, 0);
  EXPECT_EQ(none.totalMaxDisplacementM, 0.0);
  // Never satisfied: stops at the step limit and says so.
  const SmoothingLoopResult capped = smoothUntil(
      mesh, [](const TriMesh&) { return false; }, 3);
  EXPECT_FALSE(capped.satisfied);
  EXPECT_EQ(capped.steps, 3);
  EXPECT_GT(capped.totalMaxDisplacementM, 0.0);
}

TEST(Smoothing, BadInputIsRejected) {
  const TriMesh mesh = noisyPlane(3, 0.0, 0.0);
  SmoothingOptions options;
  options.strength = 0.0;
  EXPECT_THROW(smoothMeshStep(mesh, options), InvalidInput);
  options.strength = 1.0;
  options.fixedVertices = {1000};
  EXPECT_THROW(smoothMeshStep(mesh, options), InvalidInput);
  EXPECT_THROW(smoothMeshStep(TriMesh{}, {}), InvalidInput);
}

}  // namespace
}  // namespace egg
