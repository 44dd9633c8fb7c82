#pragma once
// report.json of `egg run` (docs/architecture.md "Report"). Every top-level key is always present;
// a stage that did not run says "ran": false and why. Units are in the keys (`_m`, `_m2`, `_rad`,
// `seconds`).
#include <nlohmann/json.hpp>

#include <string>

namespace egg::pipeline {

class RunReport {
 public:
  explicit RunReport(nlohmann::json scene);

  // Records that `stage` ran and took `seconds`.
  void stageRan(const std::string& stage, double seconds);
  // Records that `stage` did not run and why ("the scene disables it", "needs patches", ...).
  void stageSkipped(const std::string& stage, const std::string& reason);
  // Whether the stage's outcome is recorded.
  bool recorded(const std::string& stage) const { return document_.at("stages").contains(stage); }

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

}  // namespace egg::pipeline
