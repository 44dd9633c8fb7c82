#include "patching/patch_graph.hpp"

#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/bump_layout.hpp"

#include <gtest/gtest.h>

namespace egg::patching {
namespace {

const std::vector<std::array<int, 4>> kGraphTwoByTwo{
    {0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}};

std::vector<std::vector<int>> cutAll(const PatchLayout& layout) {
  std::vector<std::vector<int>> faces;
  for (size_t p = 0; p < layout.patches.size(); ++p)
    faces.push_back(cutLayoutPatch(layout, static_cast<int>(p)).layoutFace);
  return faces;
}

TEST(PatchGraph, TwoByTwoHasFourSharedSidesAndFourChains) {
  const TriMesh surface = samples::generateSample(
      "bump", {{"length", 8}, {"width", 8}, {"height", 1}, {"sigma", 1.5}}, 0.3);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout =
      makeLayout(surface, solver, testing::bumpLayoutCorners(surface, 3.0), kGraphTwoByTwo);
  const PatchGraph graph = buildPatchGraph(layout);
  int shared = 0, free = 0;
  for (const auto& b : graph.boundaries) {
    if (b.kind == BoundaryKind::Shared) {
      ++shared;
      ASSERT_EQ(b.uses.size(), 2u);
      // A shared side runs against itself on the two patches (both are counter-clockwise).
      EXPECT_NE(b.uses[0].reversed, b.uses[1].reversed);
      EXPECT_EQ(b.uses[0].from, 0.0);
      EXPECT_EQ(b.uses[0].to, 1.0);
    }
    if (b.kind == BoundaryKind::Free) ++free;
  }
  EXPECT_EQ(shared, 4);
  EXPECT_EQ(free, 8);
  EXPECT_EQ(graph.adjacent.size(), 4u);  // 0-1, 0-2, 1-3, 2-3
  ASSERT_EQ(graph.chains.size(), 4u);
  // u runs from side 3 to side 1: patch 0 -> patch 1 and patch 2 -> patch 3; v from side 0 to 2:
  // 0 -> 2 and 1 -> 3.
  std::set<std::vector<std::pair<int, int>>> chains;
  for (const auto& c : graph.chains) {
    EXPECT_FALSE(c.ring);
    EXPECT_FALSE(c.branching);
    std::vector<std::pair<int, int>> nodes;
    for (const auto& n : c.nodes) nodes.emplace_back(n.patch, n.family == Family::U ? 0 : 1);
    chains.insert(nodes);
  }
  EXPECT_TRUE(chains.count({{0, 0}, {1, 0}}));
  EXPECT_TRUE(chains.count({{2, 0}, {3, 0}}));
  EXPECT_TRUE(chains.count({{0, 1}, {2, 1}}));
  EXPECT_TRUE(chains.count({{1, 1}, {3, 1}}));
}

TEST(PatchGraph, PlaneCutIntoFourIsFullyCovered) {
  const TriMesh surface = samples::generateSample("plane", {{"length", 6}, {"width", 6}}, 0.4);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout =
      makeLayout(surface, solver, testing::bumpLayoutCorners(surface, 3.0), kGraphTwoByTwo);
  const Coverage coverage = computeCoverage(layout, cutAll(layout));
  EXPECT_NEAR(coverage.fraction, 1.0, 1e-12);
  EXPECT_NEAR(coverage.coveredAreaM2, 36.0, 1e-9);
  EXPECT_TRUE(coverage.cutOffs.empty());
  // Three of the four: the fourth quarter is one cut-off of 9 m^2.
  auto faces = cutAll(layout);
  faces[3].clear();
  const Coverage three = computeCoverage(layout, faces);
  EXPECT_NEAR(three.fraction, 0.75, 1e-12);
  ASSERT_EQ(three.cutOffs.size(), 1u);
  EXPECT_NEAR(three.cutOffs[0].areaM2, 9.0, 1e-9);
  EXPECT_NEAR(three.cutOffs[0].centroid.x(), 1.5, 1e-9);
}

TEST(PatchGraph, TJunctionIsReported) {
  const TriMesh surface = samples::generateSample("plane", {{"length", 6}, {"width", 6}}, 0.4);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout = makeLayout(surface, solver, testing::bumpLayoutCorners(surface, 3.0),
                                        {{0, 1, 7, 6}, {1, 2, 5, 4}, {4, 5, 8, 7}});
  const PatchGraph graph = buildPatchGraph(layout);
  ASSERT_EQ(graph.tJunctions.size(), 1u);
  EXPECT_EQ(graph.tJunctions[0].corner, 4);
  EXPECT_EQ(graph.tJunctions[0].patchesThrough, std::vector<int>{0});
  EXPECT_EQ(graph.tJunctions[0].patchesAt, (std::vector<int>{1, 2}));
  int tKind = 0;
  for (const auto& b : graph.boundaries) tKind += b.kind == BoundaryKind::TJunction;
  EXPECT_EQ(tKind, 2);
  // u members of patch 0 leave through side 1 into both right patches: a branching chain.
  bool branching = false;
  for (const auto& c : graph.chains) branching = branching || c.branching;
  EXPECT_TRUE(branching);
  EXPECT_NEAR(computeCoverage(layout, cutAll(layout)).fraction, 1.0, 1e-12);
}

}  // namespace
}  // namespace egg::patching
