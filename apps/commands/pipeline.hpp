#pragma once
// The whole job of `egg run`: scene -> surface -> patching -> per-patch EGG solve -> propagation
// -> grid -> simulation -> fabrication (DESIGN.md "Data flow"). Stages run lazily: a stage runs
// only when an output the scene asks for needs it, and every stage records its time and its own
// error figure in the report.
#include "apps/commands/report.hpp"
#include "apps/commands/scene.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace egg::app {

// Which stages a scene's outputs need (DESIGN.md: "outputs drives the graph"):
//   report    -> patching, design, grid, simulation (if enabled)
//   previews  -> patching, design, grid, simulation (if enabled)
//   plan      -> patching, design (patches.json, plan.svg)
//   cut_files, stickers, supports -> patching, design, grid, fabrication (and the simulation, if
//   enabled, when the report or previews ask for it: stresses then come from the deployed shape)
struct StageNeeds {
  bool surface = false, patching = false, grid = false, simulation = false, fabrication = false;
};
StageNeeds stageNeeds(const Scene& scene);

// Throws InvalidInput (exit 2, before anything is computed or written) when a requested output
// cannot be produced: a stage it needs is disabled by the scene or not built yet.
void checkOutputsCanBeProduced(const Scene& scene);

struct PipelineOptions {
  std::filesystem::path out_dir = "out";   // the run folder; replaced whole at the end
  std::function<void(const std::string& stage, double fraction)> progress;  // optional
};

struct PipelineResult {
  nlohmann::json report;                   // what report.json holds
  std::filesystem::path out_dir;           // absolute path of the written run folder
  double seconds = 0.0;
  // Exit code 1: patches the EGG criteria reject in the final layout (a patch Workflow 1 split is
  // not one), grids that cannot be traced, a deployment that does not converge.
  std::vector<std::string> failures;
  bool nothingRequested = false;           // outputs: []: no stage ran, nothing was written
};

// Runs the scene. Input errors (InvalidInput, IoError) are thrown before anything is written;
// the run folder appears only when the run is complete.
PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options);

}  // namespace egg::app
