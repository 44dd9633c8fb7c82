#include "core/egg/patch_maps.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace egg {
namespace {

TEST(PatchMaps, PlanePatchMapsAreThePlanarClosedForm) {
  // On a flat patch the geodesic distance map is the planar map at the patch's own angle.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3.5, -2.8, 0}, {3.1, 3.2, 0}, {-2.7, 2.9, 0}};
  const Patch patch = makePatch(mesh, corners);
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions options;
  options.resolution = 9;
  options.toleranceRelative = 0.0;  // every row exact
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, options);
  EXPECT_NO_THROW(maps.validate());
  const auto quad = *planarQuad(maps.sides, maps.alphaSpatial);
  for (Family family : {Family::U, Family::V}) {
    const auto planar = planarDistanceMap(quad, family, 9, 9);
    for (size_t k = 0; k < planar.values.size(); ++k)
      EXPECT_NEAR(maps.map(family).values[k], planar.values[k], 1e-9);
  }
  EXPECT_EQ(maps.propagations, 18);
  EXPECT_NEAR(maps.diagonalE, (corners[2] - corners[0]).norm(), 1e-9);
  EXPECT_NEAR(maps.diagonalF, (corners[3] - corners[1]).norm(), 1e-9);
  // Family sides: u from c0->c3 to c1->c2, v from c0->c1 to c3->c2.
  EXPECT_NEAR(
      (position(patch.mesh, familyBoundaryPoint(patch, Family::U, false, 1.0)) - corners[3]).norm(),
      0, 1e-12);
  EXPECT_NEAR(
      (position(patch.mesh, familyBoundaryPoint(patch, Family::V, true, 0.0)) - corners[3]).norm(),
      0, 1e-12);
  EXPECT_NEAR(familySideLength(patch, Family::U, true), (corners[2] - corners[1]).norm(), 1e-12);
  options.resolution = 2;
  EXPECT_THROW(options.validate(), InvalidInput);
}

TEST(PatchMaps, AdaptiveRowsOnAPlanePatchMatchTheClosedForm) {
  // The planar distance between points of two opposite sides is smooth in x1: a few exact rows
  // and cubic interpolation reproduce the closed form to the tolerance on a 100 x 100 map.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3.5, -2.8, 0}, {3.1, 3.2, 0}, {-2.7, 2.9, 0}};
  const Patch patch = makePatch(mesh, corners);
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions options;
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, options);  // default tolerance
  // 9 initial rows + 8 checks per family, all passing (the planar map is smooth): 34 fields, not
  // 200.
  EXPECT_EQ(maps.propagations, 34);
  const auto quad = *planarQuad(maps.sides, maps.alphaSpatial);
  for (Family family : {Family::U, Family::V}) {
    const auto planar = planarDistanceMap(quad, family, 100, 100);
    double largest = 0.0;
    for (size_t k = 0; k < planar.values.size(); ++k)
      largest = std::max(largest, std::abs(maps.map(family).values[k] - planar.values[k]));
    EXPECT_LT(largest,
              1e-4);  // 1.5e-5 measured: the check at half the node spacing is conservative
  }
}

TEST(PatchMaps, AdaptiveMapsOfABumpStayWithinTheToleranceOfTheExactMaps) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.25);
  const Patch patch =
      makePatch(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}});
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions exact;
  exact.resolution = 100;
  exact.toleranceRelative = 0.0;
  exact.proxyVertices = 0;  // the adaptive rows on the patch itself
  DistanceMapOptions adaptive = exact;
  adaptive.toleranceRelative = DistanceMapOptions{}.toleranceRelative;
  const PatchDistanceMaps reference = computeDistanceMaps(patch, solver, exact);
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, adaptive);
  EXPECT_EQ(reference.propagations, 200);
  EXPECT_LT(maps.propagations, 110);  // 96 measured
  for (Family family : {Family::U, Family::V}) {
    const double side =
        std::min(familySideLength(patch, family, false), familySideLength(patch, family, true));
    double largest = 0.0;
    for (size_t k = 0; k < maps.map(family).values.size(); ++k)
      largest =
          std::max(largest, std::abs(maps.map(family).values[k] - reference.map(family).values[k]));
    // Not a guarantee: near the centre line the exact rows themselves jitter by a few 1e-4 m
    // (geodesics sweeping over the apex vertices), which the cubic smooths over: 6.6e-4 m =
    // 1.1x the tolerance measured for u.
    EXPECT_LT(largest, 1.5 * adaptive.toleranceRelative * side)
        << (family == Family::U ? "u" : "v");
  }
  EXPECT_EQ(maps.diagonalE, reference.diagonalE);  // corner rows are always exact
  EXPECT_EQ(maps.diagonalF, reference.diagonalF);
}

