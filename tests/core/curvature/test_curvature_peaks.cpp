#include "core/curvature/curvature_peaks.hpp"

#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace egg {
namespace {

// Height field on [-a, a]^2 with n x n cells, parallel diagonals (valence 6 inside).
TriMesh heightField(double a, int n, const std::function<double(double, double)>& f) {
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -a + 2.0 * a * i / n, y = -a + 2.0 * a * j / n;
      soup.vertices.push_back({x, y, f(x, y)});
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return meshFromSoup(soup);
}

double gaussianBump(double x, double y, double cx, double cy, double height, double sigma) {
  return height * std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (2.0 * sigma * sigma));
}

TEST(CurvaturePeaks, OneBumpOnePeakAtItsApex) {
  // Apex of z = H exp(-r^2 / 2 s^2): f_xx = f_yy = -H / s^2, no slope, so K = H^2 / s^4.
  const double height = 1.0, sigma = 1.0;
  const TriMesh mesh = heightField(
      4.0, 80, [&](double x, double y) { return gaussianBump(x, y, 0, 0, height, sigma); });
  const CurvatureField field = computeCurvature(mesh);
  const auto peaks = findGaussianPeaks(mesh, field.gaussian, field.mixedArea);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_LT(peaks[0].position.head<2>().norm(), 1e-9);
  // Near the apex K(r) = 1 - 4 r^2 / s^2 + ..., and the kernel (1 - r^2/rho^2)^2 has a mean r^2 of
  // rho^2 / 4, so the average over rho = 2 mean edge lengths is 1 - rho^2 / s^2.
  const double rho = 2.0 * meanEdgeLength(mesh);
  EXPECT_NEAR(peaks[0].gaussianAveraged, 1.0 - rho * rho, 0.01);
  EXPECT_NEAR(peaks[0].gaussianVertex, 1.0, 0.01);
  EXPECT_NEAR(peaks[0].gaussianMaxNearby, 1.0, 0.01);
  EXPECT_NEAR(peaks[0].injectivityBoundM, std::numbers::pi / std::sqrt(peaks[0].gaussianMaxNearby),
              1e-12);
  EXPECT_FALSE(peaks[0].onBoundary);
}

TEST(CurvaturePeaks, TwoBumpsStrongestFirstAndThresholdFilters) {
  auto f = [](double x, double y) {
    return gaussianBump(x, y, -2.0, 0.0, 1.0, 0.8) + gaussianBump(x, y, 2.0, 0.5, 0.5, 0.8);
  };
  const TriMesh mesh = heightField(5.0, 100, f);
  const CurvatureField field = computeCurvature(mesh);
  const double strong = std::pow(1.0 / (0.8 * 0.8), 2), weak = std::pow(0.5 / (0.8 * 0.8), 2);
  PeakOptions options;
  options.minGaussian = 0.1 * weak;  // the flat skirt has tiny K of both signs: not a peak
  const auto peaks = findGaussianPeaks(mesh, field.gaussian, field.mixedArea, options);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_LT((peaks[0].position.head<2>() - Eigen::Vector2d(-2.0, 0.0)).norm(), 1e-9);
  EXPECT_LT((peaks[1].position.head<2>() - Eigen::Vector2d(2.0, 0.5)).norm(), 1e-9);
  EXPECT_NEAR(peaks[0].gaussianMaxNearby, strong, 0.02 * strong);
  EXPECT_NEAR(peaks[1].gaussianMaxNearby, weak, 0.02 * weak);
  EXPECT_LT(peaks[0].gaussianAveraged, peaks[0].gaussianMaxNearby);
  options.minGaussian = 0.5 * (strong + weak);
  EXPECT_EQ(findGaussianPeaks(mesh, field.gaussian, field.mixedArea, options).size(), 1u);
}

TEST(CurvaturePeaks, SaddlesAndPlanesHaveNoPeaks) {
  const TriMesh plane = heightField(1.0, 10, [](double, double) { return 0.0; });
  const CurvatureField flat = computeCurvature(plane);
  EXPECT_TRUE(findGaussianPeaks(plane, flat.gaussian, flat.mixedArea).empty());
  const TriMesh saddle = heightField(1.0, 20, [](double x, double y) { return 0.3 * x * y; });
  const CurvatureField field = computeCurvature(saddle);
  EXPECT_TRUE(findGaussianPeaks(saddle, field.gaussian, field.mixedArea).empty());
}

TEST(CurvaturePeaks, AveragingPreservesAConstantAndTheIntegral) {
  const TriMesh mesh =
      heightField(1.0, 12, [](double x, double y) { return 0.2 * std::sin(x) * y; });
  const Eigen::VectorXd area = mixedVoronoiAreas(mesh);
  const Eigen::VectorXd constant = Eigen::VectorXd::Constant(mesh.n_vertices(), 3.5);
  EXPECT_LT((averageOverBall(mesh, constant, area, 0.3) - constant).cwiseAbs().maxCoeff(), 1e-12);
  // Radius below the shortest edge: every ball is the vertex itself.
  Eigen::VectorXd field(mesh.n_vertices());
  for (int v = 0; v < field.size(); ++v) field(v) = std::sin(v);
  EXPECT_LT((averageOverBall(mesh, field, area, 1e-3) - field).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(CurvaturePeaks, SampleBumpOnAnIrregularMeshHasOnePeak) {
  const auto infos = samples::listSamples();
  samples::Params params;
  for (const auto& info : infos)
    if (info.name == "bump") params = info.defaults;
  if (params.empty()) GTEST_SKIP() << "no bump sample";
  const double sigma = params.at("sigma"), height = params.at("height");
  const TriMesh mesh = samples::generateSample("bump", params, sigma / 8.0);
  const CurvatureField field = computeCurvature(mesh);
  const auto peaks = findGaussianPeaks(mesh, field.gaussian, field.mixedArea);
  // Interior peaks: exactly the apex (boundary vertices of the skirt may carry fit noise, so the
  // search is restricted to the interior here).
  PeakOptions interior;
  interior.includeBoundary = false;
  interior.minGaussian = 0.05 * std::pow(height / (sigma * sigma), 2);
  const auto inner = findGaussianPeaks(mesh, field.gaussian, field.mixedArea, interior);
  ASSERT_EQ(inner.size(), 1u);
  EXPECT_LT(inner[0].position.head<2>().norm(), sigma / 4.0);
  const double apexK = std::pow(height / (sigma * sigma), 2);
  EXPECT_NEAR(inner[0].gaussianMaxNearby, apexK, 0.1 * apexK);
  std::cout << "sample bump apex K " << apexK << ": averaged " << inner[0].gaussianAveraged
            << ", vertex " << inner[0].gaussianVertex << ", max nearby "
            << inner[0].gaussianMaxNearby << "\n";
  EXPECT_FALSE(peaks.empty());
}

TEST(CurvaturePeaks, OptionsAndSizesAreValidated) {
  const TriMesh mesh = heightField(1.0, 2, [](double, double) { return 0.0; });
  PeakOptions options;
  options.smoothingRadiusM = -1.0;
  const Eigen::VectorXd k = Eigen::VectorXd::Zero(mesh.n_vertices());
  EXPECT_THROW(findGaussianPeaks(mesh, k, k, options), InvalidInput);
  EXPECT_THROW(findGaussianPeaks(mesh, Eigen::VectorXd::Zero(2), k), InvalidInput);
}

}  // namespace
}  // namespace egg
