#pragma once
// report.json of `egg run` (DESIGN.md "Report"). Every top-level key is always present; a stage
// that did not run says "ran": false and why. Units are in the keys (`_m`, `_m2`, `_rad`, `seconds`).
#include "core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace egg::app {

// The stages of the pipeline in data-flow order (DESIGN.md "Data flow").
const std::vector<std::string>& pipelineStages();

class RunReport {
 public:
  explicit RunReport(nlohmann::json scene);

  // Records that `stage` ran and took `seconds`.
  void stageRan(const std::string& stage, double seconds);
  // Records that `stage` did not run and why ("the scene disables it", "needs patches", ...).
  void stageSkipped(const std::string& stage, const std::string& reason);

  // Top-level sections (surface, patches, coverage, propagation, simulation, fabrication).
  nlohmann::json& section(const std::string& key) { return document_[key]; }
  void warn(const std::string& message) { document_["warnings"].push_back(message); }
  nlohmann::json& document() { return document_; }

  // Completes the required keys (a section of a stage that did not run gets "ran": false and
  // the stage's reason) and the total time. Call once, before writing.
  nlohmann::json finish(double totalSeconds) const;

 private:
  nlohmann::json document_;
};

// An output folder that appears whole or not at all: files are written into a hidden sibling
// staging folder, and commit() swaps it in place of the target (replacing an earlier run).
// If commit() is never called (an exception), the staging folder is removed.
// An existing target is replaced only if it is empty or an earlier eggshell run folder (it holds
// the marker file kRunMarker): `egg run -o ~` must never delete someone's home.
constexpr const char* kRunMarker = ".eggshell-run";

class StagedDirectory {
 public:
  explicit StagedDirectory(std::filesystem::path target);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  // Where to write files now (the staging folder).
  const std::filesystem::path& staging() const { return staging_; }
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace egg::app
