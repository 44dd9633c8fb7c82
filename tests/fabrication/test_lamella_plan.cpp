#include "fabrication/lamella_plan.hpp"

#include "core/errors.hpp"
#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace egg::fabrication {
namespace {

using testing::handGrid;
using testing::handOptions;

TEST(LamellaPlan, HandGridHolesAndSlotsAtTheirPlanarPositions) {
  const EggGrid grid = handGrid();
  const auto plans = planLamellae({{0, &grid, std::nullopt}}, handOptions());
  ASSERT_EQ(plans.size(), 6u);
  const LamellaPlan& u1 = plans[1];
  EXPECT_EQ(u1.id, "P0-U1");
  EXPECT_FALSE(u1.boundary);
  EXPECT_DOUBLE_EQ(u1.lengthMm, 210.0);  // 200 mm planar + 2 x 5 mm overhang
  ASSERT_EQ(u1.features.size(), 3u);
  // (1,0): a 0.4 mm notch, below min_notch_mm = 1: a plain hole, counted.
  EXPECT_EQ(u1.features[0].kind, FeatureKind::Hole);
  EXPECT_TRUE(u1.features[0].demotedNotch);
  EXPECT_NEAR(u1.features[0].xMm, 5.0, 1e-12);
  EXPECT_EQ(u1.features[0].connectionId, "P0-C1-0");
  // (1,1): the u member slides +5 mm: a slot from x = 105 to 110, 5 + 3 = 8 mm long.
  EXPECT_EQ(u1.features[1].kind, FeatureKind::Slot);
  EXPECT_NEAR(u1.features[1].xMm, 105.0, 1e-12);
  EXPECT_NEAR(u1.features[1].slideMm, 5.0, 1e-12);
  EXPECT_NEAR(u1.features[1].maxXMm(3.0) - u1.features[1].minXMm(3.0), 8.0, 1e-12);
  EXPECT_EQ(u1.features[2].kind, FeatureKind::Hole);
  EXPECT_NEAR(u1.features[2].xMm, 205.0, 1e-12);
  // v1 slides the other way at (1,1): -3 mm.
  const LamellaPlan& v1 = plans[4];
  EXPECT_EQ(v1.id, "P0-V1");
  EXPECT_EQ(v1.features[1].kind, FeatureKind::Slot);
  EXPECT_NEAR(v1.features[1].slideMm, -3.0, 1e-12);
  EXPECT_EQ(v1.features[1].connectionId, "P0-C1-1");
  // u0 is a boundary member: its 2 mm notch at (0,1) is a hole (no notches on boundaries, 3.5.3).
  EXPECT_TRUE(plans[0].boundary);
  EXPECT_EQ(plans[0].features[1].kind, FeatureKind::Hole);
  EXPECT_TRUE(plans[0].features[1].droppedBoundaryNotch);
  const FeatureCounts counts = countFeatures(plans);
  EXPECT_EQ(counts.slots, 2);
  EXPECT_EQ(counts.holes, 16);  // 18 member-connection pairs, 2 of them slots
  EXPECT_EQ(counts.demoted, 1);
  EXPECT_EQ(counts.droppedBoundary, 1);
  for (const auto& p : plans) EXPECT_EQ(p.segments.size(), 1u) << p.id;
}

TEST(LamellaPlan, LongLamellaIsSplicedClearOfItsHoles) {
  LamellaPlan plan;
  plan.id = "P0-U7";
  plan.lengthMm = 25000.0;
  // Holes every 1000 mm from 500 mm; a 460 mm slot from 11500.
  for (int k = 0; k < 25; ++k) {
    LamellaFeature f;
    f.xMm = 500.0 + 1000.0 * k;
    if (k == 11) f.kind = FeatureKind::Slot, f.slideMm = 460.0;
    plan.features.push_back(f);
  }
  const double stock = 6000.0, clearance = 100.0, bolt = 8.0;
  placeSplices(plan, stock, clearance, bolt);
  ASSERT_EQ(plan.segments.size(), 5u);  // 25 m from 6 m stock: at least 5 pieces
  EXPECT_EQ(plan.splicesMm.size(), 4u);
  for (const auto& seg : plan.segments) EXPECT_LE(seg.lengthMm(), stock + 1e-9);
  EXPECT_DOUBLE_EQ(plan.segments.front().startMm, 0.0);
  EXPECT_DOUBLE_EQ(plan.segments.back().endMm, 25000.0);
  for (double cut : plan.splicesMm) {
    for (const auto& f : plan.features) {
      const bool clear = cut <= f.minXMm(bolt) - clearance || cut >= f.maxXMm(bolt) + clearance;
      EXPECT_TRUE(clear) << "splice at " << cut << " mm meets the feature at " << f.xMm;
    }
  }
  // 6000 lies clear between the holes at 5500 and 6500 (each keeps 104 mm free).
  EXPECT_DOUBLE_EQ(plan.splicesMm[0], 6000.0);
  // From 6000 the stock reaches 12000, inside the slot's zone 11500-4-100 .. 11960+4+100: cut at
  // 11396.
  EXPECT_DOUBLE_EQ(plan.splicesMm[1], 11396.0);
}

TEST(LamellaPlan, NoClearSplicePositionIsAClearError) {
  LamellaPlan plan;
  plan.id = "P3-V2";
  plan.lengthMm = 3000.0;
  for (int k = 0; k < 30; ++k) {
    LamellaFeature f;
    f.xMm = 50.0 + 100.0 * k;
    plan.features.push_back(f);
  }
  try {
    placeSplices(plan, 1000.0, 60.0, 8.0);  // every position lies within 64 mm of a hole
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("P3-V2"), std::string::npos) << what;
    EXPECT_NE(what.find("fabrication.stock_length_mm"), std::string::npos) << what;
  }
}

