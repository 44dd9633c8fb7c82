// What propagation reads of a design: the cladding function as a side map, the footprint.
#include "propagation/patch_sides.hpp"

#include "core/egg/members.hpp"

#include <gtest/gtest.h>

namespace egg::propagation {
namespace {

TEST(PatchSides, CladdingMapSnapsTheEndsAndDropsRepeatedPoints) {
  CladdingFunction f;
  f.points = {{0, 0}, {0.2, 0.3}, {0.2, 0.3}, {0.6, 0.65}, {1 - 1e-17, 1}};
  const auto map = claddingMap(f);
  ASSERT_EQ(map.knots().size(), 4u);
  EXPECT_EQ(map.knots().back(), Eigen::Vector2d(1, 1));
  EXPECT_DOUBLE_EQ(map.value(0.2), 0.3);
  EXPECT_DOUBLE_EQ(map.value(0.4), 0.475);
}

TEST(PatchSides, AnInfeasibleDesignIsNotUsable) {
  PatchDesign design;
  design.patch.sideLengths = {1, 2, 3, 4};
  const auto data = patchSideData(design, 0.05);
  EXPECT_FALSE(data.usable);
  EXPECT_DOUBLE_EQ(data.sideLengths[3], 4.0);
}

TEST(PatchSides, FootprintIsTheLamellaWidthOverTheSineOfTheSmallestAngle) {
  // A 2 x 1 rectangle in the plane with F = identity: members meet their sides at right angles.
  PatchDesign design;
  design.feasible = true;
  design.patch.sideLengths = {2, 1, 2, 1};
  design.alphaBar.quad = planarQuad({2, 1, 2, 1}, M_PI / 2, 0.1).value();
  for (auto* f : {&design.alphaBar.claddingU, &design.alphaBar.claddingV})
    f->points = {{0, 0}, {1, 1}};
  const auto data = patchSideData(design, 0.05);
  EXPECT_TRUE(data.usable);
  for (int family = 0; family < 2; ++family)
    for (int end = 0; end < 2; ++end) EXPECT_NEAR(data.minGapM[family][end], 0.05, 1e-12);
}

}  // namespace
}  // namespace egg::propagation
