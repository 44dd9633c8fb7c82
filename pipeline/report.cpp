#include "pipeline/report.hpp"

#include "pipeline/stages.hpp"

namespace egg::pipeline {

using nlohmann::json;

RunReport::RunReport(json scene) {
  document_["scene"] = std::move(scene);
  document_["units"] = {{"length", "m"}, {"angle", "rad"}, {"time", "s"}, {"cut_files", "mm"}};
  document_["stages"] = json::object();
  document_["warnings"] = json::array();
}

void RunReport::stageRan(const std::string& stage, double seconds) {
  document_["stages"][stage] = {{"ran", true}, {"seconds", seconds}};
}

void RunReport::stageSkipped(const std::string& stage, const std::string& reason) {
  document_["stages"][stage] = {{"ran", false}, {"seconds", 0.0}, {"skipped_reason", reason}};
}

json RunReport::finish(double totalSeconds) const {
  json out = document_;
  for (StageId id : allStages()) {
    const std::string stage = toString(id);
    if (!out["stages"].contains(stage)) {
      out["stages"][stage] = {{"ran", false},
                              {"seconds", 0.0},
                              {"skipped_reason", "the run recorded no outcome for this stage"}};
    }
  }
  // A section whose stage did not run carries the stage's verdict, so a reader of one section
  // never has to cross-reference `stages` to learn why it is empty.
  auto sectionOf = [&](const std::string& key, const std::string& stage) {
    if (!out.contains(key) || out[key].is_null()) {
      const json& s = out["stages"][stage];
      out[key] = {{"ran", false}, {"skipped_reason", s.value("skipped_reason", "did not run")}};
    }
  };
  if (!out.contains("patches") || out["patches"].is_null()) out["patches"] = json::array();
  sectionOf("surface", "surface");
  sectionOf("coverage", "patching");
  sectionOf("propagation", "propagation");
  sectionOf("simulation", "simulation");
  sectionOf("fabrication", "fabrication");
  out["timings"] = {{"total_s", totalSeconds}};
  json stageSeconds = json::object();
  for (StageId id : allStages())
    stageSeconds[std::string(toString(id)) + "_s"] = out["stages"][toString(id)]["seconds"];
  out["timings"]["stages"] = stageSeconds;
  return out;
}

}  // namespace egg::pipeline
