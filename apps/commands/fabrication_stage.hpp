#pragma once
// The scene's side of the fabrication stage (fabrication/fabricate.hpp): its options and which
// files to write, read from the scene, so the pipeline wires the stage in one call:
//   if (fabricationWanted(scene))
//     report["fabrication"] = runFabricationStage(scene, patches, runDir).report;
// with patches = {{patchId, &grid, deployed centrelines (u then v) or std::nullopt}, ...}.
#include "apps/commands/scene.hpp"
#include "fabrication/fabricate.hpp"
#include "patching/patch_graph.hpp"

#include <array>

namespace egg::app {

// Lamella width/thickness (m in the scene, mm here) and material, and every fabrication.* key.
fabrication::FabricationOptions fabricationOptionsFromScene(const Scene& scene);

// The outputs "cut_files", "stickers" and "supports" of the scene.
fabrication::FabricationOutputs fabricationOutputsFromScene(const Scene& scene);

// The sides of `patch` the patch graph calls free (on the design surface's boundary, not shared
// with another patch), for FabricationPatch::freeSides: supports stand only there. All four when
// the graph does not know the patch (a single patch without a graph).
std::array<bool, 4> freeSidesOf(const patching::PatchGraph& graph, int patch);

// Whether the stage runs at all: fabrication.enabled and at least one of its outputs asked for.
bool fabricationWanted(const Scene& scene);

struct FabricationStageResult {
  fabrication::FabricationResult result;
  std::vector<std::string> files;  // written, relative to the run folder
  nlohmann::json report;           // report.json "fabrication"
  std::vector<std::string> failures;  // for the run's failures (exit 1): lamellas that could not be cut
};

// The whole stage in one call: fabricate with the scene's options, write what its outputs ask for
// below `runDir` (bom.csv always), and the report section. Throws as fabricate() and
// writeFabricationFiles() do (InvalidInput: bad input; WriteError: a file).
FabricationStageResult runFabricationStage(const Scene& scene, const std::vector<fabrication::FabricationPatch>& patches,
                                           const std::filesystem::path& runDir,
                                           const std::vector<fabrication::SharedBoundary>& shared = {});

}  // namespace egg::app
