#include "apps/commands/fabrication_stage.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg::app {
namespace {

TEST(FabricationStage, SceneDefaultsAreTheLibraryDefaults) {
  const Scene scene = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"}})"), "/scenes/test.json");
  const auto o = fabricationOptionsFromScene(scene);
  const fabrication::FabricationOptions library;
  EXPECT_DOUBLE_EQ(o.lamella_width_mm, library.lamella_width_mm);  // 0.25 m
  EXPECT_DOUBLE_EQ(o.lamella_thickness_mm, library.lamella_thickness_mm);
  EXPECT_EQ(o.material, library.material);
  EXPECT_EQ(o.sheet_mm, library.sheet_mm);
  EXPECT_DOUBLE_EQ(o.kerf_mm, library.kerf_mm);
  EXPECT_DOUBLE_EQ(o.margin_mm, library.margin_mm);
  EXPECT_DOUBLE_EQ(o.bolt_diameter_mm, library.bolt_diameter_mm);
  EXPECT_DOUBLE_EQ(o.min_notch_mm, library.min_notch_mm);
  EXPECT_DOUBLE_EQ(o.stock_length_mm, library.stock_length_mm);
  EXPECT_DOUBLE_EQ(o.sticker_margin_mm, library.sticker_margin_mm);
  EXPECT_EQ(o.stickerSheetMm(), library.sheet_mm);
  EXPECT_EQ(o.supports_at_boundary_connections, library.supports_at_boundary_connections);
  EXPECT_FALSE(o.end_overhang_mm.has_value());
  EXPECT_NO_THROW(o.validate());
  EXPECT_TRUE(fabricationWanted(scene));
}

TEST(FabricationStage, SceneKeysReachTheOptions) {
  const Scene scene = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"},
      "lamella": {"width_m": 0.01, "thickness_m": 0.001, "material": "limewood"},
      "fabrication": {"sheet_mm": [1000, 600], "kerf_mm": 0.1, "stock_length_mm": 900, "end_overhang_mm": 6,
                      "ground_height_m": 0.2},
      "outputs": ["report", "stickers"]})"),
                                 "/scenes/test.json");
  const auto o = fabricationOptionsFromScene(scene);
  EXPECT_DOUBLE_EQ(o.lamella_width_mm, 10.0);
  EXPECT_DOUBLE_EQ(o.lamella_thickness_mm, 1.0);
  EXPECT_EQ(o.material, "limewood");
  EXPECT_DOUBLE_EQ(o.sheet_mm[0], 1000.0);
  EXPECT_DOUBLE_EQ(o.kerf_mm, 0.1);
  EXPECT_DOUBLE_EQ(o.stock_length_mm, 900.0);
  EXPECT_DOUBLE_EQ(o.endOverhangMm(), 6.0);
  EXPECT_DOUBLE_EQ(*o.ground_height_m, 0.2);
  const auto outputs = fabricationOutputsFromScene(scene);
  EXPECT_FALSE(outputs.cutFiles);
  EXPECT_TRUE(outputs.stickers);
  EXPECT_FALSE(outputs.supports);
  EXPECT_TRUE(fabricationWanted(scene));
}

TEST(FabricationStage, NotWantedWithoutItsOutputsOrWhenDisabled) {
  const Scene reportOnly = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"}, "outputs": ["report"]})"),
                                      "/scenes/test.json");
  EXPECT_FALSE(fabricationWanted(reportOnly));
  const Scene disabled = parseScene(nlohmann::json::parse(R"({"surface": {"sample": "bump"}, "fabrication": {"enabled": false}})"),
                                    "/scenes/test.json");
  EXPECT_FALSE(fabricationWanted(disabled));
}

}  // namespace
}  // namespace egg::app
