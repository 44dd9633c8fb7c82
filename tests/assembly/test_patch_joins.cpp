// Layer swaps and join bolts between neighbouring patches (3.5.3) on hand-made grids: two 3 x 3
// grids side by side share the line x = 2, where patch A's last v member meets patch B's first.
#include "assembly/patch_joins.hpp"

#include "tests/support/three_by_three_grid.hpp"

#include <gtest/gtest.h>

namespace egg::assembly {
namespace {

using patching::BoundaryKind;

EggGrid shifted(double dx) {
  EggGrid grid = testing::threeByThree();
  const Eigen::Vector3d shift(dx, 0, 0.1 * dx);  // the plane z = 0.1 x continues
  for (auto& c : grid.connections) c.spatial += shift;
  for (auto* family : {&grid.u, &grid.v})
    for (auto& m : *family)
      for (auto& p : m.spatial) p += shift;
  return grid;
}

// A's side 1 (its last v member, x = 2) against B's side 3 (its v member 0, at x = 2 too).
patching::Boundary side(int id, int a, int b) {
  return {id, BoundaryKind::Shared, {{a, 1, 0.0, 1.0, false}, {b, 3, 0.0, 1.0, true}}, 2.0};
}

TEST(PatchJoins, NeighboursWithBoundaryLamellasOfOneFamilySwapLayersAndBoltAtEveryConnection) {
  const EggGrid a = shifted(0.0), b = shifted(2.0);
  patching::PatchGraph graph;
  graph.boundaries.push_back(side(0, 0, 1));
  const std::vector<const EggGrid*> grids{&a, &b};
  const std::vector<char> swapped = layerSwaps(graph, grids);
  EXPECT_EQ(swapped, (std::vector<char>{0, 1}));  // both lamellas are v members: B swaps
  const PatchJoins joins = patchJoins(graph, grids, swapped, 0.01);
  EXPECT_EQ(joins.sidesJoined, 1);
  EXPECT_EQ(joins.sidesSkipped, 0);
  ASSERT_EQ(joins.bolts.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const rods::PatchJoin& bolt = joins.bolts[i];
    EXPECT_EQ(bolt.patchA, 0);
    EXPECT_EQ(bolt.rodA, 5);  // 3 u rods, then v member 2
    EXPECT_EQ(bolt.patchB, 1);
    EXPECT_EQ(bolt.rodB, 3);  // v member 0
    EXPECT_DOUBLE_EQ(bolt.sAM, i * 1.0);
    EXPECT_DOUBLE_EQ(bolt.sBM, i * 1.0);
  }
  // Unswapped, the two lamellas would lie in one layer: the side is counted, not bolted.
  const PatchJoins same = patchJoins(graph, grids, {0, 0}, 0.01);
  EXPECT_TRUE(same.bolts.empty());
  EXPECT_EQ(same.sidesSkipped, 1);
  // Ends farther apart than the tolerance are not bolted.
  const EggGrid far = shifted(2.5);
  EXPECT_TRUE(patchJoins(graph, {&a, &far}, swapped, 0.01).bolts.empty());
}

TEST(PatchJoins, AnOddCycleOfPatchesLeavesOneSideUnbolted) {
  const EggGrid a = shifted(0.0), b = shifted(2.0), c = shifted(2.0);
  patching::PatchGraph graph;
  graph.boundaries.push_back(side(0, 0, 1));
  graph.boundaries.push_back(side(1, 0, 2));
  graph.boundaries.push_back(side(2, 1, 2));
  const std::vector<const EggGrid*> grids{&a, &b, &c};
  const std::vector<char> swapped = layerSwaps(graph, grids);
  EXPECT_EQ(swapped, (std::vector<char>{0, 1, 1}));
  const PatchJoins joins = patchJoins(graph, grids, swapped, 0.01);
  EXPECT_EQ(joins.sidesJoined, 2);
  EXPECT_EQ(joins.sidesSkipped, 1);
  EXPECT_EQ(joins.bolts.size(), 6u);
}

TEST(PatchJoins, APatchWithoutAGridIsNeitherSwappedNorBolted) {
  const EggGrid a = shifted(0.0);
  patching::PatchGraph graph;
  graph.boundaries.push_back(side(0, 0, 1));
  const std::vector<const EggGrid*> grids{&a, nullptr};
  EXPECT_EQ(layerSwaps(graph, grids), (std::vector<char>{0, 0}));
  const PatchJoins joins = patchJoins(graph, grids, {0, 0}, 0.01);
  EXPECT_TRUE(joins.bolts.empty());
  EXPECT_EQ(joins.sidesJoined + joins.sidesSkipped, 0);
}

}  // namespace
}  // namespace egg::assembly
