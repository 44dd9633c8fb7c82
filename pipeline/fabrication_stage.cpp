#include "pipeline/fabrication_stage.hpp"
#include "assembly/boundary_members.hpp"
#include "assembly/patch_joins.hpp"
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

std::string endId(const assembly::GeneralisedPatch& g, int rod, bool atStart) {
  const bool isU = rod < static_cast<int>(g.grid.u.size());
  return fmt::format("P{}-{}{}-{}", g.patchId, isU ? 'U' : 'V',
                     isU ? rod : rod - static_cast<int>(g.grid.u.size()),
                     atStart ? "start" : "end");
}

// Generalised patches (issue 41) are cut like the quads: their lamellas, holes, slots and stickers
// on the same sheets. Every member end gets a bolt hole: through its support where it stands on
// the design boundary or a hole's rim, through the quad's boundary lamella where it laps onto it
// (that lamella gets the partner hole), or into its bracket on the ring beam.
void addGeneralisedPatches(const RunState& state,
                           std::vector<fabrication::FabricationPatch>& grids) {
  const std::vector<const EggGrid*> quadGrids = gridsOf(state.patches);
  const std::vector<char> swapped = assembly::layerSwaps(state.patching->graph, quadGrids);
  for (const auto& g : state.generalised) {
    fabrication::FabricationPatch entry{g.patchId, &g.grid, std::nullopt};
    const assembly::RingBeamJoins ring =
        assembly::ringBeamJoins(g, 0, quadGrids, swapped, state.scene.lamella.widthM);
    entry.boltedTo = ring.quads;
    entry.freeSides = {false, false, false, false};
    const auto& simulation = state.infillSimulations[g.piece];
    if (simulation) entry.deployedCentrelines = simulation->deployed.centrelines;
    for (size_t a = 0; a < g.network.anchors.size(); ++a) {
      const auto& anchor = g.network.anchors[a];
      const bool isU = anchor.rod < static_cast<int>(g.grid.u.size());
      const int member = isU ? anchor.rod : anchor.rod - static_cast<int>(g.grid.u.size());
      const std::string id = endId(g, anchor.rod, a % 2 == 0);
      entry.extraHoles.push_back({isU ? Family::U : Family::V, member, anchor.sM, id, true});
      if (g.anchorHolds[a] == patching::AnchorHold::DesignBoundary)
        entry.endSupports.push_back({id, anchor.position, anchor.normal});
    }
    for (const auto& bolt : ring.bolts) {
      for (auto& quad : grids) {
        if (quad.patchId != bolt.patchA) continue;
        const int u = static_cast<int>(quad.grid->u.size());
        quad.extraHoles.push_back({bolt.rodA < u ? Family::U : Family::V,
                                   bolt.rodA < u ? bolt.rodA : bolt.rodA - u, bolt.sAM,
                                   endId(g, bolt.rodB, bolt.sBM == 0.0), false});
      }
    }
    grids.push_back(std::move(entry));
  }
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
