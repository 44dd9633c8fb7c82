#include "samples/generators/surface_mesher.hpp"

#include "samples/generators/catalog.hpp"
#include "tests/samples/mesh_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace egg::samples::detail {
namespace {

constexpr double kMesherPi = std::numbers::pi;

SurfaceSpec build(const std::string& name, Params overrides = {}) {
  for (const auto& entry : testSurfaceSamples()) {
    if (entry.info.name != name) continue;
    Params params = entry.info.defaults;
    for (const auto& [key, value] : overrides) params[key] = value;
    return entry.build(params);
  }
  throw std::runtime_error("no sample " + name);
}

TEST(SurfaceMesher, AreaEstimateIsWithinAPercent) {
  EXPECT_NEAR(estimateArea(build("plane")), 100.0, 1e-6);
  // Cap of polar angle psi: 2 pi R^2 (1 - cos psi), cos psi = 0.6 for extent 8 of radius 10.
  EXPECT_NEAR(estimateArea(build("sphere")), 2 * kMesherPi * 100 * 0.4,
              0.01 * 2 * kMesherPi * 100 * 0.4);
}

TEST(SurfaceMesher, BoundaryVerticesLieOnTheExactCurvesAndRequiredPointsAreVertices) {
  SurfaceSpec spec = build("cone");  // frustum: inner and outer arcs, two rulings
  spec.requiredPoints = {{5.0, 0.1}};
  const TriMesh mesh = meshFromSoup(meshSurface(spec, 0.4, estimateArea(spec) / (0.433 * 0.16)));
  const double slant = std::sqrt(50.0);
  bool required = false;
  for (auto v : mesh.vertices()) {
    const Vec3 p = toEigen(mesh.point(v));
    required = required || (p - spec.position({5.0, 0.1})).norm() < 1e-12;
    if (!mesh.is_boundary(v)) continue;
    // On the base (z = 0), the top circle (z = 4), or a ruling at azimuth +-pi/2.
    const double azimuth = std::atan2(p.y(), p.x());
    const bool onCurve = std::abs(p.z()) < 1e-12 || std::abs(p.z() - 4.0) < 1e-12 ||
                         std::abs(std::abs(azimuth) - kMesherPi / 2) < 1e-12;
    EXPECT_TRUE(onCurve) << p.transpose();
  }
  EXPECT_TRUE(required);
  (void)slant;
}

}  // namespace
}  // namespace egg::samples::detail
