#include "pipeline/fabrication_stage.hpp"
#include "assembly/boundary_members.hpp"
#include "assembly/generalised_fabrication.hpp"
#include "core/errors.hpp"
#include "core/timing.hpp"

#include <fmt/core.h>
#include "pipeline/run_state.hpp"

namespace egg::pipeline {

fabrication::FabricationOutputs fabricationOutputsFromScene(const Scene& scene) {
  return {scene.wants("cut_files"), scene.wants("stickers"), scene.wants("supports")};
}

FabricationStageResult fabricateScene(const Scene& scene,
                                      const std::vector<fabrication::FabricationPatch>& patches,
                                      const std::filesystem::path& runDir,
                                      const std::vector<fabrication::SharedBoundary>& shared) {
  FabricationStageResult stage;
  stage.result = fabrication::fabricate(patches, scene.fabricationOptions(), shared);
  stage.files =
      fabrication::writeFabricationFiles(stage.result, runDir, fabricationOutputsFromScene(scene));
  stage.report = fabrication::fabricationReport(stage.result, stage.files);
  if (!stage.result.unspliceable.empty()) {
    stage.failures.push_back(
        "fabrication: " + std::to_string(stage.result.unspliceable.size()) +
        " lamellas cannot be spliced and are not in the cut files; the first: " +
        stage.result.unspliceable.front());
  }
  return stage;
}

bool fabricationWanted(const Scene& scene) {
  const auto o = fabricationOutputsFromScene(scene);
  return scene.fabrication.enabled && (o.cutFiles || o.stickers || o.supports);
}

std::string fabricationDisabled(const Scene& scene) {
  return scene.fabrication.enabled ? std::string()
                                   : "the scene disables it (fabrication.enabled = false)";
}

std::string fabricationSkipReason(const RunState& state) {
  return solvedCount(state.patches) == 0 ? "no solved patch grid to cut" : std::string();
}

namespace {

// Generalised patches (issue 41) are cut like the quads: their lamellas, holes, slots and stickers
// on the same sheets, supports under their ends on the rim, bolts and brackets to the quads'
// boundary lamellas (assembly/generalised_fabrication.hpp).
void addGeneralisedPatches(RunState& state, std::vector<fabrication::FabricationPatch>& grids) {
  const std::vector<const EggGrid*> quadGrids = gridsOf(state.patches);
  const auto fabrication = state.scene.fabricationOptions();
  assembly::GeneralisedFabricationOptions options;
  options.lamellaWidthM = state.scene.lamella.widthM;
  options.endOverhangM = fabrication.effectiveEndOverhangMm() / 1000.0;
  std::vector<std::string> untrimmed;
  for (const auto& g : state.generalised) {
    for (auto& end : assembly::addGeneralisedToFabrication(g, g.ring, quadGrids, options, grids))
      untrimmed.push_back(std::move(end));
    const auto& simulation = state.infillSimulations[g.piece];
    if (simulation) grids.back().deployedCentrelines = simulation->deployed.centrelines;
  }
  if (untrimmed.empty()) return;
  std::string list;
  for (size_t k = 0; k < untrimmed.size() && k < 8; ++k) list += (k ? ", " : "") + untrimmed[k];
  state.report.warn(fmt::format(
      "fabrication: {} generalised member ends meet a quad's boundary lamella in its own layer so "
      "close to a crossing or to their other end that they cannot be cut back to its face for "
      "their bracket; they are "
      "cut as drawn and overlap the lamella (the bracket detail there is the engineer's): {}{}",
      untrimmed.size(), list, untrimmed.size() > 8 ? ", ..." : ""));
}

}  // namespace

void fabricationStage(RunState& state) {
  const Stopwatch watch;
  std::vector<fabrication::FabricationPatch> grids;
  for (const auto& p : state.patches) {
    if (!p.egg) continue;
    fabrication::FabricationPatch entry{p.id, &p.egg->grid, std::nullopt};
    if (p.simulation) entry.deployedCentrelines = p.simulation->deployed.centrelines;
    entry.freeSides =
        assembly::freeSides(state.patching->graph, p.id);  // supports only on the design boundary
    grids.push_back(std::move(entry));
  }
  addGeneralisedPatches(state, grids);
  // The grid decides whether its parts can be cut (a part wider than the sheet; a lamella whose
  // slots leave no place for a splice is left out and listed, fab.failures): a failure of this
  // run with its report, not bad input (the options themselves were checked when the scene was
  // read).
  try {
    FabricationStageResult fab =
        fabricateScene(state.scene, grids, state.staging,
                       assembly::sharedLamellae(state.patching->graph, gridsOf(state.patches)));
    state.report.stageRan("fabrication", watch.seconds());
    state.report.section("fabrication") = fab.report;
    // Every stage's warnings also in the top-level list, where a reader looks first.
    for (const auto& w : fab.report.value("warnings", nlohmann::json::array()))
      state.report.warn("fabrication: " + (w.is_string() ? w.get<std::string>() : w.dump()));
    state.failures.insert(state.failures.end(), fab.failures.begin(), fab.failures.end());
    state.fabricated = std::move(fab.result);
  } catch (const InvalidInput& e) {
    state.report.stageSkipped(
        "fabrication", std::string("the grid cannot be cut with these settings: ") + e.what());
    state.failures.push_back(std::string("fabrication: ") + e.what());
  }
}

}  // namespace egg::pipeline
