#include "core/egg/distance_map.hpp"

#include "core/errors.hpp"
#include "synthetic_maps.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TEST(DistanceMap, InterpolationReproducesLinearFunctions) {
  DistanceMap map(5, 7);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 7; ++j) map.at(i, j) = 1.0 + 2.0 * i / 4.0 - 0.5 * j / 6.0;
  for (double x1 : {0.0, 0.13, 0.5, 0.77, 1.0})
    for (double x2 : {0.0, 0.31, 0.5, 0.92, 1.0})
      EXPECT_NEAR(map.interpolate(x1, x2), 1.0 + 2.0 * x1 - 0.5 * x2, 1e-14);
}

TEST(DistanceMap, PlanarMapIsClosedForm) {
  const auto quad = *planarQuad({2.0, 1.2, 1.6, 1.0}, 1.3);
  const auto map = planarDistanceMap(quad, Family::V, 11, 11);
  EXPECT_NEAR(map.at(0, 0), 1.0, 1e-14);                     // side c0c3
  EXPECT_NEAR(map.at(10, 10), 1.2, 1e-14);                   // side c1c2
  EXPECT_NEAR(map.at(0, 10), planarDiagonalE(quad), 1e-14);  // c0 to c2
  EXPECT_NEAR(map.at(10, 0), planarDiagonalF(quad), 1e-14);  // c1 to c3
  EXPECT_NEAR(map.at(3, 7), planarDistance(quad, Family::V, 0.3, 0.7), 1e-14);
}

TEST(DistanceMap, DiagonalProductSignsAroundTheSpatialAngle) {
  // A planar patch: at alpha_bar = alpha both diagonals agree (product 0); moving alpha_bar grows
  // one diagonal and shrinks the other, so the product is negative on both sides (2.2).
  const auto maps =
      testing::planarPatchMaps({Eigen::Vector2d(0, 0), {2, 0}, {1.8, 1.2}, {0.3, 1.0}}, 9);
  EXPECT_NEAR(diagonalProduct(maps, *planarQuad(maps.sides, maps.alphaSpatial)), 0.0, 1e-12);
  EXPECT_LT(diagonalProduct(maps, *planarQuad(maps.sides, maps.alphaSpatial - 0.1)), 0.0);
  EXPECT_LT(diagonalProduct(maps, *planarQuad(maps.sides, maps.alphaSpatial + 0.1)), 0.0);
}

TEST(DistanceMap, ValidateNamesTheProblem) {
  auto maps = testing::planarPatchMaps({Eigen::Vector2d(0, 0), {1, 0}, {1, 1}, {0, 1}}, 5);
  EXPECT_NO_THROW(maps.validate());
  maps.u.at(2, 2) = std::nan("");
  EXPECT_THROW(maps.validate(), InvalidInput);
  maps = testing::planarPatchMaps({Eigen::Vector2d(0, 0), {1, 0}, {1, 1}, {0, 1}}, 5);
  maps.v.values.pop_back();
  EXPECT_THROW(maps.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg
