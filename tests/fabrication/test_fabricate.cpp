#include "fabrication/fabricate.hpp"

#include "core/egg/solve_patch.hpp"
#include "core/errors.hpp"
#include "fabrication/fasteners.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include <cmath>
#include <iostream>
#include <regex>

namespace egg::fabrication {
namespace {

using testing::handGrid;
using testing::handOptions;

struct Point {
  double x, y;
};

// Hand-computed positions on sheet 1 (mm, y up). The nesting puts P0-U1 at (215.5, 5) and P0-V1 at
// (5, 26) (test_nesting); the strips' centrelines are 5 mm above.
const Point kHolesU1[] = {{220.5, 10.0}, {420.5, 10.0}};
const Point kSlotU1[] = {{320.5, 8.5}, {325.5, 11.5}};         // corners a - r n and b + r n
const Point kSlotV1[] = {{110.0, 32.5}, {107.0, 29.5}};        // sliding -3 mm: a = 110, b = 107
const Point kLabelU1 = {215.5 + (22.65 + 103.5) / 2.0, 10.0};  // lamella label, centred
const Point kLabelC10 = {222.75, 10.0};                        // connection label, left-aligned

bool near(double a, double b) { return std::abs(a - b) <= 0.01; }  // the acceptance tolerance

TEST(Fabricate, ExtraHolesCountABoltEachUnlessTheyShareAConnectionsHole) {
  // A generalised member end's bolt (issue 41): its own hole counts a bolt; its partner on the
  // quad's lamella, where it falls on a connection's hole, shares that bolt (three lamellas).
  const EggGrid grid = handGrid();
  FabricationPatch patch{0, &grid, std::nullopt};
  patch.extraHoles = {{Family::U, 1, 0.05, "P9-U0-end", true},     // u1 at x = 55 mm: its own
                      {Family::V, 0, 0.1, "P9-U0-end", false},     // v0's hole of (1,0): shared
                      {Family::V, 2, 0.05, "P9-V0-start", true}};  // v2 at x = 55 mm: its own
  patch.ringBeamBrackets = {{"P9-V0-start", "P0-V2"}};
  const auto r = fabricate({patch}, handOptions());
  EXPECT_EQ(r.connections, 9 + 2 - 1);
  const auto& u1 = r.lamellae[1];
  ASSERT_EQ(u1.features.size(), 4u);
  EXPECT_EQ(u1.features[1].connectionId, "P9-U0-end");
  EXPECT_NEAR(u1.features[1].xMm, 55.0, 1e-12);
  EXPECT_EQ(u1.features[1].connection, -1);
  const auto& v0 = r.lamellae[3];
  ASSERT_EQ(v0.features.size(), 3u);
  EXPECT_EQ(v0.features[1].label(), "P0-C1-0=P9-U0-end");
  const std::string bom = bomCsv(r);
  EXPECT_NE(bom.find("ring_beam_bracket,P9-V0-start,1,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("to P0-V2 (its own layer"), std::string::npos);
  EXPECT_NE(bom.find("bolt,,10,"), std::string::npos);
  // The shared hole's bolt clamps three lamellas: one such bolt.
  const size_t three = bom.find("3 lamellas");
  ASSERT_NE(three, std::string::npos) << bom;
  const std::string row = bom.substr(bom.rfind('\n', three) + 1, three - bom.rfind('\n', three));
  EXPECT_EQ(row.rfind("bolt_size,", 0), 0u) << row;
  EXPECT_EQ(row.substr(row.find(',', 10) + 1, 2), "1,") << row;
}

TEST(Fabricate, HandGridCountsMatchTheGrid) {
  const EggGrid grid = handGrid();
  const auto r = fabricate({{0, &grid, std::nullopt}}, handOptions());
  EXPECT_EQ(r.lamellae.size(), 6u);
  EXPECT_EQ(r.connections, 9);
  EXPECT_EQ(r.counts.slots, 2);
  EXPECT_EQ(r.counts.demoted, 1);
  EXPECT_EQ(r.stickers.size(), 4u / 2u);
  EXPECT_EQ(r.supports.size(), 4u);
  EXPECT_EQ(r.lamellaNesting.sheets, 1);
  EXPECT_EQ(r.splices, 0);
  // 6 strips of 210 x 10 x 1 mm of limewood (500 kg/m^3).
  EXPECT_NEAR(r.totalLengthM, 1.26, 1e-12);
  EXPECT_NEAR(r.massKg, 6 * 0.21 * 0.01 * 0.001 * 500.0, 1e-12);
  EXPECT_NEAR(r.lamellaNesting.yield, 6 * 2100.0 / 150000.0, 1e-12);
  EXPECT_NEAR(r.maxStressRatio, 0.0, 1e-12);  // flat grid
  // 10 mm on a 200 mm model is 5 %: the 2 % rule of 3.5.2 warns.
  bool widthWarning = false;
  for (const auto& w : r.warnings) widthWarning |= w.find("2 %") != std::string::npos;
  EXPECT_TRUE(widthWarning);

  const std::string bom = bomCsv(r);
  // Header, 6 lamellas, 9 totals, one bolt size, one washer size, one row for sheet L01.
  EXPECT_EQ(std::count(bom.begin(), bom.end(), '\n'), 1 + 6 + 9 + 3);
  EXPECT_NE(bom.find(",note,sheet\n"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nlamella_sheet,L01,1,"), std::string::npos) << bom;
  // Every row has the header's 11 fields; a lamella names its sheet.
  std::istringstream rows(bom);
  for (std::string row; std::getline(rows, row);)
    EXPECT_EQ(std::count(row.begin(), row.end(), ','), 10) << row;
  EXPECT_NE(bom.find("stress ratio 0.000,L01\n"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nbolt,,9,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nwasher,,18,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nbrass_sleeve,,2,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nptfe_sticker,,2,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nsupport,,4,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nlamella,P0-U1,1,210.00,10.00,1.00,"), std::string::npos) << bom;

  const auto report = fabricationReport(r, {"bom.csv"});
  for (const char* key : {"lamellae", "notches", "plain_holes", "stickers", "supports", "sheets",
                          "yield", "max_stress_ratio", "mass_kg", "files"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_EQ(report["lamellae"], 6);
  EXPECT_EQ(report["notches"], 2);
  EXPECT_EQ(report["plain_holes"], 1);
  EXPECT_EQ(report["files"][0], "bom.csv");
}

TEST(Fabricate, TwoPatchesSharingASideCountOneLamellaAndOneBoltThere) {
  const EggGrid left = handGrid(), right = handGrid(0.2);
  const auto r = fabricate({{0, &left, std::nullopt}, {1, &right, std::nullopt}}, handOptions(),
                           {{0, Family::V, 2, 1, Family::V, 0, false}});
  EXPECT_EQ(r.lamellae.size(), 11u);
  EXPECT_EQ(r.connections, 18 - 3);  // the three connections on the shared side hold one bolt each
  EXPECT_EQ(r.counts.slots, 4);
  EXPECT_EQ(r.stickers.size(), 4u);
  EXPECT_EQ(r.supports.size(), 6u);  // 8 corner anchors, two pairs on the same points
  EXPECT_EQ(r.stress.size(), 11u);
  const std::string bom = bomCsv(r);
  EXPECT_NE(bom.find("\nbolt,,15,"), std::string::npos) << bom;
}

// The hand grid's members as traced, but member u1 deployed onto a circle of radius 0.5 m.
std::vector<std::vector<Eigen::Vector3d>> deployedWithU1OnACircle(const EggGrid& grid) {
  std::vector<std::vector<Eigen::Vector3d>> deployed;
  for (const auto* family : {&grid.u, &grid.v}) {
    for (const auto& m : *family) deployed.push_back(m.spatial);
  }
  deployed[1].clear();
  for (int k = 0; k <= 8; ++k) {
    const double phi = -0.2 + 0.05 * k;
    deployed[1].emplace_back(0.5 * std::sin(phi), 0.1, 0.5 * std::cos(phi));
  }
  return deployed;
}

TEST(Fabricate, SimulatedCentrelinesDriveTheBendingStress) {
  const EggGrid grid = handGrid();
  const auto deployed = deployedWithU1OnACircle(grid);
  const auto r = fabricate({{0, &grid, deployed}}, handOptions());
  const auto& lime = materialByName("limewood");
  EXPECT_TRUE(r.stress[1].fromSimulation);
  EXPECT_NEAR(r.stress[1].maxBendingStressPa, lime.youngsModulusPa * 2.0 * 0.001 / 2.0, 1e-3);
  EXPECT_EQ(r.maxStressLamella, "P0-U1");
  EXPECT_NEAR(r.maxStressRatio, 9.1e6 / lime.bendingStrengthPa, 1e-9);
}

TEST(Fabricate, SheetSmallerThanTheWidestPartIsAClearError) {
  const EggGrid grid = handGrid();
  auto options = handOptions();
  options.sheetMm = {500.0, 18.0};  // 8 mm usable across: narrower than the 10 mm strips
  try {
    fabricate({{0, &grid, std::nullopt}}, options);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("fabrication.sheet_mm:", 0), 0u) << what;
    EXPECT_NE(what.find("P0-U0"), std::string::npos) << what;
    EXPECT_NE(what.find("210 x 10 mm"), std::string::npos) << what;
  }
  // The sticker foil too.
  options = handOptions();
  options.stickerSheetMm = std::array<double, 2>{15.0, 100.0};
  try {
    fabricate({{0, &grid, std::nullopt}}, options);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("fabrication.sticker_sheet_mm: part sticker P0-C1-1/P0-U1", 0),
        0u)
        << e.what();
  }
}

TEST(Fabricate, StripsLongerThanTheSheetAreSplicedToFitIt) {
  // 160 mm sheet, 5 mm margins: pieces of at most 150 mm although the stock is 1000 mm.
  const EggGrid grid = handGrid();
  auto options = handOptions();
  options.sheetMm = {160.0, 300.0};
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  EXPECT_DOUBLE_EQ(longestPieceMm(options), 150.0);
  EXPECT_EQ(r.splices, 6);
  for (const auto& plan : r.lamellae) EXPECT_DOUBLE_EQ(plan.splicesMm.at(0), 150.0) << plan.id;
}

// Scarf joints carry the stress over their length against scarf_efficiency x the strength, on
// the net width where a hole or slot runs through them (member u1 bent to R = 0.5 m: sigma =
// E t / (2 R) everywhere).
TEST(Fabricate, ScarfJointsAreCheckedAgainstTheirEfficiencyAndNetWidth) {
  const EggGrid grid = handGrid();
  const auto deployed = deployedWithU1OnACircle(grid);
  const auto& lime = materialByName("limewood");
  const double sigmaRatio = lime.youngsModulusPa * 0.001 / (2.0 * 0.5) / lime.bendingStrengthPa;
  auto options = handOptions();
  options.spliceJoint = SpliceJoint::Scarf;
  options.scarfEfficiency = 0.8;
  // 150 mm pieces: u1's scarf ends at 150 and begins at 138 (1:12 over 1 mm), between the slot
  // (103.5..111.5) and the end hole: the full width carries it.
  options.sheetMm = {160.0, 300.0};
  auto r = fabricate({{0, &grid, deployed}}, options);
  EXPECT_EQ(r.scarfJoints, 6);
  EXPECT_EQ(r.splices, 6);
  const auto& u1 = r.lamellae[1];
  ASSERT_EQ(u1.segments.size(), 2u);
  EXPECT_DOUBLE_EQ(u1.segments[0].endMm, 150.0);
  EXPECT_DOUBLE_EQ(u1.segments[1].startMm, 138.0);
  EXPECT_NEAR(r.stress[1].scarfRatios[0], sigmaRatio / 0.8, 1e-6);
  EXPECT_NEAR(r.maxScarfRatio, sigmaRatio / 0.8, 1e-6);
  EXPECT_EQ(r.maxScarfJoint, "P0-U1 S1");
  EXPECT_NEAR(r.stress[1].stressRatio, sigmaRatio / 0.8, 1e-6);  // the joint is the weakest place
  EXPECT_NE(bomCsv(r).find("splice_joint,P0-U1 S1,1,144.00"), std::string::npos) << bomCsv(r);
  // 120 mm pieces: the scarf runs from the gap before the slot (102) to 120, across the slot: the
  // net width 10 - 3 mm carries it.
  options.sheetMm = {130.0, 300.0};
  r = fabricate({{0, &grid, deployed}}, options);
  ASSERT_EQ(r.lamellae[1].segments.size(), 2u);
  EXPECT_DOUBLE_EQ(r.lamellae[1].segments[0].endMm, 120.0);
  EXPECT_DOUBLE_EQ(r.lamellae[1].segments[1].startMm, 102.0);
  EXPECT_NEAR(r.stress[1].scarfRatios[0], sigmaRatio / (0.8 * 0.7), 1e-6);
  // Plates: no scarf, nothing checked there.
  options.spliceJoint = SpliceJoint::Plate;
  r = fabricate({{0, &grid, deployed}}, options);
  EXPECT_EQ(r.scarfJoints, 0);
  EXPECT_DOUBLE_EQ(r.stress[1].scarfRatios.at(0), 0.0);
  EXPECT_NEAR(r.stress[1].stressRatio, sigmaRatio, 1e-6);
}

TEST(Fabricate, WrittenFilesReadBackAtTheHandPositions) {
  for (const char* tool : {"rsvg-convert", "pdfinfo", "admesh"}) {
    ASSERT_TRUE(testing::haveTool(tool)) << tool << " missing: run scripts/install-deps.sh";
  }
  const EggGrid grid = handGrid();
  const auto r = fabricate({{0, &grid, std::nullopt}}, handOptions());
  const auto dir = testing::scratchDir("fabricate");
  const auto files = writeFabricationFiles(r, dir);
  const std::vector<std::string> expected{"cut/sheet_01.svg",
                                          "cut/sheet_01.dxf",
                                          "cut/sheets.pdf",
                                          "cut/assembly.pdf",
                                          "cut/stickers_01.svg",
                                          "cut/stickers_01.dxf",
                                          "cut/stickers.pdf",
                                          "supports/supports.csv",
                                          "supports/support_001.stl",
                                          "supports/support_002.stl",
                                          "supports/support_003.stl",
                                          "supports/support_004.stl",
                                          "bom.csv",
                                          "cut.zip"};
  EXPECT_EQ(files, expected);
  // cut.zip holds the cut set and the BOM (unzip -l lists them).
  if (testing::haveTool("unzip")) {
    const auto list = testing::runTool("unzip -l " + (dir / "cut.zip").string());
    EXPECT_EQ(list.status, 0) << list.output;
    for (const char* f : {"cut/sheet_01.dxf", "cut/stickers.pdf", "bom.csv"})
      EXPECT_NE(list.output.find(f), std::string::npos) << list.output;
    EXPECT_EQ(list.output.find("supports/"), std::string::npos) << list.output;
  }

  // SVG: holes, slots and labels at the hand positions.
  const auto svg = testing::readSvg(testing::readText(dir / "cut/sheet_01.svg"));
  auto hasCircle = [&](Point p) {
    for (const auto& c : svg["circles"]) {
      if (near(c[0], p.x) && near(c[1], p.y) && near(c[2], 1.5)) return true;
    }
    return false;
  };
  for (Point p : kHolesU1) EXPECT_TRUE(hasCircle(p)) << p.x << ", " << p.y;
  EXPECT_TRUE(hasCircle({10.0, 31.0}));  // P0-V1 at (0,1)
  EXPECT_EQ(svg["circles"].size(), 16u);
  EXPECT_EQ(svg["slots"].size(), 2u);
  auto hasSlot = [&](const Point* k) {
    for (const auto& s : svg["slots"]) {
      if (near(s[0], k[0].x) && near(s[1], k[0].y) && near(s[4], k[1].x) && near(s[5], k[1].y))
        return true;
    }
    return false;
  };
  EXPECT_TRUE(hasSlot(kSlotU1));
  EXPECT_TRUE(hasSlot(kSlotV1));
  auto hasText = [&](const std::string& text, Point p) {
    for (const auto& t : svg["texts"]) {
      if (t[3] == text && near(t[0], p.x) && near(t[1], p.y)) return true;
    }
    return false;
  };
  EXPECT_TRUE(hasText("P0-U1", kLabelU1));
  EXPECT_TRUE(hasText("P0-C1-0", kLabelC10));

  // DXF: the same, through ezdxf; the audit finds nothing.
  const auto dxf = testing::readDxf(dir / "cut/sheet_01.dxf");
  EXPECT_EQ(dxf["audit_errors"], 0);
  EXPECT_EQ(dxf["audit_fixes"], 0);
  EXPECT_EQ(dxf["insunits"], 4);
  int circles = 0, slotsFound = 0, texts = 0, strokesU1 = 0, strokesC10 = 0, sheetId = 0;
  // Labels are single strokes on LABEL: P0-U1 centred on its anchor (15.57 mm wide: 109 font units
  // at 3 / 21 mm each, capitals 3 mm high), P0-C1-0 starting at its anchor (15.4 mm at 2.1).
  auto inside = [](const nlohmann::json& points, double x0, double x1, double y0, double y1) {
    for (const auto& p : points) {
      if (p[0] < x0 - 0.01 || p[0] > x1 + 0.01 || p[1] < y0 - 0.01 || p[1] > y1 + 0.01)
        return false;
    }
    return true;
  };
  for (const auto& e : dxf["entities"]) {
    if (e["type"] == "CIRCLE") {
      ++circles;
    } else if (e["type"] == "LWPOLYLINE" && e["points"].size() == 4 && e["points"][1][2] == 1.0) {
      for (const Point* k : {kSlotU1, kSlotV1}) {
        if (near(e["points"][0][0], k[0].x) && near(e["points"][0][1], k[0].y) &&
            near(e["points"][2][0], k[1].x) && near(e["points"][2][1], k[1].y)) {
          ++slotsFound;
        }
      }
    } else if (e["type"] == "TEXT" || e["type"] == "MTEXT") {
      ++texts;
    }
    if (e["type"] == "LWPOLYLINE" && e["layer"] == "LABEL") {
      strokesU1 += inside(e["points"], kLabelU1.x - 7.786, kLabelU1.x + 7.786, kLabelU1.y - 1.5,
                          kLabelU1.y + 1.5);
      strokesC10 += inside(e["points"], kLabelC10.x, kLabelC10.x + 15.4, kLabelC10.y - 1.05,
                           kLabelC10.y + 1.05);
    }
    if (e["type"] == "LWPOLYLINE" && e["layer"] == "REFERENCE") ++sheetId;
  }
  EXPECT_EQ(circles, 16);
  EXPECT_EQ(slotsFound, 2);
  EXPECT_EQ(texts, 0);  // no TEXT: no CAM tool needs a font
  // P0-U1: P (2 strokes), 0, -, U, 1 (one each) = 6; P0-C1-0: 2 + 1 + 1 + 1 + 1 + 1 + 1 = 8.
  EXPECT_EQ(strokesU1, 6);
  EXPECT_EQ(strokesC10, 8);
  EXPECT_GT(sheetId, 10);  // the sheet's outline and "L01 ..." in single strokes
  // One colour index per layer.
  std::set<int> colours;
  for (const char* layer : {"CUT", "ENGRAVE", "LABEL", "REFERENCE", "TOOLPATH"})
    colours.insert(dxf["layer_colours"][layer].get<int>());
  EXPECT_EQ(colours.size(), 5u);

  // Every DXF audits clean, every SVG renders, each PDF has its page count, every STL is closed.
  for (const auto& f : files) {
    const auto path = dir / f;
    if (path.extension() == ".dxf") {
      {
        const auto dxf = testing::readDxf(path);
        EXPECT_EQ(dxf["audit_errors"], 0) << f;
        EXPECT_EQ(dxf["audit_fixes"], 0) << f;
      }
    } else if (path.extension() == ".svg") {
      const auto run = testing::runTool("rsvg-convert --format=png --output " + path.string() +
                                        ".png " + path.string());
      EXPECT_EQ(run.status, 0) << f << ": " << run.output;
    } else if (f == "cut/assembly.pdf") {
      // ISO pages (A3 by default) and every lamella id of the run in the text.
      const auto info = testing::runTool("pdfinfo " + path.string());
      EXPECT_NE(info.output.find("(A3)"), std::string::npos) << info.output;
      const auto text = testing::runTool("pdftotext " + path.string() + " -");
      for (const auto& plan : r.lamellae)
        EXPECT_NE(text.output.find(plan.id), std::string::npos) << plan.id;
      EXPECT_NE(text.output.find("P0-C1-1"), std::string::npos);  // connections labelled
      EXPECT_NE(text.output.find("support plan"), std::string::npos);
      EXPECT_NE(text.output.find("Reason"), std::string::npos);
    } else if (path.extension() == ".pdf") {
      const auto run = testing::runTool("pdfinfo " + path.string());
      EXPECT_NE(run.output.find("Pages:           1"), std::string::npos)
          << f << ": " << run.output;
      // Fitted on A3 (the default), landscape.
      EXPECT_NE(run.output.find("(A3)"), std::string::npos) << f << ": " << run.output;
    } else if (path.extension() == ".stl") {
      const auto run = testing::runTool("admesh " + path.string());
      EXPECT_EQ(run.status, 0) << run.output;
      std::smatch m;
      ASSERT_TRUE(std::regex_search(
          run.output, m, std::regex(R"(Facets with 1 disconnected edge\s*:\s*([0-9]+))")))
          << run.output;
      EXPECT_EQ(m[1], "0") << f;
      ASSERT_TRUE(std::regex_search(run.output, m, std::regex(R"(Backwards edges\s*:\s*([0-9]+))")))
          << run.output;
      EXPECT_EQ(m[1], "0") << f;
    }
  }
}

TEST(Fabricate, LamellasLongerThanTheStockAreSplitClearOfTheirHoles) {
  const EggGrid grid = handGrid();
  auto options = handOptions();
  options.stockLengthMm = 150.0;
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  EXPECT_EQ(r.splices, 6);  // every 210 mm strip once
  for (const auto& plan : r.lamellae) {
    ASSERT_EQ(plan.segments.size(), 2u) << plan.id;
    for (const auto& seg : plan.segments) EXPECT_LE(seg.lengthMm(), 150.0);
    for (const auto& f : plan.features) {
      EXPECT_TRUE(f.maxXMm(3.0) + 10.0 <= plan.splicesMm[0] ||
                  f.minXMm(3.0) - 10.0 >= plan.splicesMm[0])
          << plan.id;
    }
  }
  const std::string bom = bomCsv(r);
  EXPECT_NE(bom.find("\nsplice,,6,"), std::string::npos) << bom;
  EXPECT_NE(bom.find("\nsplice_joint,P0-U1 S1,1,150.00,10.00,1.00,"), std::string::npos) << bom;
}

TEST(Fabricate, BoltSizesFromTheIsoTables) {
  // M16 through two 50 mm lamellas: grip 100 + 2 x 3 (ISO 7089 17x30x3) + 14.8 (ISO 4032 nut)
  // + 2 x 2 (pitch) = 124.8 mm, the next standard length 130 mm; through three: 174.8 -> 180.
  const BoltSize two = boltSize(16.0, 100.0), three = boltSize(16.0, 150.0);
  EXPECT_EQ(two.name, "M16x130");
  EXPECT_DOUBLE_EQ(two.lengthMm, 130.0);
  EXPECT_EQ(three.name, "M16x180");
  EXPECT_EQ(two.washerName, "ISO 7089 17x30x3");
  EXPECT_EQ(two.note.find(','), std::string::npos);  // a CSV field
  // Above 200 mm the steps are 20 mm: M8 through 190 mm: 190 + 3.2 + 6.8 + 2.5 = 202.5 -> 220.
  EXPECT_DOUBLE_EQ(boltSize(8.0, 190.0).lengthMm, 220.0);
  EXPECT_EQ(boltSize(9.0, 20.0).name, "d9x20");  // no M9: the grip, and a note
}

TEST(Fabricate, MultiPageSheetsPdf) {
  // A tighter sheet: 2 strips per sheet (one row of 210 + 0.5 + 210 on 440 - 10 usable... per row).
  const EggGrid grid = handGrid();
  auto options = handOptions();
  options.sheetMm = {440.0, 21.0};  // usable 430 x 11: one row of two strips
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  EXPECT_EQ(r.lamellaNesting.sheets, 3);
  const auto dir = testing::scratchDir("fabricate_pages");
  const auto files = writeFabricationFiles(r, dir, {true, false, false});
  // svg + dxf per sheet, sheets.pdf, assembly.pdf, bom.csv, cut.zip
  EXPECT_EQ(files.size(), 3u * 2u + 4u);
  const auto run = testing::runTool("pdfinfo " + (dir / "cut/sheets.pdf").string());
  EXPECT_NE(run.output.find("Pages:           3"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

// A solved patch end to end: the 6 m bump of samples/scenes/bump_patch.json (poplar plywood
// lamellas 100 x 10 mm). Its counts must match its grid; the numbers are printed for the record.
TEST(Fabricate, SolvedBumpPatchEndToEnd) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, 0.35);
  EggOptions egg;
  egg.maps.resolution = 41;
  egg.members.lamellaWidthM = 0.1;
  egg.members.spacingFactor = 6.0;
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}};
  const EggResult solved = solveEgg(mesh, corners, egg);
  const EggGrid& grid = solved.grid;
  FabricationOptions options;
  options.lamellaWidthMm = 100.0;
  options.lamellaThicknessMm = 10.0;
  options.sheetMm = {2500.0, 1250.0};
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  EXPECT_EQ(r.lamellae.size(), grid.u.size() + grid.v.size());
  EXPECT_EQ(r.connections, static_cast<int>(grid.connections.size()));
  EXPECT_EQ(r.counts.holes + r.counts.slots, 2 * static_cast<int>(grid.connections.size()));
  // Slots: exactly the inner members' notches of at least min_notch_mm (countNotches of the grid).
  EXPECT_EQ(r.counts.slots + r.counts.droppedBoundary,
            countNotches(grid, options.minNotchMm / 1000.0));
  EXPECT_GT(r.counts.slots, 0);
  EXPECT_EQ(r.supports.size(), grid.anchors.size());
  EXPECT_GT(r.maxStressRatio, 0.0);
  const auto dir = testing::scratchDir("fabricate_bump");
  const auto files = writeFabricationFiles(r, dir);
  for (const auto& f : files) {
    if (f.size() > 4 && f.substr(f.size() - 4) == ".dxf") {
      {
        const auto dxf = testing::readDxf(dir / f);
        EXPECT_EQ(dxf["audit_errors"], 0) << f;
        EXPECT_EQ(dxf["audit_fixes"], 0) << f;
      }
    }
  }
  std::cout << "bump patch: " << fabricationReport(r, files).dump() << "\n";
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

TEST(Fabricate, LamellasThatCannotBeSplicedAreListedAndTheRestIsCut) {
  // 20 mm stock with 100 mm clear of every hole (holes 100 mm apart): no lamella can be spliced.
  const EggGrid grid = testing::handGrid();
  auto options = testing::handOptions();
  options.stockLengthMm = 20.0;
  options.spliceClearanceMm = 100.0;
  options.minSpliceClearanceMm = 100.0;
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  ASSERT_EQ(r.unspliceable.size(), r.lamellae.size());
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    EXPECT_NE(r.unspliceable[i].find("lamella " + r.lamellae[i].id + " "), std::string::npos)
        << r.unspliceable[i];
    EXPECT_TRUE(r.lamellae[i].segments.empty());
  }
  EXPECT_EQ(r.lamellaNesting.sheets, 0);  // nothing to cut
  EXPECT_FALSE(r.stickers.empty());       // the stickers and supports do not depend on it
  EXPECT_EQ(fabricationReport(r)["unspliceable_lamellae"].size(), r.lamellae.size());
  EXPECT_NE(bomCsv(r).find("NOT CUT: no splice position"), std::string::npos);
  // With the hand options every lamella is one piece and none is listed.
  EXPECT_TRUE(fabricate({{0, &grid, std::nullopt}}, testing::handOptions()).unspliceable.empty());
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

TEST(Fabricate, DefaultSupportBlocksNarrowAboveSteepGround) {
  // Corner P0-C0-0 on a plane inclined 60 deg (normal along x), the points 30 mm above the ground.
  // The top of a block of side b falls (b / 2) tan 60 below the point: the widest that keeps 5 mm
  // above the ground is 2 (30 - 5) / tan 60 = 28.9 mm, so the default 3 w = 30 mm narrows to 28.
  EggGrid grid = testing::handGrid();
  grid.connections[0].normal = Eigen::Vector3d(std::sin(M_PI / 3.0), 0.0, std::cos(M_PI / 3.0));
  auto options = testing::handOptions();
  options.supportBlockMm.reset();
  options.groundHeightM = 0.47;
  const auto r = fabricate({{0, &grid, std::nullopt}}, options);
  ASSERT_EQ(r.supports.size(), 4u);
  EXPECT_EQ(r.supports[0].connectionId, "P0-C0-0");
  EXPECT_DOUBLE_EQ(r.supports[0].blockMm, 28.0);
  EXPECT_DOUBLE_EQ(r.supports[0].belowGroundMm, 0.0);
  for (size_t i = 1; i < r.supports.size(); ++i) EXPECT_DOUBLE_EQ(r.supports[i].blockMm, 30.0);
  EXPECT_EQ(r.narrowedSupportBlocks, 1);
  for (const auto& w : r.warnings) EXPECT_EQ(w.find("below the ground"), std::string::npos) << w;
  // 10 mm above the ground even a block of the lamella's width (10 mm) falls 5 tan 60 = 8.66 mm,
  // to 1.34 mm above the ground; the bottom goes 5 mm below that: 3.66 mm below the ground.
  options.groundHeightM = 0.49;
  const auto low = fabricate({{0, &grid, std::nullopt}}, options);
  EXPECT_DOUBLE_EQ(low.supports[0].blockMm, 10.0);
  EXPECT_NEAR(low.supports[0].belowGroundMm, 5.0 + 5.0 * std::tan(M_PI / 3.0) - 10.0, 1e-9);
  bool warned = false;
  for (const auto& w : low.warnings)
    warned |= w.find("the deepest: S001 (4 mm)") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_NE(supportsCsv(low.supports).find(",block,10,3.7\n"), std::string::npos)
      << supportsCsv(low.supports);
}

}  // namespace
}  // namespace egg::fabrication
