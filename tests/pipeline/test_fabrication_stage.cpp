#include "pipeline/fabrication_stage.hpp"

#include "core/errors.hpp"
#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

namespace egg::pipeline {
namespace {

// The scene holds fabrication::FabricationOptions itself; what it derives (the lamella's section
// and material, in mm) agrees with the library's defaults.
TEST(FabricationStage, SceneDefaultsAreTheLibraryDefaults) {
  const Scene scene =
      parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"}})"), "/scenes/test.json");
  const auto o = scene.fabricationOptions();
  const fabrication::FabricationOptions library;
  EXPECT_DOUBLE_EQ(o.lamellaWidthMm, library.lamellaWidthMm);  // 0.25 m
  EXPECT_DOUBLE_EQ(o.lamellaThicknessMm, library.lamellaThicknessMm);
  EXPECT_EQ(o.material, library.material);
  EXPECT_EQ(o.effectiveStickerSheetMm(), library.sheetMm);
  EXPECT_FALSE(o.endOverhangMm.has_value());
  EXPECT_NO_THROW(o.validate());
  EXPECT_TRUE(fabricationWanted(scene));
}

TEST(FabricationStage, SceneKeysReachTheOptions) {
  const Scene scene = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"},
      "lamella": {"width_m": 0.01, "thickness_m": 0.001, "material": "limewood"},
      "fabrication": {"sheet_mm": [1000, 600], "kerf_mm": 0.1, "stock_length_mm": 900, "end_overhang_mm": 6,
                      "ground_height_m": 0.2, "min_splice_clearance_mm": 7,
                      "splice_joint": "plate_or_scarf", "scarf_slope": 10, "scarf_efficiency": 0.9},
      "outputs": ["report", "stickers"]})"),
                                 "/scenes/test.json");
  const auto o = scene.fabricationOptions();
  EXPECT_DOUBLE_EQ(o.lamellaWidthMm, 10.0);
  EXPECT_DOUBLE_EQ(o.lamellaThicknessMm, 1.0);
  EXPECT_EQ(o.material, "limewood");
  EXPECT_DOUBLE_EQ(o.sheetMm[0], 1000.0);
  EXPECT_DOUBLE_EQ(o.kerfMm, 0.1);
  EXPECT_DOUBLE_EQ(o.stockLengthMm, 900.0);
  EXPECT_DOUBLE_EQ(o.effectiveEndOverhangMm(), 6.0);
  EXPECT_DOUBLE_EQ(*o.groundHeightM, 0.2);
  EXPECT_DOUBLE_EQ(o.effectiveMinSpliceClearanceMm(), 7.0);
  EXPECT_EQ(o.spliceJoint, fabrication::SpliceJoint::PlateOrScarf);
  EXPECT_DOUBLE_EQ(o.scarfLengthMm(), 10.0);  // 1:10 over 1 mm
  EXPECT_DOUBLE_EQ(o.scarfEfficiency, 0.9);
  const auto outputs = fabricationOutputsFromScene(scene);
  EXPECT_FALSE(outputs.cutFiles);
  EXPECT_TRUE(outputs.stickers);
  EXPECT_FALSE(outputs.supports);
  EXPECT_TRUE(fabricationWanted(scene));
}

TEST(FabricationStage, NotWantedWithoutItsOutputsOrWhenDisabled) {
  const Scene reportOnly =
      parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"}, "outputs": ["report"]})"),
                 "/scenes/test.json");
  EXPECT_FALSE(fabricationWanted(reportOnly));
  const Scene disabled =
      parseScene(nlohmann::json::parse(
                     R"({"surface": {"sample": "bump"}, "fabrication": {"enabled": false}})"),
                 "/scenes/test.json");
  EXPECT_FALSE(fabricationWanted(disabled));
}

TEST(FabricationStage, OneCallWritesWhatTheSceneAsksForAndReportsIt) {
  // The hand grid of the fabrication tests with its options given as scene keys.
  const Scene scene = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"},
      "lamella": {"width_m": 0.01, "thickness_m": 0.001, "material": "limewood"},
      "fabrication": {"sheet_mm": [500, 300], "kerf_mm": 0.5, "margin_mm": 5, "bolt_diameter_mm": 3,
                      "min_notch_mm": 1, "stock_length_mm": 1000, "end_overhang_mm": 5, "label_height_mm": 3,
                      "sticker_sheet_mm": [200, 100], "support_block_mm": 30},
      "outputs": ["report", "cut_files", "supports"]})"),
                                 "/scenes/test.json");
  const EggGrid grid = fabrication::testing::handGrid();
  const auto dir = fabrication::testing::scratchDir("stage");
  const auto stage = fabricateScene(scene, {{0, &grid, std::nullopt}}, dir);
  // No "stickers" output: no sticker sheets written (the stickers are still counted).
  const std::vector<std::string> expected{"cut/sheet_01.svg",
                                          "cut/sheet_01.dxf",
                                          "cut/sheets.pdf",
                                          "cut/assembly.pdf",
                                          "supports/supports.csv",
                                          "supports/support_001.stl",
                                          "supports/support_002.stl",
                                          "supports/support_003.stl",
                                          "supports/support_004.stl",
                                          "bom.csv",
                                          "cut.zip"};
  EXPECT_EQ(stage.files, expected);
  for (const auto& f : expected) EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  EXPECT_EQ(stage.report["lamellae"], 6);
  EXPECT_EQ(stage.report["notches"], 2);
  EXPECT_EQ(stage.report["plain_holes"], 1);
  EXPECT_EQ(stage.report["stickers"], 2);
  EXPECT_EQ(stage.report["supports"], 4);
  EXPECT_EQ(stage.report["sheets"], 1);
  EXPECT_EQ(stage.report["bolts"], 9);
  EXPECT_EQ(stage.report["files"].size(), expected.size());
}

TEST(FabricationStage, SheetTooSmallIsBadInputNamingTheSceneField) {
  const Scene scene = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"},
      "lamella": {"width_m": 0.01, "thickness_m": 0.001}, "fabrication": {"sheet_mm": [500, 13], "margin_mm": 2}})"),
                                 "/scenes/test.json");
  const EggGrid grid = fabrication::testing::handGrid();
  try {
    fabricateScene(scene, {{0, &grid, std::nullopt}},
                   fabrication::testing::scratchDir("stage_small"));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fabrication.sheet_mm:", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace egg::pipeline
