// The per-patch simulation's supports: patch by patch, every connection on a patch's four sides
// is held (Section 3.5.2, strategy iv; the thesis' patches were simulated apart on supports along
// their boundaries, Fig. 3.17).
#include "apps/commands/patch_stage.hpp"

#include "apps/commands/grid_to_rods.hpp"
#include "core/materials/materials.hpp"

#include <gtest/gtest.h>

namespace egg::app {
namespace {

// Three u members crossing three v members on the plane z = 0.1 x; the middle connection (1, 1)
// is the only one not on a side.
EggGrid threeByThree() {
  EggGrid grid;
  for (int k = 0; k < 3; ++k) {
    GridMember u;
    u.family = Family::U;
    u.index = k;
    u.boundary = k != 1;
    u.spatial = {{0, double(k), 0}, {2, double(k), 0.2}};
    u.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    u.planarLength = u.spatialLength = (u.spatial[1] - u.spatial[0]).norm();
    grid.u.push_back(u);
    GridMember v = u;
    v.family = Family::V;
    v.spatial = {{double(k), 0, 0.1 * k}, {double(k), 2, 0.1 * k}};
    v.planarLength = v.spatialLength = 2.0;
    grid.v.push_back(v);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      GridConnection c;
      c.memberU = i;
      c.memberV = j;
      c.spatial = Eigen::Vector3d(j, i, 0.1 * j);
      c.normal = Eigen::Vector3d(-0.1, 0, 1) * 3.0;  // not unit on purpose
      c.sBarU = j * grid.u[i].planarLength / 2.0;
      c.sBarV = i * 1.0;
      c.onBoundary = i != 1 || j != 1;
      grid.connections.push_back(c);
    }
  }
  grid.anchors.push_back({0, "corner"});
  grid.anchors.push_back({8, "corner"});
  return grid;
}

TEST(PatchStage, HoldEverySideAddsASupportAtEachBoundaryConnectionNotAnchoredYet) {
  const EggGrid grid = threeByThree();
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
    EXPECT_DOUBLE_EQ(a.s_m, c.sBarU) << k;
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
}  // namespace egg::app
