// A generalised patch's fabrication input (issue 41) next to the hand-made 3 x 3 quad: two members
// end on the quad's side 0 (u member 0, layer 0, from (0,0,0) to (2,0,0.2)) at right angles. The
// one in layer 1 laps onto it: one bolt through both, the partner hole in the quad's lamella. The
// one in layer 0 butts against it: its strip stops half a width plus the gap short of the centre
// line and a bracket bolts it to the lamella.
#include "assembly/generalised_fabrication.hpp"

#include "core/errors.hpp"
#include "fabrication/lamella_plan.hpp"
#include "tests/support/fabrication_hand_grid.hpp"
#include "tests/support/three_by_three_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace egg::assembly {
namespace {

using patching::AnchorHold;

GeneralisedPatch twoMembersOnSide0() {
  GeneralisedPatch g;
  g.patchId = 4;
  for (int layer : {0, 1}) {
    const double x = layer == 0 ? 0.5 : 1.5;  // a quarter and three quarters along u0
    GridMember m;
    m.family = layer == 0 ? Family::U : Family::V;
    m.spatial = {{x, -1.0, 0.1 * x}, {x, 0.0, 0.1 * x}};
    m.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    m.planarEnd = {1.0, 0.0};
    m.planarLength = m.spatialLength = 1.0;
    (layer == 0 ? g.grid.u : g.grid.v).push_back(m);
    rods::Rod rod;
    rod.lengthM = 1.0;
    rod.layer = layer;
    rod.guess = m.spatial;
    rod.guessNormals = m.normals;
    g.network.rods.push_back(rod);
    g.network.anchors.push_back({layer, 0.0, m.spatial[0], Eigen::Vector3d::UnitZ()});
    g.anchorHolds.push_back(AnchorHold::DesignBoundary);
    g.network.anchors.push_back({layer, 1.0, m.spatial[1], Eigen::Vector3d::UnitZ()});
    g.anchorHolds.push_back(AnchorHold::PatchSide);
  }
  return g;
}

fabrication::FabricationOptions metreOptions() {
  auto o = fabrication::testing::handOptions();
  o.lamellaWidthMm = 400.0;
  o.lamellaThicknessMm = 20.0;
  o.endOverhangMm = 200.0;
  o.boltDiameterMm = 16.0;
  o.stockLengthMm = 6000.0;
  o.sheetMm = {6000.0, 3000.0};
  return o;
}

// 0.4 m lamellas with 0.2 m overhangs (the metreOptions strips).
GeneralisedFabricationOptions metreEnds() {
  GeneralisedFabricationOptions options;
  options.lamellaWidthM = 0.4;
  options.endOverhangM = 0.2;
  return options;
}

double holeAt(const fabrication::LamellaPlan& plan, const std::string& id) {
  for (const auto& f : plan.features)
    if (f.connectionId == id) return f.xMm;
  ADD_FAILURE() << plan.id << " has no hole " << id;
  return -1.0;
}

TEST(GeneralisedFabrication, LappingEndsBoltThroughTheQuadsLamellaButtingEndsAreCutBackToABracket) {
  const EggGrid quad = testing::threeByThree();
  const GeneralisedPatch g = twoMembersOnSide0();
  const RingBeamJoins ring = ringBeamJoins(g, 1, {&quad}, {0}, 0.4);
  ASSERT_EQ(ring.bolts.size(), 1u);
  ASSERT_EQ(ring.brackets.size(), 1u);
  std::vector<fabrication::FabricationPatch> patches{{0, &quad, std::nullopt}};
  GeneralisedFabricationOptions options = metreEnds();
  EXPECT_TRUE(addGeneralisedToFabrication(g, ring, {&quad}, options, patches).empty());
  ASSERT_EQ(patches.size(), 2u);
  const auto& entry = patches[1];
  EXPECT_EQ(entry.boltedTo, (std::vector<int>{0}));
  // The rim ends stand on supports; every end has its bolt.
  ASSERT_EQ(entry.endSupports.size(), 2u);
  EXPECT_EQ(entry.endSupports[0].id, "P4-U0-start");
  EXPECT_EQ(entry.extraHoles.size(), 4u);
  ASSERT_EQ(entry.ringBeamBrackets.size(), 1u);
  EXPECT_EQ(entry.ringBeamBrackets[0].endId, "P4-U0-end");
  EXPECT_EQ(entry.ringBeamBrackets[0].lamellaId, "P0-U0");
  // At right angles the cut is w/2 + gap = 0.21 m, the bracket bolt an overhang further in.
  ASSERT_EQ(entry.endTrims.size(), 1u);
  EXPECT_FALSE(entry.endTrims[0].atStart);
  EXPECT_NEAR(entry.endTrims[0].trimMm, 410.0, 1e-9);
  const auto plans = fabrication::planLamellae(patches, metreOptions());
  const auto find = [&](const std::string& id) {
    return *std::find_if(plans.begin(), plans.end(), [&](const auto& p) { return p.id == id; });
  };
  const auto butting = find("P4-U0");
  EXPECT_NEAR(butting.lengthMm, 1000.0 + 400.0 - 410.0, 1e-9);
  EXPECT_NEAR(holeAt(butting, "P4-U0-start"), 200.0, 1e-9);
  EXPECT_NEAR(holeAt(butting, "P4-U0-end"), butting.lengthMm - 200.0, 1e-9);
  const auto lapping = find("P4-V0");
  EXPECT_NEAR(lapping.lengthMm, 1400.0, 1e-9);
  EXPECT_NEAR(holeAt(lapping, "P4-V0-end"), 1200.0, 1e-9);
  // The quad's u0 carries the lapping end's bolt at three quarters and the bracket's at a quarter.
  const auto side = find("P0-U0");
  const double length = quad.u[0].planarLength;
  EXPECT_NEAR(holeAt(side, "P4-V0-end"), 200.0 + 750.0 * length, 1e-6);
  EXPECT_NEAR(holeAt(side, "P4-U0-end"), 200.0 + 250.0 * length, 1e-6);
}

TEST(GeneralisedFabrication, AButtingEndNextToACrossingIsCutAsDrawnAndNamed) {
  const EggGrid quad = testing::threeByThree();
  GeneralisedPatch g = twoMembersOnSide0();
  GridConnection c;  // u0 crosses something 0.5 m from its end: the bracket bolt would be at 0.41
  c.memberU = 0;
  c.memberV = 0;
  c.sBarU = c.sU = 0.5;
  c.sBarV = c.sV = 0.5;
  g.grid.connections.push_back(c);
  const RingBeamJoins ring = ringBeamJoins(g, 1, {&quad}, {0}, 0.4);
  std::vector<fabrication::FabricationPatch> patches{{0, &quad, std::nullopt}};
  GeneralisedFabricationOptions options = metreEnds();
  const auto untrimmed = addGeneralisedToFabrication(g, ring, {&quad}, options, patches);
  ASSERT_EQ(untrimmed.size(), 1u);
  EXPECT_EQ(untrimmed[0], "P4-U0-end (bolt 410 mm, crossing 500 mm from the end)");
  EXPECT_TRUE(patches[1].endTrims.empty());
  EXPECT_EQ(patches[1].ringBeamBrackets.size(), 1u);  // still fixed by its bracket
  options.lamellaWidthM = 0.0;
  EXPECT_THROW(addGeneralisedToFabrication(g, ring, {&quad}, options, patches), InvalidInput);
}

TEST(GeneralisedFabrication, AtAnObliqueMeetingTheSquareEndsCornerIsCutClearToo) {
  // The butting member meets u0 at about 45 degrees: its centre line is cut (w/2)/sin back from
  // u0's centre line, and its acute corner reaches (w/2) cos/sin further: both clear by the gap.
  const EggGrid quad = testing::threeByThree();
  GeneralisedPatch g = twoMembersOnSide0();
  auto& m = g.grid.u[0];
  m.spatial = {{-0.5, -1.0, 0.0}, {0.5, 0.0, 0.05}};
  g.network.rods[0].guess = m.spatial;
  g.network.anchors[0].position = m.spatial[0];
  const RingBeamJoins ring = ringBeamJoins(g, 1, {&quad}, {0}, 0.4);
  ASSERT_EQ(ring.brackets.size(), 1u);
  std::vector<fabrication::FabricationPatch> patches{{0, &quad, std::nullopt}};
  GeneralisedFabricationOptions options = metreEnds();
  EXPECT_TRUE(addGeneralisedToFabrication(g, ring, {&quad}, options, patches).empty());
  ASSERT_EQ(patches[1].endTrims.size(), 1u);
  // Geometry: the cut end's two corners, w/2 either side of the centre line in the tangent plane,
  // lie at least half the width plus the gap from u0's centre line, the nearer one just so.
  const Eigen::Vector3d along = (m.spatial[1] - m.spatial[0]).normalized();
  const Eigen::Vector3d across = Eigen::Vector3d(2.0, 0.0, 0.2).normalized();
  const Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(along).normalized();
  const double cut = patches[1].endTrims[0].trimMm / 1000.0 - 0.2;  // less the overhang
  const Eigen::Vector3d end = m.spatial[1] - cut * along;
  double nearest = INFINITY;
  for (const double sign : {-1.0, 1.0}) {
    const Eigen::Vector3d corner = end + sign * 0.2 * side;
    nearest = std::min(nearest, (corner - corner.dot(across) * across).norm());
  }
  EXPECT_GE(nearest, 0.2 + 0.01 - 2e-3);  // the mesh-free plane z = 0.1 x tilts it slightly
  EXPECT_LE(nearest, 0.2 + 0.01 + 2e-3);
}

}  // namespace
}  // namespace egg::assembly
