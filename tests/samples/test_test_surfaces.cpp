// The test surfaces satisfy their implicit equations exactly (they are oracles for the geodesic
// and curvature tests), face outward, and honour their parameters.
#include "samples/generators/samples.hpp"

#include "tests/samples/mesh_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace egg::samples {
namespace {

using Eigen::Vector3d;
constexpr double kSurfacesPi = std::numbers::pi;

// Checks every vertex against `residual` (zero on the surface) and every face normal against the
// outward direction `outward(centroid)`.
void expectOnSurface(const TriMesh& mesh, const std::function<double(const Vector3d&)>& residual,
                     const std::function<Vector3d(const Vector3d&)>& outward) {
  double worst = 0.0;
  for (auto v : mesh.vertices())
    worst = std::max(worst, std::abs(residual(toEigen(mesh.point(v)))));
  EXPECT_LT(worst, 1e-12);
  int inward = 0;
  for (auto f : mesh.faces()) {
    inward +=
        testing::faceNormal(mesh, f).dot(outward(testing::faceCentroid(mesh, f))) <= 0 ? 1 : 0;
  }
  EXPECT_EQ(inward, 0);
}

const Vector3d kUp(0, 0, 1);

TEST(TestSurfaces, Plane) {
  const TriMesh mesh = generateSample("plane", {}, 0.5);
  expectOnSurface(
      mesh, [](const Vector3d& p) { return p.z(); }, [](const Vector3d&) { return kUp; });
  EXPECT_NEAR(surfaceArea(mesh), 100.0, 1e-9);
}

TEST(TestSurfaces, SphereCapAndHemisphere) {
  const TriMesh cap = generateSample("sphere", {}, 0.5);
  expectOnSurface(
      cap, [](const Vector3d& p) { return (p.norm() - 10.0) / 10.0; },
      [](const Vector3d& c) { return c; });
  const auto box = boundingBox(cap);
  EXPECT_NEAR(box.min.z(), std::sqrt(100.0 - 64.0), 1e-9);  // rim at footprint radius 8
  EXPECT_NEAR(box.max.z(), 10.0, 0.02);
  const TriMesh hemisphere = generateSample("sphere", {{"radius", 2.0}, {"extent", 2.0}}, 0.2);
  expectOnSurface(
      hemisphere, [](const Vector3d& p) { return p.norm() - 2.0; },
      [](const Vector3d& c) { return c; });
  EXPECT_NEAR(boundingBox(hemisphere).min.z(), 0.0, 1e-12);
  EXPECT_NEAR(surfaceArea(hemisphere), 2 * kSurfacesPi * 4.0, 0.02 * 2 * kSurfacesPi * 4.0);
}

TEST(TestSurfaces, CylinderVault) {
  const TriMesh mesh = generateSample("cylinder", {{"angle", kSurfacesPi / 2}}, 0.4);
  expectOnSurface(
      mesh, [](const Vector3d& p) { return std::hypot(p.y(), p.z()) - 5.0; },
      [](const Vector3d& c) { return Vector3d(0, c.y(), c.z()); });
  const auto box = boundingBox(mesh);
  EXPECT_NEAR(box.size().x(), 10.0, 1e-12);
  EXPECT_NEAR(box.size().y(), 2 * 5.0 * std::sin(kSurfacesPi / 4),
              1e-9);  // the arc's corners are vertices
  EXPECT_NEAR(box.min.z(), 5.0 * std::cos(kSurfacesPi / 4), 1e-9);
}

TEST(TestSurfaces, ConeFrustumAndPointedCone) {
  const auto residual = [](const Vector3d& p) {
    return std::hypot(p.x(), p.y()) - 5.0 * (1 - p.z() / 5.0);
  };
  const auto outward = [](const Vector3d& c) {
    return Vector3d(c.x(), c.y(), std::hypot(c.x(), c.y()));
  };
  const TriMesh frustum = generateSample("cone", {}, 0.3);
  expectOnSurface(frustum, residual, outward);
  EXPECT_NEAR(boundingBox(frustum).max.z(), 4.0, 1e-9);  // top circle of radius 1
  // Half of a frustum's lateral area pi (R + r) slant.
  EXPECT_NEAR(surfaceArea(frustum), 0.5 * kSurfacesPi * 6.0 * std::sqrt(16.0 + 16.0), 0.015 * 53.3);
  const TriMesh pointed = generateSample("cone", {{"top_radius", 0.0}}, 0.3);
  expectOnSurface(pointed, residual, outward);
  bool apex = false;
  for (auto v : pointed.vertices())
    apex = apex || (toEigen(pointed.point(v)) - Vector3d(0, 0, 5)).norm() < 1e-12;
  EXPECT_TRUE(apex);
}

TEST(TestSurfaces, Hypar) {
  const TriMesh mesh = generateSample("hypar", {{"c", 0.2}}, 0.4);
  expectOnSurface(
      mesh, [](const Vector3d& p) { return p.z() - 0.2 * p.x() * p.y(); },
      [](const Vector3d&) { return kUp; });
  EXPECT_NEAR(boundingBox(mesh).max.z(), 0.2 * 25, 1e-9);  // corners are vertices
}

TEST(TestSurfaces, Hyperboloid) {
  const TriMesh mesh = generateSample("hyperboloid", {}, 0.3);
  expectOnSurface(
      mesh,
      [](const Vector3d& p) {
        return (p.x() * p.x() + p.y() * p.y()) / 9.0 - p.z() * p.z() / 16.0 - 1.0;
      },
      [](const Vector3d& c) { return Vector3d(c.x(), c.y(), 0); });
  const auto box = boundingBox(mesh);
  EXPECT_NEAR(box.size().z(), 6.0, 1e-12);
  EXPECT_NEAR(box.max.x(), 3.0 * std::sqrt(1 + 9.0 / 16.0), 5e-3);  // a rim vertex may miss phi = 0
}

TEST(TestSurfaces, BumpAndWaves) {
  const TriMesh bump = generateSample("bump", {{"height", 3.0}, {"sigma", 1.5}}, 0.4);
  expectOnSurface(
      bump,
      [](const Vector3d& p) {
        return p.z() - 3.0 * std::exp(-(p.x() * p.x() + p.y() * p.y()) / 4.5);
      },
      [](const Vector3d&) { return kUp; });
  const TriMesh waves = generateSample("waves", {{"amplitude", 0.3}, {"wavelength", 4.0}}, 0.4);
  expectOnSurface(
      waves,
      [](const Vector3d& p) {
        return p.z() - 0.3 * std::sin(2 * kSurfacesPi * p.x() / 4.0) *
                           std::sin(2 * kSurfacesPi * p.y() / 4.0);
      },
      [](const Vector3d&) { return kUp; });
}

}  // namespace
}  // namespace egg::samples
