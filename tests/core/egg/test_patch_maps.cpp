#include "core/egg/patch_maps.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace egg {
namespace {

TEST(PatchMaps, PlanePatchMapsAreThePlanarClosedForm) {
  // On a flat patch the geodesic distance map is the planar map at the patch's own angle.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  const std::array<Eigen::Vector3d, 4> corners{Eigen::Vector3d(-3, -3, 0), {3.5, -2.8, 0}, {3.1, 3.2, 0}, {-2.7, 2.9, 0}};
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
    for (size_t k = 0; k < planar.values.size(); ++k) EXPECT_NEAR(maps.map(family).values[k], planar.values[k], 1e-9);
  }
  EXPECT_EQ(maps.propagations, 18);
  EXPECT_NEAR(maps.diagonalE, (corners[2] - corners[0]).norm(), 1e-9);
  EXPECT_NEAR(maps.diagonalF, (corners[3] - corners[1]).norm(), 1e-9);
  // Family sides: u from c0->c3 to c1->c2, v from c0->c1 to c3->c2.
  EXPECT_NEAR((position(patch.mesh, familyBoundaryPoint(patch, Family::U, false, 1.0)) - corners[3]).norm(), 0, 1e-12);
  EXPECT_NEAR((position(patch.mesh, familyBoundaryPoint(patch, Family::V, true, 0.0)) - corners[3]).norm(), 0, 1e-12);
  EXPECT_NEAR(familySideLength(patch, Family::U, true), (corners[2] - corners[1]).norm(), 1e-12);
  options.resolution = 2;
  EXPECT_THROW(options.validate(), InvalidInput);
}

TEST(PatchMaps, AdaptiveRowsOnAPlanePatchMatchTheClosedForm) {
  // The planar distance between points of two opposite sides is smooth in x1: a few exact rows
  // and cubic interpolation reproduce the closed form to the tolerance on a 100 x 100 map.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  const std::array<Eigen::Vector3d, 4> corners{Eigen::Vector3d(-3, -3, 0), {3.5, -2.8, 0}, {3.1, 3.2, 0}, {-2.7, 2.9, 0}};
  const Patch patch = makePatch(mesh, corners);
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions options;
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, options);  // default tolerance
  // 9 initial rows + 8 checks per family, all passing (the planar map is smooth): 34 fields, not 200.
  EXPECT_EQ(maps.propagations, 34);
  const auto quad = *planarQuad(maps.sides, maps.alphaSpatial);
  for (Family family : {Family::U, Family::V}) {
    const auto planar = planarDistanceMap(quad, family, 100, 100);
    double largest = 0.0;
    for (size_t k = 0; k < planar.values.size(); ++k)
      largest = std::max(largest, std::abs(maps.map(family).values[k] - planar.values[k]));
    EXPECT_LT(largest, 1e-4);  // 1.5e-5 measured: the check at half the node spacing is conservative
  }
}

TEST(PatchMaps, AdaptiveMapsOfABumpStayWithinTheToleranceOfTheExactMaps) {
  const TriMesh mesh =
      samples::generateSample("bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.25);
  const Patch patch = makePatch(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}});
  const geodesic::DistanceSolver solver(patch.mesh);
  DistanceMapOptions exact;
  exact.resolution = 100;
  exact.toleranceRelative = 0.0;
  DistanceMapOptions adaptive = exact;
  adaptive.toleranceRelative = DistanceMapOptions{}.toleranceRelative;
  const PatchDistanceMaps reference = computeDistanceMaps(patch, solver, exact);
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, adaptive);
  EXPECT_EQ(reference.propagations, 200);
  EXPECT_LT(maps.propagations, 110);  // 96 measured
  for (Family family : {Family::U, Family::V}) {
    const double side = std::min(familySideLength(patch, family, false), familySideLength(patch, family, true));
    double largest = 0.0;
    for (size_t k = 0; k < maps.map(family).values.size(); ++k)
      largest = std::max(largest, std::abs(maps.map(family).values[k] - reference.map(family).values[k]));
    // Not a guarantee: near the centre line the exact rows themselves jitter by a few 1e-4 m
    // (geodesics sweeping over the apex vertices), which the cubic smooths over: 6.6e-4 m =
    // 1.1x the tolerance measured for u.
    EXPECT_LT(largest, 1.5 * adaptive.toleranceRelative * side) << (family == Family::U ? "u" : "v");
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
        "bump", {{"height", 1.0 * s}, {"sigma", 1.5 * s}, {"length", 8.0 * s}, {"width", 8.0 * s}}, 0.3 * s);
    const Patch patch = makePatch(mesh, {Eigen::Vector3d(-3 * s, -3 * s, 0), {3 * s, -3 * s, 0}, {3 * s, 3 * s, 0}, {-3 * s, 3 * s, 0}});
    const geodesic::DistanceSolver solver(patch.mesh);
    DistanceMapOptions exact;
    exact.toleranceRelative = 0.0;
    const auto reference = computeDistanceMaps(patch, solver, exact);
    const auto maps = computeDistanceMaps(patch, solver, DistanceMapOptions{});
    fields = maps.propagations;
    double largest = 0.0;
    for (size_t k = 0; k < maps.u.values.size(); ++k) largest = std::max(largest, std::abs(maps.u.values[k] - reference.u.values[k]));
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
}

}  // namespace
}  // namespace egg