TEST(PatchMaps, TheToleranceScalesWithThePatch) {
  // The same bump and mesh scaled by 1/7 (a 0.86 m patch): geodesic distances scale by 1/7, and
  // so does the tolerance, so the refinement takes the same decisions up to rounding (100 and
  // 101 fields) and both maps stay within the relative tolerance. An absolute tolerance of the
  // same size on the large patch allowed 7x the relative error on the small one, with far
  // fewer fields.
  const auto relativeError = [](double scale, int& fields) {
    const double s = scale;
    const TriMesh mesh = samples::generateSample(
        "bump", {{"height", 1.0 * s}, {"sigma", 1.5 * s}, {"length", 8.0 * s}, {"width", 8.0 * s}},
        0.3 * s);
    const Patch patch = makePatch(mesh, {Eigen::Vector3d(-3 * s, -3 * s, 0),
                                         {3 * s, -3 * s, 0},
                                         {3 * s, 3 * s, 0},
                                         {-3 * s, 3 * s, 0}});
    const geodesic::DistanceSolver solver(patch.mesh);
    DistanceMapOptions adaptive;
    adaptive.proxyVertices = 0;  // the adaptive rows on the patch itself
    DistanceMapOptions exact = adaptive;
    exact.toleranceRelative = 0.0;
    const auto reference = computeDistanceMaps(patch, solver, exact);
    const auto maps = computeDistanceMaps(patch, solver, adaptive);
    fields = maps.propagations;
    double largest = 0.0;
    for (size_t k = 0; k < maps.u.values.size(); ++k)
      largest = std::max(largest, std::abs(maps.u.values[k] - reference.u.values[k]));
    return largest / familySideLength(patch, Family::U, false);
  };
  int fieldsLarge = 0, fieldsSmall = 0;
  const double large = relativeError(1.0, fieldsLarge);
  const double small = relativeError(1.0 / 7.0, fieldsSmall);
  EXPECT_NEAR(fieldsSmall, fieldsLarge, 4);
  EXPECT_LT(fieldsLarge, 200);
  EXPECT_LT(large, DistanceMapOptions{}.toleranceRelative);
  EXPECT_LT(small, DistanceMapOptions{}.toleranceRelative);
}

