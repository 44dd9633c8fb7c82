#include "fabrication/options.hpp"

#include "core/errors.hpp"
#include "core/materials/materials.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace egg::fabrication {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& what) {
  throw InvalidInput(field + ": " + what);
}

void requirePositive(const std::string& field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    std::ostringstream msg;
    msg << "must be a positive number, got " << value;
    fail(field, msg.str());
  }
}

void requireNonNegative(const std::string& field, double value) {
  if (!std::isfinite(value) || value < 0.0) {
    std::ostringstream msg;
    msg << "must be zero or positive, got " << value;
    fail(field, msg.str());
  }
}

}  // namespace

double FabricationOptions::effectiveLabelHeightMm() const {
  if (labelHeightMm) return *labelHeightMm;
  return std::clamp(0.35 * lamellaWidthMm, 1.0, 30.0);
}

const char* toString(SpliceJoint joint) {
  switch (joint) {
    case SpliceJoint::Plate: return "plate";
    case SpliceJoint::Scarf: return "scarf";
    case SpliceJoint::PlateOrScarf: return "plate_or_scarf";
  }
  return "unknown";
}

const char* toString(DxfVersion version) { return version == DxfVersion::R12 ? "R12" : "R2000"; }

const char* toString(PaperSize size) {
  switch (size) {
    case PaperSize::A0: return "A0";
    case PaperSize::A1: return "A1";
    case PaperSize::A2: return "A2";
    case PaperSize::A3: return "A3";
    case PaperSize::A4: return "A4";
  }
  return "A3";
}

std::array<double, 2> paperSizeMm(PaperSize size) {
  switch (size) {
    case PaperSize::A0: return {841.0, 1189.0};
    case PaperSize::A1: return {594.0, 841.0};
    case PaperSize::A2: return {420.0, 594.0};
    case PaperSize::A3: return {297.0, 420.0};
    case PaperSize::A4: return {210.0, 297.0};
  }
  return {297.0, 420.0};
}

const char* toString(SheetPdf mode) {
  switch (mode) {
    case SheetPdf::Fit: return "fit";
    case SheetPdf::Tile: return "tile";
    case SheetPdf::TrueSize: return "true_size";
  }
  return "fit";
}

const char* toString(CutStock stock) { return stock == CutStock::Boards ? "boards" : "sheet"; }

void FabricationOptions::validate() const {
  requirePositive("lamella.width_m", lamellaWidthMm);
  requirePositive("lamella.thickness_m", lamellaThicknessMm);
  try {
    materialByName(material);
  } catch (const InvalidInput& e) {
    fail("lamella.material", e.what());
  }
  requirePositive("fabrication.sheet_mm", sheetMm[0]);
  requirePositive("fabrication.sheet_mm", sheetMm[1]);
  requireNonNegative("fabrication.kerf_mm", kerfMm);
  requireNonNegative("fabrication.margin_mm", marginMm);
  if (2.0 * marginMm >= std::min(sheetMm[0], sheetMm[1]))
    fail("fabrication.margin_mm", "leaves no room on the sheet");
  requirePositive("fabrication.bolt_diameter_mm", boltDiameterMm);
  if (boltDiameterMm >= lamellaWidthMm) {
    fail("fabrication.bolt_diameter_mm",
         "must be smaller than the lamella width (lamella.width_m)");
  }
  requireNonNegative("fabrication.min_notch_mm", minNotchMm);
  requirePositive("fabrication.stock_length_mm", stockLengthMm);
  if (endOverhangMm) {
    requireNonNegative("fabrication.end_overhang_mm", *endOverhangMm);
    if (*endOverhangMm < boltDiameterMm / 2.0) {
      fail("fabrication.end_overhang_mm",
           "must be at least half the bolt diameter (the end holes would be open)");
    }
  }
  if (spliceClearanceMm) requireNonNegative("fabrication.splice_clearance_mm", *spliceClearanceMm);
  if (minSpliceClearanceMm)
    requireNonNegative("fabrication.min_splice_clearance_mm", *minSpliceClearanceMm);
  if (!std::isfinite(scarfSlope) || scarfSlope < 4.0 || scarfSlope > 40.0) {
    std::ostringstream msg;
    msg << "must lie in [4, 40] (the run of the scarf per unit of thickness), got " << scarfSlope;
    fail("fabrication.scarf_slope", msg.str());
  }
  if (!std::isfinite(scarfEfficiency) || scarfEfficiency <= 0.0 || scarfEfficiency > 1.0) {
    std::ostringstream msg;
    msg << "must lie in (0, 1], got " << scarfEfficiency;
    fail("fabrication.scarf_efficiency", msg.str());
  }
  if (labelHeightMm) requirePositive("fabrication.label_height_mm", *labelHeightMm);
  requireNonNegative("fabrication.sticker_margin_mm", stickerMarginMm);
  if (stickerSheetMm) {
    requirePositive("fabrication.sticker_sheet_mm", (*stickerSheetMm)[0]);
    requirePositive("fabrication.sticker_sheet_mm", (*stickerSheetMm)[1]);
    if (2.0 * marginMm >= std::min((*stickerSheetMm)[0], (*stickerSheetMm)[1])) {
      fail("fabrication.sticker_sheet_mm",
           "leaves no room inside the margin (fabrication.margin_mm)");
    }
  }
  if (toolDiameterMm) {
    requirePositive("fabrication.tool_diameter_mm", *toolDiameterMm);
    if (*toolDiameterMm >= boltDiameterMm) {
      fail("fabrication.tool_diameter_mm",
           "must be smaller than the bolt holes and slots (fabrication.bolt_diameter_mm): a bit "
           "as wide or wider cannot rout them");
    }
  }
  if (groundHeightM && !std::isfinite(*groundHeightM))
    fail("fabrication.ground_height_m", "must be a finite number");
  if (supportBlockMm) {
    requirePositive("fabrication.support_block_mm", *supportBlockMm);
    if (*supportBlockMm <= 2.0 * boltDiameterMm) {
      fail("fabrication.support_block_mm",
           "must exceed twice the bolt diameter (room for the bolt hole)");
    }
  }
}

}  // namespace egg::fabrication
