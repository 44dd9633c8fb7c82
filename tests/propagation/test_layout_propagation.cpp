// Propagation over patch graphs built from hand-made layouts (no surface needed: the graph reads
// only the patches' corners, sides and segments): orientation, C0 bookkeeping, rings, fallbacks.
#include "propagation/layout_propagation.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <map>

namespace egg::propagation {
namespace {

using patching::PatchLayout;

// A layout from corner-index quads: every patch side is one straight segment of unit length.
PatchLayout layoutOf(const std::vector<std::array<int, 4>>& quads) {
  PatchLayout layout;
  layout.patches = quads;
  std::map<std::pair<int, int>, int> segmentOf;
  for (const auto& q : quads) {
    std::array<patching::PatchSideSegments, 4> sides;
    for (int k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      const auto key = std::pair{std::min(a, b), std::max(a, b)};
      if (!segmentOf.count(key)) {
        segmentOf[key] = static_cast<int>(layout.segments.size());
        patching::LayoutSegment s;
        s.curve = static_cast<int>(layout.curves.size());
        s.from = key.first;
        s.to = key.second;
        s.length = 1.0;
        layout.segments.push_back(s);
        patching::LayoutCurve c;
        c.from = key.first;
        c.to = key.second;
        c.corners = {key.first, key.second};
        layout.curves.push_back(c);
      }
      sides[k] = {{segmentOf[key], a != key.first}};
    }
    layout.patchSides.push_back(sides);
  }
  return layout;
}

PatchSideData sideData(PiecewiseLinearMap u = {}, PiecewiseLinearMap v = {}) {
  PatchSideData d;
  d.usable = true;
  d.cladding = {u, v};
  d.sideLengths = {1, 1, 1, 1};
  return d;
}

PropagationOptions withMembers(int m) {
  PropagationOptions o;
  o.members = m;
  return o;
}

// 2 x 2 block of a plane: corners (i, j) = 3 j + i, patches with c0 at their lower-left corner.
std::vector<std::array<int, 4>> twoByTwo() {
  std::vector<std::array<int, 4>> quads;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      quads.push_back({3 * j + i, 3 * j + i + 1, 3 * (j + 1) + i + 1, 3 * (j + 1) + i});
  return quads;
}

TEST(LayoutPropagation, TwoByTwoPlaneWithIdentityGivesEquidistantMembers) {
  const auto graph = patching::buildPatchGraph(layoutOf(twoByTwo()));
  const std::vector<PatchSideData> patches(4, sideData());
  const auto result = propagateLayout(graph, patches, withMembers(5));
  EXPECT_EQ(result.chains.size(), 4u);  // two u chains, two v chains
  EXPECT_TRUE(result.fallbacks.empty());
  for (int p = 0; p < 4; ++p)
    for (int f = 0; f < 2; ++f) {
      ASSERT_EQ(result.x1[p][f].size(), 5u) << p;
      for (int j = 0; j < 5; ++j) EXPECT_NEAR(result.x1[p][f][j], j / 4.0, 1e-12);
    }
  EXPECT_NEAR(result.evennessAfter, 4 * 3 * 4 * (1.0 / 16),
              1e-12);  // 4 chains x 3 boundaries x 4 gaps
}

TEST(LayoutPropagation, MembersMeetOnSharedSidesWithAKnownF) {
  // Patch 0's u family continues into patch 1 (side 1 of 0 is side 3 of 1): x1 of patch 1 is
  // F_0(x1 of patch 0), the same point of the shared side.
  const PiecewiseLinearMap f0({{0, 0}, {0.4, 0.55}, {1, 1}}), f1({{0, 0}, {0.7, 0.5}, {1, 1}});
  const auto graph = patching::buildPatchGraph(layoutOf({{0, 1, 4, 3}, {1, 2, 5, 4}}));
  const auto result = propagateLayout(graph, {sideData(f0), sideData(f1)}, withMembers(6));
  ASSERT_EQ(result.nodeOf[0][0].first, result.nodeOf[1][0].first);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(result.x1[1][0][j], f0.value(result.x1[0][0][j]), 1e-12);
  EXPECT_LE(result.evennessAfter, result.evennessBefore);
}

TEST(LayoutPropagation, APatchEnteredAtItsEndSideIsReadBackwards) {
  // Patch 1 is given turned by 180 degrees: its side 1 is patch 0's side 1, run the other way.
  const PiecewiseLinearMap f0({{0, 0}, {0.4, 0.55}, {1, 1}}), f1({{0, 0}, {0.7, 0.5}, {1, 1}});
  const auto graph = patching::buildPatchGraph(layoutOf({{0, 1, 4, 3}, {5, 4, 1, 2}}));
  const auto result = propagateLayout(graph, {sideData(f0), sideData(f1)}, withMembers(6));
  ASSERT_EQ(result.chains.size(), 1u);  // the u chain of both; each v family alone falls back
  const auto [c, k] = result.nodeOf[1][0];
  ASSERT_GE(c, 0);
  const auto& chain = result.chains[c];
  EXPECT_NE(chain.nodes[0].forward, chain.nodes[1].forward);
  EXPECT_NE(chain.nodes[0].mirrored, chain.nodes[1].mirrored);
  // Member j of patch 0 ends at F_0(x1) along the side; patch 1's member m-1-j ends there too,
  // at parameter 1 - F_0(x1) of its own end side.
  for (int j = 0; j < 6; ++j)
    EXPECT_NEAR(f1.value(result.x1[1][0][5 - j]), 1.0 - f0.value(result.x1[0][0][j]), 1e-12) << j;
}

TEST(LayoutPropagation, ARingOfFourPatchesNeedNotClose) {
  // A strip of four glued into a ring (corners 0..3 below, 4..7 above, wrapping).
  std::vector<std::array<int, 4>> quads;
  for (int i = 0; i < 4; ++i) quads.push_back({i, (i + 1) % 4, (i + 1) % 4 + 4, i + 4});
  const auto graph = patching::buildPatchGraph(layoutOf(quads));
  const PiecewiseLinearMap f({{0, 0}, {0.5, 0.3}, {1, 1}});
  const std::vector<PatchSideData> patches(4, sideData(f));
  const auto result = propagateLayout(graph, patches, withMembers(5));
  const auto [c, k] = result.nodeOf[0][0];
  ASSERT_GE(c, 0);
  const auto& chain = result.chains[c];
  ASSERT_TRUE(chain.ring);
  ASSERT_EQ(chain.nodes.size(), 4u);
  EXPECT_EQ(chain.boundaries.front(), chain.boundaries.back());  // the cut side, twice
  // After four compressions by F the members do not come back to where they started.
  double mismatch = 0.0;
  for (int j = 0; j < 5; ++j)
    mismatch = std::max(mismatch,
                        std::abs(chain.solution.positions[4][j] - chain.solution.positions[0][j]));
  EXPECT_GT(mismatch, 1e-3);
  EXPECT_LE(result.evennessAfter, result.evennessBefore);
  // The cut is a piece of its own, with no joints (its members are not paired); the three other
  // shared sides of the u ring pair the inner members: 3 each.
  int cuts = 0;
  for (const auto& piece : result.pieces) {
    if (piece.kind == PieceKind::RingCut) {
      ++cuts;
      EXPECT_EQ(piece.boundary, chain.boundaries.front());
      EXPECT_EQ(piece.chain, c);
      EXPECT_TRUE(piece.joints.empty());
    } else if (piece.patchA >= 0 && result.nodeOf[piece.patchA][0].first == c) {
      EXPECT_EQ(piece.joints.size(), 3u) << piece.boundary;
    }
  }
  EXPECT_EQ(cuts, 1);
}

// A T-junction: patch 0 below two patches 1, 2 whose corner 7 lies half-way along patch 0's top
// side.
//   corners 0 1 2 (bottom), 3 7 4 (top of patch 0, 7 a T), 5 8 6 (top of 1 and 2)
// Patch 0's v members end on its side 2 and continue into patches 1 and 2 (their side 0).
PatchLayout tJunctionLayout(const std::vector<std::array<int, 4>>& extra = {}) {
  std::vector<std::array<int, 4>> quads{{0, 2, 4, 3}, {3, 7, 8, 5}, {7, 4, 6, 8}};
  quads.insert(quads.end(), extra.begin(), extra.end());
  auto layout = layoutOf(quads);
  // Patch 0's side 2 runs 4 -> 3 through 7: two segments.
  const int s37 = layout.patchSides[1][0][0].first, s74 = layout.patchSides[2][0][0].first;
  layout.patchSides[0][2] = {{s74, false}, {s37, true}};
  return layout;
}

TEST(LayoutPropagation, ATJunctionMemberIsKept) {
  const auto graph = patching::buildPatchGraph(tJunctionLayout());
  // F_v of patch 0 kinked at (0.4, 0.55): the member that ends at the T (x2 = 0.5) starts at
  // x1 = 0.4 * 0.5 / 0.55. Patches 1 and 2 read identity maps.
  const PiecewiseLinearMap f0({{0, 0}, {0.4, 0.55}, {1, 1}});
  std::vector<PatchSideData> patches{sideData({}, f0), sideData(), sideData()};
  const auto result = propagateLayout(graph, patches, withMembers(4));
  for (const auto& f : result.fallbacks)
    for (const auto& n : f.nodes)
      EXPECT_EQ(n.family, Family::U) << f.reason;  // only patch 0's lone u family
  EXPECT_TRUE(result.notes.empty()) << result.notes.front();
  const auto& x0 = result.x1[0][1];
  // Patch 0 first (the sub-chains are single patches: the first is the lowest): the T is an
  // original, and each half of its side (0.5 m on its end side) gets round(0.5 / (1/3)) - 1 = 1
  // free member.
  ASSERT_EQ(x0.size(), 5u);
  int atT = -1;
  for (int j = 0; j < 5; ++j)
    if (std::abs(f0.value(x0[j]) - 0.5) < 1e-12) atT = j;
  ASSERT_EQ(atT, 2);
  EXPECT_NEAR(x0[2], 0.4 * 0.5 / 0.55, 1e-12);
  // Patches 1 and 2 take patch 0's members on their halves. Patch 0's v parameter on its side 2
  // runs 3 <- 7 <- 4, so x2 in [0, 0.5] lies on 3 -> 7, patch 1's side 0, at x = 2 x2; x2 in
  // [0.5, 1] on 7 -> 4, patch 2's side 0, at x = 2 x2 - 1.
  ASSERT_EQ(result.x1[1][1].size(), 3u);
  ASSERT_EQ(result.x1[2][1].size(), 3u);
  EXPECT_NEAR(result.x1[1][1][1], 2.0 * f0.value(x0[1]), 1e-12);
  EXPECT_NEAR(result.x1[2][1][1], 2.0 * f0.value(x0[3]) - 1.0, 1e-12);
  EXPECT_EQ(result.originals, 3);  // the T on patch 0, patch 0's members inside each half
  // Both pieces: the same members on both sides, paired by joints of equal points.
  int pieces = 0;
  for (const auto& piece : result.pieces) {
    if (piece.kind != PieceKind::TJunction) continue;
    ++pieces;
    EXPECT_EQ(piece.membersA, 3);
    EXPECT_EQ(piece.membersB, 3);
    EXPECT_EQ(piece.joints.size(),
              2u);  // the inner member, and the T member against a boundary member
    for (int j : piece.joints) {
      const auto& joint = result.joints[j];
      const double xa = joint.a.atEnd ? f0.value(result.x1[joint.a.patch][1][joint.a.member])
                                      : result.x1[joint.a.patch][1][joint.a.member];
      const double xb = result.x1[joint.b.patch][1][joint.b.member];
      EXPECT_NEAR(joint.offset + joint.scale * xa, xb, 1e-12);
      EXPECT_TRUE(joint.a.atEnd);
      EXPECT_FALSE(joint.b.atEnd);
    }
  }
  EXPECT_EQ(pieces, 2);
}

TEST(LayoutPropagation, SubChainsAreSolvedBreadthFirstOverTheTJunctions) {
  // Patches 1 and 2 continue their v members into 3 and 4 above (whole sides), so the sub-chains
  // {1, 3} and {2, 4} are longer than {0}: {1, 3} goes first (equidistant thirds, identity maps),
  // then its T-junction neighbour 0, whose half 3 -> 7 of side 2 is closed (patch 1's members at
  // x = 0, 1/6, 1/3, 1/2) and whose other half gets one free member (at 3/4, the middle); then
  // {2, 4}, which takes 0's members on 7 -> 4 and adds none.
  //   top row corners 5 8 6, above them 11 12 13
  const auto graph = patching::buildPatchGraph(tJunctionLayout({{5, 8, 12, 11}, {8, 6, 13, 12}}));
  std::vector<PatchSideData> patches(5, sideData());
  const auto result = propagateLayout(graph, patches, withMembers(4));
  for (const auto& f : result.fallbacks)
    for (const auto& n : f.nodes) EXPECT_EQ(n.family, Family::U) << f.reason;
  EXPECT_TRUE(result.notes.empty()) << result.notes.front();
  const std::vector<std::vector<double>> expected{{0, 1 / 6.0, 1 / 3.0, 0.5, 0.75, 1},
                                                  {0, 1 / 3.0, 2 / 3.0, 1},
                                                  {0, 0.5, 1},
                                                  {0, 1 / 3.0, 2 / 3.0, 1},
                                                  {0, 0.5, 1}};
  for (int p = 0; p < 5; ++p) {
    ASSERT_EQ(result.x1[p][1].size(), expected[p].size()) << p;
    for (size_t j = 0; j < expected[p].size(); ++j)
      EXPECT_NEAR(result.x1[p][1][j], expected[p][j], 1e-9) << p << " " << j;
  }
  int tPieces = 0;
  for (const auto& piece : result.pieces) {
    EXPECT_EQ(piece.membersA, piece.membersB) << piece.boundary;
    tPieces += piece.kind == PieceKind::TJunction;
  }
  EXPECT_EQ(tPieces, 2);
  EXPECT_LE(result.evennessAfter, result.evennessBefore);
}

TEST(LayoutPropagation, InfeasiblePatchesCutChains) {
  // An infeasible patch in the middle of a chain of three cuts it: the others fall back too.
  const auto strip =
      patching::buildPatchGraph(layoutOf({{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}}));
  std::vector<PatchSideData> three(3, sideData());
  three[1].usable = false;
  const auto cut = propagateLayout(strip, three, withMembers(4));
  EXPECT_TRUE(cut.x1[0][0].empty());
  EXPECT_TRUE(cut.x1[2][0].empty());
  EXPECT_THROW(propagateLayout(strip, std::vector<PatchSideData>(2, sideData())), InvalidInput);
}

TEST(LayoutPropagation, AutomaticCountFollowsTheSpacingRule) {
  const auto graph = patching::buildPatchGraph(layoutOf({{0, 1, 4, 3}, {1, 2, 5, 4}}));
  std::vector<PatchSideData> patches(2, sideData());
  for (auto& p : patches) p.sideLengths = {3.0, 2.0, 3.0, 2.0};  // u runs between the 2 m sides
  PropagationOptions options;
  options.lamellaWidthM = 0.05;
  options.spacingFactor = 8.0;  // target spacing 0.4 m: 2 m / 0.4 = 5 intervals
  const auto result = propagateLayout(graph, patches, options);
  EXPECT_EQ(result.x1[0][0].size(), 6u);
}

}  // namespace
}  // namespace egg::propagation