TEST(PatchMaps, OptionsNameTheBadField) {
  const auto message = [](const DistanceMapOptions& options) {
    try {
      options.validate();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  DistanceMapOptions options;
  EXPECT_EQ(message(options), "");
  // The messages name the scene key a user writes.
  options.toleranceRelative = -1e-6;
  EXPECT_NE(message(options).find("grid.map_tolerance_relative"), std::string::npos);
  options.toleranceRelative = std::nan("");
  EXPECT_NE(message(options).find("grid.map_tolerance_relative"), std::string::npos);
  options.toleranceRelative = INFINITY;
  EXPECT_NE(message(options).find("grid.map_tolerance_relative"), std::string::npos);
  options.toleranceRelative = 0.0;
  EXPECT_EQ(message(options), "");
  options.initialNodes = 1;
  EXPECT_NE(message(options).find("initialNodes"), std::string::npos);
  options.initialNodes = 2;
  options.resolution = 2;
  EXPECT_NE(message(options).find("map_resolution"), std::string::npos);
  options.resolution = 100;
  for (int bad : {-1, 1, 7}) {
    options.proxyVertices = bad;
    EXPECT_NE(message(options).find("grid.map_proxy_vertices"), std::string::npos) << bad;
  }
  options.proxyVertices = 8;
  EXPECT_EQ(message(options), "");
  options.proxyToleranceRelative = -1.0;
  EXPECT_NE(message(options).find("proxyToleranceRelative"), std::string::npos);
  options.proxyToleranceRelative = 1e-3;
  options.proxySaddleAngleTolerance = std::nan("");
  EXPECT_NE(message(options).find("proxySaddleAngleTolerance"), std::string::npos);
}

TEST(PatchMaps, APatchNoLargerThanTheProxyIsItsOwnProxy) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.4);
  const Patch patch =
      makePatch(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}});
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions onPatch;
  onPatch.resolution = 21;
  onPatch.proxyVertices = 0;
  DistanceMapOptions large = onPatch;
  large.proxyVertices =
      static_cast<int>(patch.mesh.n_vertices());  // not more vertices than the option
  // A patch no larger than the proxy is its own proxy: the rows at the proxy's tolerance.
  DistanceMapOptions ownProxy = onPatch;
  ownProxy.toleranceRelative = onPatch.proxyToleranceRelative;
  const auto ownProxyMaps = computeDistanceMaps(patch, solver, ownProxy);
  DistanceMapOptions small = onPatch;
  small.proxyVertices = static_cast<int>(patch.mesh.n_vertices()) / 2;
  const auto reference = computeDistanceMaps(patch, solver, onPatch);
  const auto same = computeDistanceMaps(patch, solver, large);
  const auto proxy = computeDistanceMaps(patch, solver, small);
  EXPECT_EQ(same.u.values, ownProxyMaps.u.values);  // bit-identical
  EXPECT_EQ(same.v.values, ownProxyMaps.v.values);
  EXPECT_EQ(same.propagations, ownProxyMaps.propagations);
  EXPECT_LT(same.propagations, reference.propagations);  // the looser rows need fewer fields
  EXPECT_NE(proxy.u.values, reference.u.values);         // and the smaller option did use a proxy
}

TEST(PatchMaps, ProxyMapsOfABumpStayWithinAMeasuredBoundOfTheFineMaps) {
  // A 6 x 6 m patch of ~2.8k vertices on the bench bump: the maps on a 600-vertex proxy (the
  // default) against exact maps on the patch. The fine mesh's own noise, max |D_u - D_v| on this
  // patch symmetric about its diagonal (D_u = D_v on the smooth surface), is the scale.
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.13);
  const Patch patch =
      makePatch(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}});
  ASSERT_GT(patch.mesh.n_vertices(), 2000u);
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions exact;
  exact.resolution = 41;
  exact.toleranceRelative = 0.0;
  exact.proxyVertices = 0;
  DistanceMapOptions proxy;
  proxy.resolution = 41;
  ASSERT_EQ(proxy.proxyVertices, 600);
  const auto reference = computeDistanceMaps(patch, solver, exact);
  const auto maps = computeDistanceMaps(patch, solver, proxy);
  double error = 0.0, noise = 0.0;
  for (size_t k = 0; k < maps.u.values.size(); ++k) {
    error = std::max({error, std::abs(maps.u.values[k] - reference.u.values[k]),
                      std::abs(maps.v.values[k] - reference.v.values[k])});
    noise = std::max(noise, std::abs(reference.u.values[k] - reference.v.values[k]));
  }
  EXPECT_GT(error, 1e-5);            // the proxy was used
  EXPECT_LT(error, 1.5e-3);          // 9.8e-4 measured (3.1k vertices, 41 x 41 samples)
  EXPECT_LT(error, 3.0 * noise);     // 2.0x the mesh noise of 4.8e-4 measured
  EXPECT_LT(maps.propagations, 40);  // 9 initial rows + 8 passing checks per family
  EXPECT_EQ(maps.sides, patch.sideLengths);
  EXPECT_EQ(maps.alphaSpatial, patch.innerAngles[0]);
  EXPECT_NEAR(maps.diagonalE, reference.diagonalE, 2.0e-3);
  EXPECT_NEAR(maps.diagonalF, reference.diagonalF, 2.0e-3);
}

}  // namespace
}  // namespace egg
