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

double FabricationOptions::labelHeightMm() const {
  if (label_height_mm) return *label_height_mm;
  return std::clamp(0.35 * lamella_width_mm, 1.0, 30.0);
}

const char* toString(SpliceJoint joint) {
  switch (joint) {
    case SpliceJoint::Plate: return "plate";
    case SpliceJoint::Scarf: return "scarf";
    case SpliceJoint::PlateOrScarf: return "plate_or_scarf";
  }
  return "unknown";
}

void FabricationOptions::validate() const {
  requirePositive("lamella.width_m", lamella_width_mm);
  requirePositive("lamella.thickness_m", lamella_thickness_mm);
  try {
    materialByName(material);
  } catch (const InvalidInput& e) {
    fail("lamella.material", e.what());
  }
  requirePositive("fabrication.sheet_mm", sheet_mm[0]);
  requirePositive("fabrication.sheet_mm", sheet_mm[1]);
  requireNonNegative("fabrication.kerf_mm", kerf_mm);
  requireNonNegative("fabrication.margin_mm", margin_mm);
  if (2.0 * margin_mm >= std::min(sheet_mm[0], sheet_mm[1])) fail("fabrication.margin_mm", "leaves no room on the sheet");
  requirePositive("fabrication.bolt_diameter_mm", bolt_diameter_mm);
  if (bolt_diameter_mm >= lamella_width_mm) {
    fail("fabrication.bolt_diameter_mm", "must be smaller than the lamella width (lamella.width_m)");
  }
  requireNonNegative("fabrication.min_notch_mm", min_notch_mm);
  requirePositive("fabrication.stock_length_mm", stock_length_mm);
  if (end_overhang_mm) {
    requireNonNegative("fabrication.end_overhang_mm", *end_overhang_mm);
    if (*end_overhang_mm < bolt_diameter_mm / 2.0) {
      fail("fabrication.end_overhang_mm", "must be at least half the bolt diameter (the end holes would be open)");
    }
  }
  if (splice_clearance_mm) requireNonNegative("fabrication.splice_clearance_mm", *splice_clearance_mm);
  if (min_splice_clearance_mm) requireNonNegative("fabrication.min_splice_clearance_mm", *min_splice_clearance_mm);
  if (!std::isfinite(scarf_slope) || scarf_slope < 4.0 || scarf_slope > 40.0) {
    std::ostringstream msg;
    msg << "must lie in [4, 40] (the run of the scarf per unit of thickness), got " << scarf_slope;
    fail("fabrication.scarf_slope", msg.str());
  }
  if (!std::isfinite(scarf_efficiency) || scarf_efficiency <= 0.0 || scarf_efficiency > 1.0) {
    std::ostringstream msg;
    msg << "must lie in (0, 1], got " << scarf_efficiency;
    fail("fabrication.scarf_efficiency", msg.str());
  }
  if (label_height_mm) requirePositive("fabrication.label_height_mm", *label_height_mm);
  requireNonNegative("fabrication.sticker_margin_mm", sticker_margin_mm);
  if (sticker_sheet_mm) {
    requirePositive("fabrication.sticker_sheet_mm", (*sticker_sheet_mm)[0]);
    requirePositive("fabrication.sticker_sheet_mm", (*sticker_sheet_mm)[1]);
    if (2.0 * margin_mm >= std::min((*sticker_sheet_mm)[0], (*sticker_sheet_mm)[1])) {
      fail("fabrication.sticker_sheet_mm", "leaves no room inside the margin (fabrication.margin_mm)");
    }
  }
  if (ground_height_m && !std::isfinite(*ground_height_m)) fail("fabrication.ground_height_m", "must be a finite number");
  if (support_block_mm) {
    requirePositive("fabrication.support_block_mm", *support_block_mm);
    if (*support_block_mm <= 2.0 * bolt_diameter_mm) {
      fail("fabrication.support_block_mm", "must exceed twice the bolt diameter (room for the bolt hole)");
    }
  }
}

}  // namespace egg::fabrication
