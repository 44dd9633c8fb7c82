#pragma once
// `egg stress --suite pipeline` (issue 18, "Stiff and extreme cases over the whole pipeline"): a
// fixed suite of scenes and meshes run through the real pipeline, each in its own child process
// with a time limit, so a hang is caught, a crash does not take the suite down, and peak memory is
// per case. A case passes when it converges or stops with a stated reason (a typed error from
// core/errors.hpp is the right answer for a non-manifold or disconnected mesh); it fails on a
// non-finite number, a crash, a timeout, or a non-zero exit without a message.
#include "core/io/child_process.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace egg::app {

struct PipelineStressCase {
  std::string name;
  std::string kind;  // the class: width_thickness, youngs_modulus, scale, ...
  std::string description;
  nlohmann::json scene;  // an `egg run` scene; surface.file "mesh.obj" when writeMesh is set
  std::function<void(const std::filesystem::path&)> writeMesh;  // writes the case's OBJ
  bool surfaceOnly = false;  // `egg surface --stats` + `egg geodesic` instead of `egg run`
  bool geodesic = true;  // surfaceOnly: also the geodesic field (`egg stress --large-mesh-stages
                         // surface` drops it)
  double timeLimitS = 60.0;
};

// The fixed suite (same cases every run, in this order).
std::vector<PipelineStressCase> pipelineStressCases();

struct PipelineStressRow {
  std::string name, kind, stages, result;
  bool ok = false;  // converged or a stated reason; false: NaN, crash, timeout
  int iterations = 0;
  double rmseM = 0.0, maxErrorM = 0.0, seconds = 0.0, peakRssMb = 0.0;
  nlohmann::json toJson() const;
};

// Interprets one child's outcome plus the report it wrote (null if none).
PipelineStressRow classify(const PipelineStressCase& c, const ChildOutcome& o,
                           const nlohmann::json& report);

// Runs a case; `command` runs `egg` with the given arguments (exec in `egg stress`).
using EggCommand = std::function<int(const std::vector<std::string>& args)>;
PipelineStressRow runPipelineStressCase(const PipelineStressCase& c, const EggCommand& command,
                                        const std::filesystem::path& workDir);

}  // namespace egg::app