// Slots nearly as long as their spacing (the Yas canopy: 3 m slides every 3.3 m): 2800 mm cut-outs
// from 3000 k + 100 to 3000 k + 2900 leave 200 mm gaps. No position is 400 mm clear; the splices go
// to the middles of the gaps, 100 mm from the slots each side, the furthest gap in each stock
// length.
LamellaPlan slottedPlan() {
  LamellaPlan plan;
  plan.id = "P5-U5";
  plan.lengthMm = 18000.0;
  for (int k = 0; k < 6; ++k) {
    LamellaFeature f;
    f.kind = FeatureKind::Slot;
    f.xMm = 3000.0 * k +
            2892.0;  // the bolt slides 2784 mm back: extent 3000 k + 100 .. + 2900 with d = 16
    f.slideMm = -2784.0;
    plan.features.push_back(f);
  }
  return plan;
}

TEST(LamellaPlan, SlotsLeavingNoRoomForTheClearanceGetSplicesMidGap) {
  LamellaPlan plan = slottedPlan();
  placeSplices(plan, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 56.0);
  ASSERT_EQ(plan.splicesMm.size(), 2u);
  EXPECT_DOUBLE_EQ(plan.splicesMm[0], 6000.0);
  EXPECT_DOUBLE_EQ(plan.splicesMm[1], 12000.0);
  ASSERT_EQ(plan.spliceClearancesMm.size(), 2u);
  EXPECT_DOUBLE_EQ(plan.spliceClearancesMm[0], 100.0);
  EXPECT_DOUBLE_EQ(plan.spliceClearancesMm[1], 100.0);
  for (const auto& seg : plan.segments) EXPECT_LE(seg.lengthMm(), 6000.0);
  // Without a fallback (the minimum defaults to the clearance) it is impossible.
  LamellaPlan strict = slottedPlan();
  EXPECT_THROW(placeSplices(strict, 6000.0, 400.0, 16.0), InvalidInput);
}

TEST(LamellaPlan, SplicesTooTightForTheMinimumNameTheStretchAndItsWidestGap) {
  LamellaPlan plan = slottedPlan();
  try {
    placeSplices(plan, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 120.0);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("fabrication.stock_length_mm: lamella P5-U5 (18000 mm) cannot be spliced "
                         "between 0 and 6000 mm",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find("gaps of at most 200 mm"), std::string::npos) << what;
    EXPECT_NE(what.find("needs a gap of 2 x 120 mm (fabrication.min_splice_clearance_mm"),
              std::string::npos)
        << what;
    // Cut-outs grown by 120 mm overlap (gaps of 200 mm) from the strip's start to 17900 + 120 mm.
    EXPECT_NE(what.find("it would take pieces of up to 18000 mm"), std::string::npos) << what;
  }
}

TEST(LamellaPlan, SharedBoundaryLamellaCarriesTheHolesOfBothPatches) {
  // Patch 1 continues patch 0 along +x: patch 0's v2 and patch 1's v0 are the same side.
  const EggGrid left = handGrid(), right = handGrid(0.2);
  const std::vector<FabricationPatch> patches{{0, &left, std::nullopt}, {1, &right, std::nullopt}};
  const SharedBoundary side{0, Family::V, 2, 1, Family::V, 0, false};
  const auto plans = planLamellae(patches, handOptions(), {side});
  ASSERT_EQ(plans.size(), 11u);  // 12 members, one lamella for the shared side
  const auto shared = std::find_if(plans.begin(), plans.end(),
                                   [](const LamellaPlan& p) { return p.id == "P0-V2"; });
  ASSERT_NE(shared, plans.end());
  ASSERT_EQ(shared->features.size(), 3u);  // both patches' members meet it at the same three points
  for (int k = 0; k < 3; ++k) {
    const auto& f = shared->features[k];
    EXPECT_NEAR(f.xMm, 5.0 + 100.0 * k, 1e-12);
    ASSERT_EQ(f.alsoConnections.size(), 1u);
    EXPECT_EQ(f.alsoConnections[0], std::make_pair(1, 3 * k));  // patch 1's connection (k, 0)
    EXPECT_TRUE(f.holds(1, 3 * k));
    // The other patch's connection by its id: patch 1's connection (k, 0).
    EXPECT_EQ(f.label(), "P0-C" + std::to_string(k) + "-2=P1-C" + std::to_string(k) + "-0");
  }
  EXPECT_EQ(std::count_if(plans.begin(), plans.end(),
                          [](const LamellaPlan& p) { return p.id == "P1-V0"; }),
            0);
}

TEST(LamellaPlan, ReversedSharedSideMirrorsTheOtherPatchsHoles) {
  auto strip = [](const std::string& id, std::vector<double> holes) {
    LamellaPlan p;
    p.id = id;
    p.boundary = true;
    p.lengthMm = 210.0;
    p.overhangMm = 5.0;
    for (double x : holes) {
      LamellaFeature f;
      f.xMm = x;
      f.connectionId = id + "@" + std::to_string(static_cast<int>(x));
      p.features.push_back(f);
    }
    return p;
  };
  std::vector<LamellaPlan> plans{strip("A", {5.0, 105.0, 205.0}), strip("B", {5.0, 35.0, 205.0})};
  plans[1].patchId = 1;
  const int merged = mergeSharedBoundaries(plans, {{0, Family::U, 0, 1, Family::U, 0, true}}, 0.5);
  EXPECT_EQ(merged, 2);  // B's ends land on A's ends
  ASSERT_EQ(plans.size(), 1u);
  ASSERT_EQ(plans[0].features.size(), 4u);
  EXPECT_NEAR(plans[0].features[2].xMm, 175.0, 1e-12);  // 35 -> 5 + (200 - 30)
  EXPECT_EQ(plans[0].features[2].connectionId, "B@35");
  // Not boundary members, or different lengths: errors naming the side.
  std::vector<LamellaPlan> inner{strip("A", {5.0}), strip("B", {5.0})};
  inner[1].patchId = 1;
  inner[0].boundary = false;
  EXPECT_THROW(mergeSharedBoundaries(inner, {{0, Family::U, 0, 1, Family::U, 0, false}}, 0.5),
               InvalidInput);
  std::vector<LamellaPlan> unequal{strip("A", {5.0}), strip("B", {5.0})};
  unequal[1].patchId = 1;
  unequal[1].lengthMm = 212.0;
  try {
    mergeSharedBoundaries(unequal, {{0, Family::U, 0, 1, Family::U, 0, false}}, 0.5);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("P0-U0 = P1-U0"), std::string::npos) << e.what();
  }
}

TEST(LamellaPlan, InconsistentGridIsRejected) {
  EggGrid grid = handGrid();
  grid.connections.back().memberV = 3;  // the grid has v members 0..2
  try {
    planLamellae({{4, &grid, std::nullopt}}, handOptions());
    ADD_FAILURE() << "a connection to a missing member was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("patch 4: connection 8 joins members 2 and 3"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(planLamellae({{4, nullptr, std::nullopt}}, handOptions()), InvalidInput);
}

TEST(LamellaPlan, GridWhereNotEveryMemberCrossesEveryOtherCarriesOnlyItsCrossings) {
  // A generalised patch's grid (issue 41) lists only the pairs that cross: the hand grid without
  // (1,1) (u1's slot) and (2,0).
  EggGrid grid = handGrid();
  grid.connections.erase(grid.connections.begin() + 6);  // (2,0)
  grid.connections.erase(grid.connections.begin() + 4);  // (1,1)
  const auto plans = planLamellae({{9, &grid, std::nullopt}}, handOptions());
  ASSERT_EQ(plans.size(), 6u);
  const LamellaPlan& u1 = plans[1];
  ASSERT_EQ(u1.features.size(), 2u);
  EXPECT_EQ(u1.features[0].connectionId, "P9-C1-0");
  EXPECT_EQ(u1.features[1].connectionId, "P9-C1-2");
  EXPECT_NEAR(u1.features[1].xMm, 205.0, 1e-12);
  // Features name their connection by its index in the list: (1,2) is now the fifth.
  EXPECT_EQ(u1.features[1].connection, 4);
  EXPECT_EQ(plans[2].features.size(), 2u);  // u2 lost (2,0)
  const LamellaPlan& v0 = plans[3];
  ASSERT_EQ(v0.features.size(), 2u);
  EXPECT_EQ(v0.features[1].connectionId, "P9-C1-0");
  EXPECT_EQ(plans[4].features.size(), 2u);  // v1 lost (1,1)
  const FeatureCounts counts = countFeatures(plans);
  EXPECT_EQ(counts.slots, 0);  // both slots were at (1,1)
  EXPECT_EQ(counts.holes, 14);
}

TEST(LamellaPlan, OverhangTooShortForAnEndSlotIsAnError) {
  EggGrid grid = handGrid();
  // (1,2) sits at the end of u1 (x = 205 of 210 mm); a +4 mm slot would reach 210.5 mm.
  grid.connections[1 * 3 + 2].notchU = 0.004;
  EXPECT_THROW(planLamellae({{0, &grid, std::nullopt}}, handOptions()), InvalidInput);
}

// A slot whose cut-out (bolt diameter 16 mm included) runs from lo to hi.
LamellaFeature slotBetween(double lo, double hi) {
  LamellaFeature f;
  f.kind = FeatureKind::Slot;
  f.xMm = lo + 8.0;
  f.slideMm = hi - lo - 16.0;
  return f;
}

// Gaps of 100 mm between slots (a plate needs 2 x 120): at 5000, 5800, 7250, 8000 and the ends.
LamellaPlan densePlan() {
  LamellaPlan plan;
  plan.id = "P6-U5";
  plan.lengthMm = 12000.0;
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {100, 5000}, {5100, 5800}, {5900, 7250}, {7350, 8000}, {8100, 11900}}) {
    plan.features.push_back(slotBetween(lo, hi));
  }
  return plan;
}

