// Sides, shared lamellas, free sides and design-boundary supports on hand-made grids and graphs
// whose answers are counted by hand (Section 3.5.3).
#include "assembly/boundary_members.hpp"

#include "tests/support/three_by_three_grid.hpp"

#include <gtest/gtest.h>

namespace egg::assembly {
namespace {

using patching::BoundaryKind;

TEST(BoundaryMembers, EachSideRunsAlongItsBoundaryMemberWithItsConnections) {
  const EggGrid grid = testing::threeByThree();  // connection (i, j) at index 3 i + j
  const BoundaryLamella side1 = boundaryLamella(grid, PatchSide(1));
  EXPECT_EQ(side1.family, Family::V);
  EXPECT_EQ(side1.member, 2);
  EXPECT_EQ(side1.rod, 5);  // after the 3 u rods
  EXPECT_EQ(sideConnections(grid, PatchSide(0)), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(sideConnections(grid, PatchSide(1)), (std::vector<int>{2, 5, 8}));
  EXPECT_EQ(sideConnections(grid, PatchSide(2)), (std::vector<int>{6, 7, 8}));
  EXPECT_EQ(sideConnections(grid, PatchSide(3)), (std::vector<int>{0, 3, 6}));
  for (int k = 0; k < 4; ++k)
    for (int c : sideConnections(grid, PatchSide(k)))
      EXPECT_TRUE(grid.connections[c].onBoundary) << k << " " << c;
}

TEST(BoundaryMembers, FreeSidesFromThePatchGraph) {
  // Patch 0: side 2 on the design boundary, side 1 shared with patch 1's side 3, side 0 half free
  // and half a T-junction: free (a support may stand on its free part). Patch 7 is not in the
  // graph (one patch, no graph): all four sides free.
  patching::PatchGraph graph;
  graph.boundaries.push_back({0, BoundaryKind::Free, {{0, 2, 0.0, 1.0, false}}, 10.0});
  graph.boundaries.push_back(
      {1, BoundaryKind::Shared, {{0, 1, 0.0, 1.0, false}, {1, 3, 0.0, 1.0, true}}, 8.0});
  graph.boundaries.push_back({2, BoundaryKind::Free, {{0, 0, 0.0, 0.5, false}}, 4.0});
  graph.boundaries.push_back(
      {3, BoundaryKind::TJunction, {{0, 0, 0.5, 1.0, false}, {2, 2, 0.0, 1.0, true}}, 4.0});
  EXPECT_EQ(freeSides(graph, 0), (std::array<bool, 4>{true, false, true, false}));
  EXPECT_EQ(freeSides(graph, 1), (std::array<bool, 4>{false, false, false, false}));
  EXPECT_EQ(freeSides(graph, 7), (std::array<bool, 4>{true, true, true, true}));
  EXPECT_TRUE(isWholeSharedSide(graph.boundaries[1]));
  EXPECT_FALSE(isWholeSharedSide(graph.boundaries[3]));
}

TEST(BoundaryMembers, SharedLamellaeNameBothBoundaryMembersAndTheirDirection) {
  const EggGrid a = testing::threeByThree(), b = testing::threeByThree();
  patching::PatchGraph graph;
  // Patch 0's side 1 (last v member, with its corners) against patch 1's side 3 (v member 0,
  // against its corners): the segment runs with side 1 and against side 3 (reversed use), so both
  // lamellas run the same way along it.
  graph.boundaries.push_back(
      {0, BoundaryKind::Shared, {{0, 1, 0.0, 1.0, false}, {1, 3, 0.0, 1.0, true}}, 2.0});
  // Patch 0's side 2 (last u member, against its corners) on the segment as it runs: against.
  graph.boundaries.push_back(
      {1, BoundaryKind::Shared, {{0, 2, 0.0, 1.0, false}, {2, 0, 0.0, 1.0, false}}, 2.0});
  graph.boundaries.push_back({2, BoundaryKind::Free, {{0, 0, 0.0, 1.0, false}}, 2.0});
  const auto shared = sharedLamellae(graph, {&a, &b, nullptr});
  ASSERT_EQ(shared.size(), 1u);  // patch 2 has no grid
  EXPECT_EQ(shared[0].patchA, 0);
  EXPECT_EQ(shared[0].familyA, Family::V);
  EXPECT_EQ(shared[0].indexA, 2);
  EXPECT_EQ(shared[0].patchB, 1);
  EXPECT_EQ(shared[0].familyB, Family::V);
  EXPECT_EQ(shared[0].indexB, 0);
  EXPECT_FALSE(shared[0].reversed);
  const EggGrid c = testing::threeByThree();
  const auto both = sharedLamellae(graph, {&a, &b, &c});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].familyA, Family::U);
  EXPECT_EQ(both[1].indexA, 2);
  EXPECT_EQ(both[1].familyB, Family::U);
  EXPECT_EQ(both[1].indexB, 0);
  EXPECT_TRUE(both[1].reversed);  // side 2 runs against its corners, side 0 with them
}

TEST(BoundaryMembers, DesignBoundarySupportsHoldEveryConnectionOfAFreeSideOnce) {
  EggGrid grid = testing::threeByThree();  // anchors at connections 0 and 8
  patching::PatchGraph graph;
  graph.boundaries.push_back({0, BoundaryKind::Free, {{0, 0, 0.0, 1.0, false}}, 2.0});  // 0, 1, 2
  graph.boundaries.push_back({1, BoundaryKind::Free, {{0, 1, 0.0, 1.0, false}}, 2.0});  // 2, 5, 8
  graph.boundaries.push_back(
      {2, BoundaryKind::Shared, {{0, 2, 0.0, 1.0, false}, {1, 0, 0.0, 1.0, true}}, 2.0});
  EXPECT_EQ(supportDesignBoundary(graph, {&grid, nullptr}), 3);  // 1, 2, 5
  ASSERT_EQ(grid.anchors.size(), 5u);
  std::vector<int> held;
  for (const auto& anchor : grid.anchors) held.push_back(anchor.connection);
  EXPECT_EQ(held, (std::vector<int>{0, 8, 1, 2, 5}));
  EXPECT_EQ(grid.anchors.back().reason, "design boundary support");
  EXPECT_EQ(supportDesignBoundary(graph, {&grid, nullptr}), 0);  // nothing new the second time
}

}  // namespace
}  // namespace egg::assembly
