#include "core/egg/patch_maps.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

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
  const PatchDistanceMaps maps = computeDistanceMaps(patch, solver, options);
  EXPECT_NO_THROW(maps.validate());
  const auto quad = *planarQuad(maps.sides, maps.alphaSpatial);
  for (Family family : {Family::U, Family::V}) {
    const auto planar = planarDistanceMap(quad, family, 9, 9);
    for (size_t k = 0; k < planar.values.size(); ++k) EXPECT_NEAR(maps.map(family).values[k], planar.values[k], 1e-9);
  }
  EXPECT_NEAR(maps.diagonalE, (corners[2] - corners[0]).norm(), 1e-9);
  EXPECT_NEAR(maps.diagonalF, (corners[3] - corners[1]).norm(), 1e-9);
  // Family sides: u from c0->c3 to c1->c2, v from c0->c1 to c3->c2.
  EXPECT_NEAR((position(patch.mesh, familyBoundaryPoint(patch, Family::U, false, 1.0)) - corners[3]).norm(), 0, 1e-12);
  EXPECT_NEAR((position(patch.mesh, familyBoundaryPoint(patch, Family::V, true, 0.0)) - corners[3]).norm(), 0, 1e-12);
  EXPECT_NEAR(familySideLength(patch, Family::U, true), (corners[2] - corners[1]).norm(), 1e-12);
  options.resolution = 2;
  EXPECT_THROW(options.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg
