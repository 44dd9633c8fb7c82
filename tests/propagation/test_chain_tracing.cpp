// Tracing a layout in member order (C0 closed on the traced member ends) on the 2 x 2 bump that
// the pipeline tests use, and the head-on case a consistently oriented layout avoids.
#include "propagation/chain_tracing.hpp"

#include "core/geodesic/distance_solver.hpp"
#include "patching/workflow1.hpp"
#include "propagation/patch_sides.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

namespace egg::propagation {
namespace {

struct Designed {
  TriMesh surface;
  std::unique_ptr<geodesic::DistanceSolver> solver;
  patching::LayoutDesign layout;
  patching::PatchGraph graph;
  std::vector<const PatchDesign*> designs;
  std::vector<PatchSideData> sides;
};

// The bump of tests/apps/test_pipeline.cpp, corners (i, j) = 3 j + i on a 3 m grid around the peak.
std::unique_ptr<Designed> designBump(const std::vector<std::array<int, 4>>& quads) {
  auto d = std::make_unique<Designed>();
  d->surface = samples::generateSample(
      "bump", {{"length", 8}, {"width", 8}, {"height", 1}, {"sigma", 1.5}}, 0.4);
  d->solver = std::make_unique<geodesic::DistanceSolver>(d->surface);
  std::vector<Eigen::Vector3d> corners;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      corners.push_back(position(
          d->surface, geodesic::snapToSurface(d->surface, {-3.0 + 3.0 * i, -3.0 + 3.0 * j, 0.0})));
  patching::LayoutDesignOptions options;
  options.design.maps.resolution = 30;
  options.design.members.count = 4;
  options.design.members.lamellaWidthM = 0.05;
  options.design.uniqueness.smooth = true;
  d->layout = patching::designLayout(patching::makeLayout(d->surface, *d->solver, corners, quads),
                                     *d->solver, options);
  std::vector<bool> usable;
  for (const auto& p : d->layout.patches) usable.push_back(p.cut.has_value());
  d->graph = patching::buildPatchGraph(d->layout.layout, usable);
  for (const auto& p : d->layout.patches) {
    d->designs.push_back(p.feasible() ? &*p.design : nullptr);
    d->sides.push_back(p.feasible() ? patchSideData(*p.design, 0.05) : PatchSideData{});
  }
  return d;
}

PropagationOptions fourMembers() {
  PropagationOptions o;
  o.members = 4;
  o.lamellaWidthM = 0.05;
  return o;
}

TEST(ChainTracing, SlowTwoByTwoBumpMembersMeetOnEverySharedSide) {
  const auto d = designBump({{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}});
  for (const auto* design : d->designs) ASSERT_NE(design, nullptr);
  const LayoutPropagation members = propagateLayout(d->graph, d->sides, fourMembers());
  ASSERT_EQ(members.chains.size(), 4u);
  EXPECT_LE(members.evennessAfter, members.evennessBefore);
  const LayoutTracing traced = traceLayout(d->designs, members);
  EXPECT_EQ(traced.rounds, 2);  // the member runs (none waits for another), then the grids
  EXPECT_EQ(traced.matchedRuns, 0);
  EXPECT_EQ(traced.heldRuns, 0);
  ASSERT_EQ(traced.gaps.size(), 4u);
  for (const auto& gap : traced.gaps) {
    EXPECT_EQ(gap.kind, GapKind::Closed);
    EXPECT_EQ(gap.piece, PieceKind::WholeSide);
    EXPECT_EQ(gap.membersA, 4);
    EXPECT_EQ(gap.membersB, 4);
    EXPECT_LE(gap.maxGapM, 1e-6) << gap.patchA << "-" << gap.patchB;
  }
  EXPECT_LE(traced.c0MaxGapM, 1e-6);
  // Patch 1's u members start where patch 0's traced u members end (x2 after refinement).
  ASSERT_TRUE(traced.patches[0].grid && traced.patches[1].grid);
  for (int j = 1; j < 3; ++j)
    EXPECT_EQ(traced.patches[1].grid->u[j].x1, traced.patches[0].grid->u[j].x2) << j;
  // Propagation alone (without the tracing order) would leave the refinement's gap.
  double refinement = 0.0;
  for (int j = 1; j < 3; ++j)
    refinement =
        std::max(refinement, std::abs(traced.patches[0].grid->u[j].x2 - members.x1[1][0][j]));
  EXPECT_LT(refinement, 1e-3);
}

TEST(ChainTracing, SlowHeadOnMembersAreClosedByMovingAFreeStart) {
  // Patch 1 given turned by 180 degrees: both patches' u members END on their shared side, so
  // neither can start from the other's traced end. Both starts lie on free sides: patch 1's run
  // waits for patch 0's and its start is iterated until its traced end meets patch 0's (the
  // refinement alone leaves millimetres on these coarse 30 x 30 maps).
  const auto d = designBump({{0, 1, 4, 3}, {5, 4, 1, 2}});
  const LayoutPropagation members = propagateLayout(d->graph, d->sides, fourMembers());
  const LayoutTracing traced = traceLayout(d->designs, members);
  ASSERT_EQ(traced.gaps.size(), 1u);
  EXPECT_EQ(traced.gaps[0].kind, GapKind::HeadOn);
  EXPECT_LE(traced.gaps[0].maxGapM, 1e-6);
  EXPECT_EQ(traced.c0MaxGapM, traced.gaps[0].maxGapM);
  EXPECT_EQ(traced.matchedRuns, 2);  // the two inner u members of patch 1
  EXPECT_EQ(traced.heldRuns, 0);
  EXPECT_EQ(traced.rounds, 3);  // patch 0's runs, patch 1's (matching them), the grids
  // Patch 1's starts moved off the propagated values (by the refinement's size, well under 1 %).
  ASSERT_TRUE(traced.patches[1].grid);
  double moved = 0.0;
  for (int j = 1; j < 3; ++j)
    moved = std::max(moved, std::abs(traced.patches[1].grid->u[j].x1 - members.x1[1][0][j]));
  EXPECT_GT(moved, 1e-9);
  EXPECT_LT(moved, 1e-2);
}

TEST(ChainTracing, SlowTJunctionMemberEndsAtTheSmallerPatchesCorner) {
  // Patch 0 spans the bottom row; patches 1 and 2 stand on its top side, their common corner 4
  // a T-junction on it. Patch 0's v members end on that side (x2 refined), 1's and 2's start
  // there: their inner members start from patch 0's traced ends, and patch 0's member at the T
  // (an original) has its free start iterated until its traced end is corner 4 itself.
  const auto d = designBump({{0, 2, 5, 3}, {3, 4, 7, 6}, {4, 5, 8, 7}});
  for (const auto* design : d->designs) ASSERT_NE(design, nullptr);
  const LayoutPropagation members = propagateLayout(d->graph, d->sides, fourMembers());
  for (const auto& f : members.fallbacks)
    for (const auto& n : f.nodes) EXPECT_FALSE(n.family == Family::V) << f.reason;
  EXPECT_TRUE(members.notes.empty());
  const LayoutTracing traced = traceLayout(d->designs, members);
  int tPieces = 0;
  for (const auto& gap : traced.gaps) {
    EXPECT_EQ(gap.membersA, gap.membersB) << gap.boundary;
    EXPECT_LE(gap.maxGapM, 1e-6) << gap.boundary << " " << toString(gap.kind);
    tPieces += gap.piece == PieceKind::TJunction;
  }
  EXPECT_EQ(tPieces, 2);
  EXPECT_LE(traced.c0MaxGapM, 1e-6);
  EXPECT_GE(traced.matchedRuns, 1);
  EXPECT_EQ(traced.heldRuns, 0);
  // Some traced v member of patch 0 ends at corner 4, where patches 1 and 2 meet.
  ASSERT_TRUE(traced.patches[0].grid && traced.patches[1].grid);
  const Eigen::Vector3d corner = traced.patches[1].grid->v.back().spatial.front();  // patch 1's c1
  double nearest = 1e9;
  for (const auto& m : traced.patches[0].grid->v)
    if (!m.boundary) nearest = std::min(nearest, (m.spatial.back() - corner).norm());
  EXPECT_LE(nearest, 1e-6);
}

}  // namespace
}  // namespace egg::propagation
