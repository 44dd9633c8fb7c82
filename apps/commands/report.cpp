#include "apps/commands/report.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <fstream>
#include <random>
#include <system_error>
#include <unistd.h>

namespace egg::app {

using nlohmann::json;

const std::vector<std::string>& pipelineStages() {
  static const std::vector<std::string> stages{"surface", "patching",   "design",     "propagation",
                                               "grid",    "simulation", "fabrication"};
  return stages;
}

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
  for (const auto& stage : pipelineStages()) {
    if (!out["stages"].contains(stage)) {
      out["stages"][stage] = {{"ran", false}, {"seconds", 0.0}, {"skipped_reason", "not implemented"}};
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
  for (const auto& stage : pipelineStages()) stageSeconds[stage + "_s"] = out["stages"][stage]["seconds"];
  out["timings"]["stages"] = stageSeconds;
  return out;
}

StagedDirectory::StagedDirectory(std::filesystem::path target) : target_(std::move(target)) {
  namespace fs = std::filesystem;
  if (target_.empty()) throw InvalidInput("output folder: empty path");
  target_ = fs::absolute(target_).lexically_normal();
  if (target_.filename().empty()) target_ = target_.parent_path();
  const fs::path parent = target_.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw WriteError(parent.string() + ": cannot create folder: " + ec.message());
  const bool exists = fs::exists(target_, ec);
  if (ec) throw WriteError(target_.string() + ": cannot inspect the output folder: " + ec.message());
  if (exists) {
    if (!fs::is_directory(target_, ec)) throw InvalidInput(target_.string() + ": exists and is not a folder");
    const bool empty = fs::is_empty(target_, ec);
    if (ec) throw WriteError(target_.string() + ": cannot read the output folder: " + ec.message());
    if (!empty && !fs::exists(target_ / kRunMarker, ec)) {
      throw InvalidInput(target_.string() + ": exists and is not an eggshell run folder (no " + kRunMarker +
                         "); refusing to replace it — choose another --out");
    }
  }
  staging_ = parent / ("." + target_.filename().string() + ".staging-" + temporarySuffix());
  fs::create_directory(staging_, ec);
  if (ec) throw WriteError(staging_.string() + ": cannot create staging folder: " + ec.message());
  try {
    writeFileAtomically(staging_ / kRunMarker, "eggshell run folder: replaced whole by the next egg run\n");
  } catch (...) {
    // The destructor does not run for a throwing constructor: remove the staging folder here.
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
    throw;
  }
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(staging_, ignored);
  }
}

void StagedDirectory::commit() {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path previous;
  const bool exists = fs::exists(target_, ec);
  if (ec) throw WriteError(target_.string() + ": cannot inspect the output folder: " + ec.message());
  if (exists) {
    previous = target_.parent_path() / ("." + target_.filename().string() + ".previous-" + temporarySuffix());
    fs::rename(target_, previous, ec);
    if (ec) throw WriteError(target_.string() + ": cannot replace the earlier results: " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::string message = target_.string() + ": cannot move the results into place: " + ec.message();
    if (!previous.empty()) {
      std::error_code restore;
      fs::rename(previous, target_, restore);  // put the old results back
      if (restore) {
        message += "; the earlier results could not be put back either (" + restore.message() + ") and are in " +
                   previous.string();
      }
    }
    throw WriteError(message);
  }
  committed_ = true;
  if (!previous.empty()) fs::remove_all(previous, ec);
}

}  // namespace egg::app
