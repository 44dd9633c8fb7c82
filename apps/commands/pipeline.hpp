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

struct PipelineOptions {
  std::filesystem::path out_dir = "out";   // the run folder; replaced whole at the end
  std::function<void(const std::string& stage, double fraction)> progress;  // optional
};

struct PipelineResult {
  nlohmann::json report;                   // what report.json holds
  std::filesystem::path out_dir;           // absolute path of the written run folder
  double seconds = 0.0;
  std::vector<std::string> failures;       // patches the EGG criteria rejected (exit code 1)
};

// Runs the scene. Input errors (InvalidInput, IoError) are thrown before anything is written;
// the run folder appears only when the run is complete.
PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options);

}  // namespace egg::app
