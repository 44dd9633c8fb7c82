#include "patching/workflow1.hpp"

#include "core/geodesic/distance_solver.hpp"
#include "patching/patch_graph.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

namespace egg::patching {
namespace {

// A 1.8 m tall Gaussian bump (sigma 1.5 m) on 8 x 8 m: too tall for one patch over its peak.
TriMesh workflowTallBump() {
  return samples::generateSample(
      "bump", {{"height", 1.8}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.35);
}

LayoutDesignOptions workflow1() {
  LayoutDesignOptions options;
  options.design.maps.resolution = 41;
  options.design.uniqueness.smooth = false;  // Workflow 1 splits instead
  options.split = true;
  return options;
}

PatchLayout layoutOf(const TriMesh& surface, const geodesic::DistanceSolver& solver,
                     const std::vector<Eigen::Vector3d>& corners,
                     const std::vector<std::array<int, 4>>& quads) {
  std::vector<Eigen::Vector3d> snapped;
  for (const auto& c : corners)
    snapped.push_back(position(surface, geodesic::snapToSurface(surface, c)));
  return makeLayout(surface, solver, snapped, quads);
}

TEST(Workflow1, SlowOneFamilyFailingGetsASideOverThePeakAndANeighbourATJunction) {
  const TriMesh surface = workflowTallBump();
  const geodesic::DistanceSolver solver(surface);
  // Patch 0: 6 x 2 m across the peak (its u members, along x, fail eta; Section 3.4.1). Patch 1:
  // its neighbour below y = -1, which shares patch 0's side 0.
  const PatchLayout initial =
      layoutOf(surface, solver,
               {{-3, -1, 0}, {3, -1, 0}, {3, 1, 0}, {-3, 1, 0}, {-3, -1.9, 0}, {3, -1.9, 0}},
               {{0, 1, 2, 3}, {4, 5, 1, 0}});
  const LayoutDesign result = designLayout(initial, solver, workflow1());
  ASSERT_EQ(result.splits.size(), 1u);
  EXPECT_EQ(result.splits[0].kind, "side over p_max across the u members (eta)");
  EXPECT_EQ(result.splits[0].children.size(), 2u);
  ASSERT_EQ(result.patches.size(), 3u);  // the neighbour and the two halves
  for (const auto& p : result.patches) {
    EXPECT_TRUE(p.feasible()) << p.failure;
    ASSERT_TRUE(p.design);
    EXPECT_EQ(p.design->uniqueness.smoothingRounds, 0);  // split, not smoothed
    EXPECT_LE(std::max(p.design->uniqueness.etaU, p.design->uniqueness.etaV), 1.0015);
  }
  // The new side runs over the peak (the bump top at the origin) and ends on the neighbour's side.
  const PatchGraph graph = buildPatchGraph(result.layout);
  ASSERT_EQ(graph.tJunctions.size(), 1u);
  EXPECT_EQ(graph.tJunctions[0].patchesThrough, std::vector<int>{0});  // the neighbour, now patch 0
  const auto& newCurve = result.layout.curves.back();
  double closest = 1e9;
  for (const auto& p : newCurve.positions) closest = std::min(closest, p.head<2>().norm());
  EXPECT_LT(closest, 0.3);
  EXPECT_NEAR(
      computeCoverage(result.layout,
                      {result.patches[0].cut->layoutFace, result.patches[1].cut->layoutFace,
                       result.patches[2].cut->layoutFace})
          .coveredAreaM2,
      [&] {
        double a = 0;
        for (const auto& p : result.patches) a += p.cut->patch.area;
        return a;
      }(),
      1e-9);
}

TEST(Workflow1, SlowBothFamiliesFailingGetACornerAtThePeak) {
  const TriMesh surface = workflowTallBump();
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout initial =
      layoutOf(surface, solver, {{-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, {{0, 1, 2, 3}});
  const LayoutDesign result = designLayout(initial, solver, workflow1());
  ASSERT_GE(result.splits.size(), 1u);
  EXPECT_EQ(result.splits[0].kind, "corner at p_max (eta, u and v)");
  EXPECT_LT(result.splits[0].peak.head<2>().norm(), 0.3);
  ASSERT_EQ(result.patches.size(), 4u);
  for (const auto& p : result.patches) EXPECT_TRUE(p.feasible()) << p.failure;
  // The four quarters meet at one corner, the peak.
  std::map<int, int> uses;
  for (const auto& q : result.layout.patches)
    for (int c : q) ++uses[c];
  int shared = -1;
  for (const auto& [c, n] : uses)
    if (n == 4) shared = c;
  ASSERT_GE(shared, 0);
  EXPECT_LT(result.layout.corners[shared].head<2>().norm(), 0.3);
}

TEST(Workflow1, SlowAnImpossibleLayoutEndsWithAClearReason) {
  const TriMesh surface = workflowTallBump();
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout initial =
      layoutOf(surface, solver, {{-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, {{0, 1, 2, 3}});
  LayoutDesignOptions options = workflow1();
  options.maxSplits = 0;
  const LayoutDesign result = designLayout(initial, solver, options);
  ASSERT_EQ(result.patches.size(), 1u);
  EXPECT_FALSE(result.patches[0].feasible());
  EXPECT_NE(result.patches[0].failure.find("split budget"), std::string::npos)
      << result.patches[0].failure;
  // A minimum size larger than the patch: not split either.
  options.maxSplits = 10;
  options.minSideM = 4.0;
  const LayoutDesign small = designLayout(initial, solver, options);
  ASSERT_EQ(small.patches.size(), 1u);
  EXPECT_NE(small.patches[0].failure.find("minimum patch size"), std::string::npos)
      << small.patches[0].failure;
}

TEST(Workflow1, AGivenLayoutIsDesignedAsItIs) {
  const TriMesh surface = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.35);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout initial = layoutOf(
      surface, solver, {{-3, -3, 0}, {0, -3, 0}, {0, 3, 0}, {-3, 3, 0}, {3, -3, 0}, {3, 3, 0}},
      {{0, 1, 2, 3}, {1, 4, 5, 2}});
  LayoutDesignOptions options = workflow1();
  options.split = false;
  const LayoutDesign result = designLayout(initial, solver, options);
  EXPECT_TRUE(result.splits.empty());
  ASSERT_EQ(result.patches.size(), 2u);
  EXPECT_EQ(result.evaluations, 2);
  for (const auto& p : result.patches) EXPECT_TRUE(p.feasible()) << p.failure;
}

}  // namespace
}  // namespace egg::patching
