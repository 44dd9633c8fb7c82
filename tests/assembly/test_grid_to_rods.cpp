#include "assembly/grid_to_rods.hpp"

#include "tests/support/three_by_three_grid.hpp"

#include <gtest/gtest.h>

namespace egg::assembly {
namespace {

// Two u members (boundary, inner) crossing two v members; the inner-inner connection carries
// notches of opposite sign.
EggGrid smallGrid() {
  EggGrid grid;
  for (int k = 0; k < 2; ++k) {
    GridMember u;
    u.family = Family::U;
    u.index = k;
    u.boundary = k == 0;
    u.spatial = {{0, double(k), 0}, {2, double(k), 0.1}};
    u.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    u.spatialLength = 2.0025;
    u.planarLength = 2.0;
    grid.u.push_back(u);
    GridMember v = u;
    v.family = Family::V;
    v.boundary = k == 0;
    v.spatial = {{double(k), 0, 0}, {double(k), 2, 0.1}};
    v.planarLength = 2.5;
    grid.v.push_back(v);
  }
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      GridConnection c;
      c.memberU = i;
      c.memberV = j;
      c.spatial = Eigen::Vector3d(j, i, 0.05);
      c.normal = Eigen::Vector3d(0, 0, 2);  // not unit on purpose
      c.sBarU = j * 1.0;
      c.sBarV = i * 1.0;
      c.onBoundary = i == 0 || j == 0;
      // Notch lengths everywhere, even on the boundary: the converter must drop those (boundary
      // members carry no notches, Section 2.4.5).
      c.notchU = 0.03;   // slides towards the end of the u member
      c.notchV = -0.02;  // towards the start of the v member
      grid.connections.push_back(c);
    }
  }
  grid.anchors.push_back({0, "corner"});
  return grid;
}

GridToRodsOptions options() {
  GridToRodsOptions o;
  o.section = {0.1, 0.01};
  o.material = materialByName("poplar_plywood");
  return o;
}

TEST(GridToRods, MembersBecomeStraightRodsInTwoLayers) {
  const auto network = rodNetworkFromGrid(smallGrid(), options());
  ASSERT_EQ(network.rods.size(), 4u);
  EXPECT_EQ(network.rods[0].layer, 0);
  EXPECT_EQ(network.rods[3].layer, 1);
  EXPECT_DOUBLE_EQ(network.rods[0].lengthM, 2.0);  // the planar (cut) length, not the spatial one
  EXPECT_DOUBLE_EQ(network.rods[2].lengthM, 2.5);
  EXPECT_DOUBLE_EQ(network.rods[1].material.youngsModulusPa, 7.6e9);
  EXPECT_DOUBLE_EQ(network.rods[1].section.thicknessM, 0.01);
  EXPECT_EQ(network.rods[1].guess.size(), 2u);
  EXPECT_NO_THROW(rods::validateNetwork(network));
}

TEST(GridToRods, NotchSignGivesTheSlidingDirection) {
  const auto network = rodNetworkFromGrid(smallGrid(), options());
  ASSERT_EQ(network.connections.size(), 4u);
  const auto& inner = network.connections[3];
  EXPECT_EQ(inner.rodA, 1);
  EXPECT_EQ(inner.rodB, 3);
  EXPECT_DOUBLE_EQ(inner.notchA.afterM, 0.03);
  EXPECT_DOUBLE_EQ(inner.notchA.beforeM, 0.0);
  EXPECT_DOUBLE_EQ(inner.notchB.beforeM, 0.02);
  EXPECT_DOUBLE_EQ(inner.notchB.afterM, 0.0);
  for (int k = 0; k < 3; ++k) {  // boundary connections: plain holes
    const auto& c = network.connections[k];
    EXPECT_DOUBLE_EQ(c.notchA.afterM + c.notchA.beforeM + c.notchB.afterM + c.notchB.beforeM, 0.0)
        << k;
  }
}

TEST(GridToRods, WithoutNotchesEveryBoltIsAPlainHole) {
  auto o = options();
  o.notches = false;
  const auto network = rodNetworkFromGrid(smallGrid(), o);
  EXPECT_DOUBLE_EQ(network.connections[3].notchA.afterM, 0.0);
  EXPECT_DOUBLE_EQ(network.connections[3].notchB.beforeM, 0.0);
}

TEST(GridToRods, AnchorsHoldTheirConnectionOnTheSurface) {
  const auto network = rodNetworkFromGrid(smallGrid(), options());
  ASSERT_EQ(network.anchors.size(), 1u);
  EXPECT_EQ(network.anchors[0].rod, 0);
  EXPECT_DOUBLE_EQ(network.anchors[0].sM, 0.0);
  EXPECT_TRUE(network.anchors[0].position.isApprox(Eigen::Vector3d(0, 0, 0.05)));
  EXPECT_NEAR(network.anchors[0].normal.norm(), 1.0, 1e-15);
}

TEST(GridToRods, HoldEverySideAddsASupportAtEachBoundaryConnectionNotAnchoredYet) {
  const EggGrid grid = testing::threeByThree();
  GridToRodsOptions convert;
  convert.section = {0.1, 0.01};
  convert.material = materialByName("poplar_plywood");
  const rods::RodNetwork anchored = rodNetworkFromGrid(grid, convert);
  ASSERT_EQ(anchored.anchors.size(), 2u);
  const rods::RodNetwork held = holdEverySide(anchored, grid);
  // 8 connections on the sides, 2 of them anchors already: 6 more, none at the middle one.
  ASSERT_EQ(held.anchors.size(), 8u);
  const std::vector<int> added{1, 2, 3, 5, 6, 7};
  for (size_t k = 0; k < added.size(); ++k) {
    const GridConnection& c = grid.connections[added[k]];
    const rods::Anchor& a = held.anchors[2 + k];
    EXPECT_EQ(a.rod, c.memberU) << k;
    EXPECT_DOUBLE_EQ(a.sM, c.sBarU) << k;
    EXPECT_EQ(a.position, c.spatial) << k;
    EXPECT_NEAR(a.normal.norm(), 1.0, 1e-15) << k;
    EXPECT_NEAR(a.normal.dot(c.normal.normalized()), 1.0, 1e-15) << k;
  }
  // The network itself is unchanged otherwise (same rods and bolts), and validates.
  EXPECT_EQ(held.rods.size(), anchored.rods.size());
  EXPECT_EQ(held.connections.size(), anchored.connections.size());
  EXPECT_NO_THROW(rods::validateNetwork(held));
}

}  // namespace
}  // namespace egg::assembly
