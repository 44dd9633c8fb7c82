#include "apps/commands/fabrication_stage.hpp"

namespace egg::app {

fabrication::FabricationOptions fabricationOptionsFromScene(const Scene& scene) {
  const FabricationSpec& f = scene.fabrication;
  fabrication::FabricationOptions o;
  o.lamella_width_mm = scene.lamella.width_m * 1000.0;
  o.lamella_thickness_mm = scene.lamella.thickness_m * 1000.0;
  o.material = scene.lamella.material;
  o.sheet_mm = f.sheet_mm;
  o.kerf_mm = f.kerf_mm;
  o.margin_mm = f.margin_mm;
  o.bolt_diameter_mm = f.bolt_diameter_mm;
  o.min_notch_mm = f.min_notch_mm;
  o.stock_length_mm = f.stock_length_mm;
  o.end_overhang_mm = f.end_overhang_mm;
  o.splice_clearance_mm = f.splice_clearance_mm;
  o.min_splice_clearance_mm = f.min_splice_clearance_mm;
  o.label_height_mm = f.label_height_mm;
  o.splice_joint = f.splice_joint;
  o.scarf_slope = f.scarf_slope;
  o.scarf_efficiency = f.scarf_efficiency;
  o.sticker_margin_mm = f.sticker_margin_mm;
  o.sticker_sheet_mm = f.sticker_sheet_mm;
  o.ground_height_m = f.ground_height_m;
  o.support_block_mm = f.support_block_mm;
  o.supports_at_boundary_connections = f.supports_at_boundary_connections;
  return o;
}

fabrication::FabricationOutputs fabricationOutputsFromScene(const Scene& scene) {
  return {scene.wants("cut_files"), scene.wants("stickers"), scene.wants("supports")};
}

FabricationStageResult runFabricationStage(const Scene& scene, const std::vector<fabrication::FabricationPatch>& patches,
                                           const std::filesystem::path& runDir,
                                           const std::vector<fabrication::SharedBoundary>& shared) {
  FabricationStageResult stage;
  stage.result = fabrication::fabricate(patches, fabricationOptionsFromScene(scene), shared);
  stage.files = fabrication::writeFabricationFiles(stage.result, runDir, fabricationOutputsFromScene(scene));
  stage.report = fabrication::fabricationReport(stage.result, stage.files);
  if (!stage.result.unspliceable.empty()) {
    stage.failures.push_back("fabrication: " + std::to_string(stage.result.unspliceable.size()) +
                             " lamellas cannot be spliced and are not in the cut files; the first: " +
                             stage.result.unspliceable.front());
  }
  return stage;
}

std::array<bool, 4> freeSidesOf(const patching::PatchGraph& graph, int patch) {
  std::array<bool, 4> free{false, false, false, false};
  bool known = false;
  for (const auto& b : graph.boundaries) {
    for (const auto& use : b.uses) {
      if (use.patch != patch || use.side < 0 || use.side > 3) continue;
      known = true;
      if (b.kind == "free") free[use.side] = true;
    }
  }
  return known ? free : std::array<bool, 4>{true, true, true, true};
}

bool fabricationWanted(const Scene& scene) {
  const auto o = fabricationOutputsFromScene(scene);
  return scene.fabrication.enabled && (o.cutFiles || o.stickers || o.supports);
}

}  // namespace egg::app
