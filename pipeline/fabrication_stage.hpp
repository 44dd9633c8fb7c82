#pragma once
// The fabrication stage (Sections 3.5, 3.6.1): cut files, stickers, supports and the BOM of the
// traced grids (fabrication/fabricate.hpp), with its options and files from the scene, and
// stresses from the deployed centrelines where the simulation ran.
#include "fabrication/fabricate.hpp"
#include "pipeline/scene.hpp"

namespace egg::pipeline {

struct RunState;

// The outputs "cut_files", "stickers" and "supports" of the scene.
fabrication::FabricationOutputs fabricationOutputsFromScene(const Scene& scene);

// Whether the stage runs at all: fabrication.enabled and at least one of its outputs asked for.
bool fabricationWanted(const Scene& scene);

struct FabricationStageResult {
  fabrication::FabricationResult result;
  std::vector<std::string> files;  // written, relative to the run folder
  nlohmann::json report;           // report.json "fabrication"
  std::vector<std::string>
      failures;  // for the run's failures (exit 1): lamellas that could not be cut
};

// The whole stage in one call: fabricate with the scene's options, write what its outputs ask for
// below `runDir` (bom.csv always), and the report section. Throws as fabricate() and
// writeFabricationFiles() do (InvalidInput: bad input; WriteError: a file).
FabricationStageResult fabricateScene(const Scene& scene,
                                      const std::vector<fabrication::FabricationPatch>& patches,
                                      const std::filesystem::path& runDir,
                                      const std::vector<fabrication::SharedBoundary>& shared = {});

// Stage table row: the scene may switch it off; nothing to cut without a solved grid. A grid whose
// parts cannot be cut with the scene's settings (a part wider than the sheet) is a failure of
// the run with its report, recorded as the stage's skip reason.
std::string fabricationDisabled(const Scene& scene);
std::string fabricationSkipReason(const RunState& state);
void fabricationStage(RunState& state);
}  // namespace egg::pipeline
