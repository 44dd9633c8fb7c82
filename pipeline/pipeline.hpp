#pragma once
// The whole job of `egg run`: scene -> surface -> patching -> per-patch EGG solve -> propagation
// -> grid -> simulation -> fabrication (docs/architecture.md "Data flow"), a loop over the stage
// table (stages.hpp). Stages run lazily: a stage runs only when an output the scene asks for
// needs it, and every stage records its time and its own error figure in the report.
#include "pipeline/report.hpp"
#include "pipeline/scene.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace egg::pipeline {

// Throws InvalidInput (exit 2, before anything is computed or written) when a requested output
// cannot be produced: a stage it needs is disabled by the scene or not built yet.
void checkOutputsCanBeProduced(const Scene& scene);

struct PipelineOptions {
  std::filesystem::path outDir = "out";  // the run folder; replaced whole at the end
  std::function<void(const std::string& stage, double fraction)> progress;  // optional
};

struct PipelineResult {
  nlohmann::json report;         // what report.json holds
  std::filesystem::path outDir;  // absolute path of the written run folder
  double seconds = 0.0;
  // Exit code 1: patches the EGG criteria reject in the final layout (a patch Workflow 1 split is
  // not one), grids that cannot be traced, a deployment that does not converge.
  std::vector<std::string> failures;
  bool nothingRequested = false;  // outputs: []: no stage ran, nothing was written
};

// Runs the scene. Input errors (InvalidInput, IoError) are thrown before anything is written;
// the run folder appears only when the run is complete.
PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options);

}  // namespace egg::pipeline