TEST(LamellaPlan, ScarfsJoinStripsWhoseSlotsLeaveNoRoomForAPlate) {
  LamellaPlan plates = densePlan();
  EXPECT_THROW(placeSplices(plates, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 120.0),
               InvalidInput);
  // 1:12 over 50 mm: scarfs of 600 to 1200 mm whose feather ends lie in gaps (8 mm clear of the
  // slots). The furthest end within 6000 mm is 5892 (gap 5808..5892), the slope beginning in the
  // gap 5008..5092 (800 mm); from there, 8092 with the slope from 7342 (750 mm); 4658 mm remain.
  LamellaPlan plan = densePlan();
  placeSplices(plan, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 120.0,
               SpliceJoint::PlateOrScarf, 600.0);
  ASSERT_EQ(plan.splicesMm.size(), 2u);
  ASSERT_EQ(plan.segments.size(), 3u);
  EXPECT_TRUE(plan.spliceIsScarf[0] && plan.spliceIsScarf[1]);
  EXPECT_DOUBLE_EQ(plan.segments[0].endMm, 5892.0);
  EXPECT_DOUBLE_EQ(plan.segments[1].startMm, 5092.0);
  EXPECT_DOUBLE_EQ(plan.segments[1].endMm, 8092.0);
  EXPECT_DOUBLE_EQ(plan.segments[2].startMm, 7342.0);
  EXPECT_DOUBLE_EQ(plan.segments[2].endMm, 12000.0);
  EXPECT_DOUBLE_EQ(plan.splicesMm[0], 5492.0);
  EXPECT_DOUBLE_EQ(plan.splicesMm[1], 7717.0);
  EXPECT_DOUBLE_EQ(plan.spliceClearancesMm[0], 8.0);
  for (const auto& seg : plan.segments) EXPECT_LE(seg.lengthMm(), 6000.0);
  // No feather end inside a cut-out.
  for (const auto& seg : plan.segments) {
    for (const auto& f : plan.features) {
      for (double end : {seg.startMm, seg.endMm})
        EXPECT_FALSE(end > f.minXMm(16.0) && end < f.maxXMm(16.0)) << end;
    }
  }
}

TEST(LamellaPlan, ScarfModeScarfsEverySpliceAndPlateOrScarfKeepsPlatesWhereTheyFit) {
  LamellaPlan plan;
  plan.id = "P0-U0";
  plan.lengthMm = 9000.0;
  for (double x : {100.0, 4500.0, 8900.0}) {
    LamellaFeature hole;
    hole.xMm = x;
    plan.features.push_back(hole);
  }
  LamellaPlan mixed = plan;
  placeSplices(mixed, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 56.0,
               SpliceJoint::PlateOrScarf, 600.0);
  ASSERT_EQ(mixed.splicesMm.size(), 1u);
  EXPECT_FALSE(mixed.spliceIsScarf[0]);
  EXPECT_DOUBLE_EQ(mixed.splicesMm[0], 6000.0);
  placeSplices(plan, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 56.0, SpliceJoint::Scarf,
               600.0);
  ASSERT_EQ(plan.splicesMm.size(), 1u);
  EXPECT_TRUE(plan.spliceIsScarf[0]);
  EXPECT_DOUBLE_EQ(plan.segments[0].endMm, 6000.0);
  EXPECT_DOUBLE_EQ(plan.segments[1].startMm, 5400.0);  // the shortest scarf: 600 mm
}

TEST(LamellaPlan, ScarfsThroughASlitEndAtTheStockLength) {
  // The Yas-like slots 3 m apart leave gaps 3 m apart: no scarf of 600-1200 mm has both ends in
  // one, so each scarf ends at the stock length (6000, then 11400) and begins 600 mm before it,
  // through the slots, its clearance zero.
  LamellaPlan plan = slottedPlan();
  placeSplices(plan, 6000.0, 400.0, 16.0, "fabrication.stock_length_mm", 120.0,
               SpliceJoint::PlateOrScarf, 600.0);
  ASSERT_EQ(plan.segments.size(), 4u);
  EXPECT_DOUBLE_EQ(plan.segments[0].endMm, 6000.0);
  EXPECT_DOUBLE_EQ(plan.segments[1].startMm, 5400.0);
  EXPECT_DOUBLE_EQ(plan.segments[1].endMm, 11400.0);
  EXPECT_DOUBLE_EQ(plan.segments[2].startMm, 10800.0);
  EXPECT_DOUBLE_EQ(plan.segments[2].endMm, 16800.0);
  EXPECT_DOUBLE_EQ(plan.segments[3].startMm, 16200.0);
  EXPECT_DOUBLE_EQ(plan.spliceClearancesMm[0],
                   0.0);  // 6000 sits in a gap (5900..6100) but 5400 in a slot
}

}  // namespace
}  // namespace egg::fabrication
