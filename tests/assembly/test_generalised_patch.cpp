// A generalised patch (issue 41) as the grid fabrication and the 3D model read and the rods the
// simulations deploy: on a sphere cap's layout (the design's own numbers are the known answers),
// and its ends bolted to a quad patch's boundary lamella on the hand-made 3 x 3 grid.
#include "assembly/generalised_patch.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/three_by_three_grid.hpp"

#include <gtest/gtest.h>

namespace egg::assembly {
namespace {

using patching::AnchorHold;

// The distance from p to the straight line through a planar segment.
double offLine(const Eigen::Vector2d& p, const generalised::Segment2& s) {
  const Eigen::Vector2d d = (s[1] - s[0]).normalized();
  const Eigen::Vector2d r = p - s[0];
  return std::abs(d.x() * r.y() - d.y() * r.x());
}

TEST(GeneralisedPatch, CapDesignBecomesASparseGridWithItsRodsInGridOrder) {
  const TriMesh mesh = samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 5.0}}, 0.3);
  const generalised::GridDomain domain(mesh);
  generalised::LayoutParameters parameters;
  parameters.lines = {6, 6};
  parameters.angleRad = 0.3;
  patching::InfillPiece piece;
  generalised::GeneralisedDesignOptions options;
  options.section = {0.08, 0.01};
  piece.design = generalised::designGeneralisedGrid(
      domain, generalised::layoutFromLines(domain, parameters), options);
  const auto& design = *piece.design;
  const auto& members = design.layout.members;
  for (size_t m = 0; m < members.size(); ++m)
    piece.memberEndHolds.push_back(
        {AnchorHold::DesignBoundary, m % 2 ? AnchorHold::PatchSide : AnchorHold::Cut});
  const GeneralisedPatch patch = generalisedPatch(piece, 2, 11);
  EXPECT_EQ(patch.patchId, 11);
  EXPECT_EQ(patch.piece, 2);
  const EggGrid& grid = patch.grid;
  ASSERT_EQ(grid.u.size() + grid.v.size(), members.size());
  ASSERT_EQ(patch.network.rods.size(), members.size());
  // Not every u member crosses every v member on a cap: the grid is sparse.
  EXPECT_LT(grid.connections.size(), grid.u.size() * grid.v.size());
  ASSERT_EQ(grid.connections.size(), design.fieldCrossings.size());
  for (size_t m = 0; m < members.size(); ++m) {
    const int r = patch.rodOfMember[m];
    const bool isU = r < static_cast<int>(grid.u.size());
    EXPECT_EQ(isU, members[m].family == 0);
    const GridMember& gm = isU ? grid.u[r] : grid.v[r - grid.u.size()];
    EXPECT_DOUBLE_EQ(gm.planarLength, design.network.rods[m].lengthM);
    EXPECT_DOUBLE_EQ(patch.network.rods[r].lengthM, gm.planarLength);
    EXPECT_EQ(patch.network.rods[r].layer, members[m].family);
    EXPECT_FALSE(gm.boundary);
    // Both ends held, in rod order, with the holds the infill found.
    EXPECT_EQ(patch.network.anchors[2 * r].rod, r);
    EXPECT_DOUBLE_EQ(patch.network.anchors[2 * r].sM, 0.0);
    EXPECT_DOUBLE_EQ(patch.network.anchors[2 * r + 1].sM, gm.planarLength);
    EXPECT_EQ(patch.anchorHolds[2 * r], AnchorHold::DesignBoundary);
    EXPECT_EQ(patch.anchorHolds[2 * r + 1], m % 2 ? AnchorHold::PatchSide : AnchorHold::Cut);
  }
  for (size_t k = 0; k < grid.connections.size(); ++k) {
    const GridConnection& c = grid.connections[k];
    const auto& crossing = design.planarProblem.crossings[k];
    EXPECT_EQ(patch.rodOfMember[crossing.g], c.memberU);
    EXPECT_EQ(patch.rodOfMember[crossing.h], static_cast<int>(grid.u.size()) + c.memberV);
    // The bolt's planar point lies on both cut lamellas.
    EXPECT_LT(offLine(c.planar, {grid.u[c.memberU].planarStart, grid.u[c.memberU].planarEnd}),
              1e-9);
    EXPECT_LT(offLine(c.planar, {grid.v[c.memberV].planarStart, grid.v[c.memberV].planarEnd}),
              1e-9);
    // s = s_bar + l, and the rods' bolt is the grid's connection.
    const auto& bolt = patch.network.connections[k];
    EXPECT_DOUBLE_EQ(bolt.sAM, c.sBarU);
    EXPECT_DOUBLE_EQ(bolt.sBM, c.sBarV);
    EXPECT_NEAR(c.sU - c.sBarU, c.notchU, 1e-15);
    EXPECT_NEAR(c.sV - c.sBarV, c.notchV, 1e-15);
    EXPECT_NEAR(c.notchU,
                design.planarProblem.crossings[k].lambdaG *
                        design.planarProblem.members[crossing.g].lengthM -
                    c.sBarU,
                1e-12);
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    // The sphere's normal is radial: (x, y) / R from the axis (vertex normals of 0.3 m edges).
    EXPECT_NEAR(c.normal.x(), c.spatial.x() / 10.0, 0.01);
    EXPECT_NEAR(c.normal.y(), c.spatial.y() / 10.0, 0.01);
    EXPECT_EQ(c.spatial, design.tracedCrossings[k]);
  }
  EXPECT_NO_THROW(rods::validateNetwork(patch.network));
  // Swapped, h is the grid's u in layer 0 and g its v on top; every bolt the same crossing.
  const GeneralisedPatch swapped = generalisedPatch(piece, 2, 11, true);
  EXPECT_TRUE(swapped.swappedLayers);
  EXPECT_EQ(swapped.grid.u.size(), grid.v.size());
  EXPECT_EQ(swapped.grid.v.size(), grid.u.size());
  for (size_t m = 0; m < members.size(); ++m) {
    const int r = swapped.rodOfMember[m];
    EXPECT_EQ(r < static_cast<int>(swapped.grid.u.size()), members[m].family == 1);
    EXPECT_EQ(swapped.network.rods[r].layer, 1 - members[m].family);
  }
  ASSERT_EQ(swapped.grid.connections.size(), grid.connections.size());
  for (size_t k = 0; k < grid.connections.size(); ++k) {
    const GridConnection &a = grid.connections[k], &b = swapped.grid.connections[k];
    EXPECT_EQ(a.memberU, b.memberV);
    EXPECT_EQ(a.memberV, b.memberU);
    EXPECT_DOUBLE_EQ(a.sBarU, b.sBarV);
    EXPECT_DOUBLE_EQ(a.notchV, b.notchU);
    EXPECT_LT((a.planar - b.planar).norm(), 1e-9);  // the same crossing of the two cut lamellas
  }
  EXPECT_NO_THROW(rods::validateNetwork(swapped.network));
}

