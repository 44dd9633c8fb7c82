#include "fabrication/options.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg::fabrication {
namespace {

void expectFieldError(const FabricationOptions& o, const std::string& field) {
  try {
    o.validate();
    FAIL() << "expected InvalidInput naming " << field;
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind(field + ":", 0), 0u) << e.what();
  }
}

TEST(FabricationOptions, DefaultsAreValid) {
  EXPECT_NO_THROW(FabricationOptions{}.validate());
  FabricationOptions o;
  EXPECT_DOUBLE_EQ(o.effectiveEndOverhangMm(), 125.0);      // half the 250 mm width
  EXPECT_DOUBLE_EQ(o.effectiveSpliceClearanceMm(), 250.0);  // the width
  EXPECT_DOUBLE_EQ(o.effectiveLabelHeightMm(), 30.0);       // 0.35 w = 87.5, clamped
  o.lamellaWidthMm = 10.0;
  EXPECT_DOUBLE_EQ(o.effectiveLabelHeightMm(), 3.5);
}

TEST(FabricationOptions, EachBadFieldIsNamed) {
  FabricationOptions o;
  o.sheetMm = {0.0, 100.0};
  expectFieldError(o, "fabrication.sheet_mm");
  o = {};
  o.kerfMm = -1.0;
  expectFieldError(o, "fabrication.kerf_mm");
  o = {};
  o.marginMm = 700.0;
  expectFieldError(o, "fabrication.margin_mm");
  o = {};
  o.boltDiameterMm = 300.0;
  expectFieldError(o, "fabrication.bolt_diameter_mm");
  o = {};
  o.minNotchMm = -0.1;
  expectFieldError(o, "fabrication.min_notch_mm");
  o = {};
  o.stockLengthMm = 0.0;
  expectFieldError(o, "fabrication.stock_length_mm");
  o = {};
  o.endOverhangMm = 1.0;
  expectFieldError(o, "fabrication.end_overhang_mm");
  o = {};
  o.material = "balsa";
  expectFieldError(o, "lamella.material");
  o = {};
  o.scarfSlope = 2.0;
  expectFieldError(o, "fabrication.scarf_slope");
  o = {};
  o.scarfEfficiency = 1.5;
  expectFieldError(o, "fabrication.scarf_efficiency");
  o = {};
  o.supportBlockMm = 10.0;
  expectFieldError(o, "fabrication.support_block_mm");
  o = {};
  o.stickerSheetMm = std::array<double, 2>{100.0, -1.0};
  expectFieldError(o, "fabrication.sticker_sheet_mm");
}

}  // namespace
}  // namespace egg::fabrication