TEST(GeneralisedPatch, WithoutADesignIsAnError) {
  patching::InfillPiece piece;
  EXPECT_THROW(generalisedPatch(piece, 0, 4), InvalidInput);
}

// Two rods of a generalised patch whose ends lie on the 3 x 3 grid's side 0 (u member 0, from
// (0,0,0) to (2,0,0.2), layer 0 unless the patch is swapped).
GeneralisedPatch ringPatch() {
  GeneralisedPatch g;
  g.patchId = 4;
  for (int layer : {0, 1}) {
    rods::Rod rod;
    rod.lengthM = 1.0;
    rod.layer = layer;
    rod.guess = {{0, 0, 0}, {0, -1, 0}};
    rod.guessNormals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    g.network.rods.push_back(rod);
  }
  const auto anchor = [&](int rod, double s, Eigen::Vector3d at, AnchorHold hold) {
    g.network.anchors.push_back({rod, s, at, Eigen::Vector3d::UnitZ()});
    g.anchorHolds.push_back(hold);
  };
  anchor(0, 0.0, {0.5, -1.0, 0.05}, AnchorHold::DesignBoundary);
  anchor(0, 1.0, {0.5, 0.0, 0.05}, AnchorHold::PatchSide);     // on u0 at a quarter
  anchor(1, 0.0, {1.5, -0.004, 0.15}, AnchorHold::PatchSide);  // 4 mm off u0, three quarters
  anchor(1, 1.0, {1.5, -2.0, 0.15}, AnchorHold::PatchSide);    // no lamella within reach
  return g;
}

TEST(RingBeamJoins, EndsInTheOtherLayerBoltToTheQuadsBoundaryLamellaTheRestKeepTheirAnchors) {
  const EggGrid quad = testing::threeByThree();
  const double length = quad.u[0].planarLength;
  const GeneralisedPatch g = ringPatch();
  // u0 in layer 0: rod 1 (layer 1) laps onto it, rod 0 (layer 0) cannot.
  RingBeamJoins joins = ringBeamJoins(g, 7, {&quad}, {0}, 0.01);
  ASSERT_EQ(joins.bolts.size(), 1u);
  const rods::PatchJoin& bolt = joins.bolts[0];
  EXPECT_EQ(bolt.patchA, 0);
  EXPECT_EQ(bolt.rodA, 0);  // u member 0 is rod 0
  EXPECT_NEAR(bolt.sAM, 0.75 * length, 1e-12);
  EXPECT_EQ(bolt.patchB, 7);
  EXPECT_EQ(bolt.rodB, 1);
  EXPECT_DOUBLE_EQ(bolt.sBM, 0.0);
  EXPECT_EQ(joins.releasedAnchors, (std::vector<int>{2}));
  EXPECT_EQ(joins.sameLayer, 1);
  EXPECT_EQ(joins.unmatched, 1);
  EXPECT_NEAR(joins.maxGapM, 0.004, 1e-12);
  EXPECT_EQ(joins.quads, (std::vector<int>{0}));
  // The quad swapped (u on top): rod 0's end bolts instead, at a quarter of u0.
  joins = ringBeamJoins(g, 7, {&quad}, {1}, 0.01);
  ASSERT_EQ(joins.bolts.size(), 1u);
  EXPECT_EQ(joins.bolts[0].rodB, 0);
  EXPECT_NEAR(joins.bolts[0].sAM, 0.25 * length, 1e-12);
  EXPECT_DOUBLE_EQ(joins.bolts[0].sBM, 1.0);
  EXPECT_EQ(joins.releasedAnchors, (std::vector<int>{1}));
  // No quad grid: nothing to bolt to.
  joins = ringBeamJoins(g, 7, {nullptr}, {0}, 0.01);
  EXPECT_TRUE(joins.bolts.empty());
  EXPECT_EQ(joins.unmatched, 3);
}

}  // namespace
}  // namespace egg::assembly
