#pragma once
// The stage table of `egg run` (docs/architecture.md "Stages"): runPipeline loops over it in
// order. A row says what the stage needs, when it does not run and why, and what it does; a new
// stage or output is one file and one row here (and one in outputTable()).
#include "pipeline/run_state.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace egg::pipeline {

enum class StageId {
  Surface,
  Patching,
  Design,
  Propagation,
  Grid,
  Simulation,
  Fabrication,
  Verification,
  Deployment
};
// The key of the stage in report.json "stages" ("surface", ..., "fabrication").
const char* toString(StageId stage);
// Every stage in data-flow order (what report.json's "stages" lists).
const std::vector<StageId>& allStages();

struct Stage {
  StageId id;
  std::vector<StageId> needs;  // stages whose results it reads (they run first)
  double progress = 0.0;       // where the progress line stands when it starts, 0..1
  // Why the scene switches the stage off (empty: it does not), asked first.
  std::string (*disabled)(const Scene&) = nullptr;
  // Why the stage does not run given what ran before (empty: it runs). Only asked of a stage
  // some requested output needs; the others are skipped with "no requested output needs it".
  std::string (*skipReason)(const RunState&) = nullptr;
  // The stage's work: fills the state and report.json's section. Its wall time is recorded
  // unless it records its own outcome. No function: another stage does the work and records it
  // (Workflow 1 designs every patch while it splits, so the patching stage records "design").
  void (*run)(RunState&) = nullptr;
  // What the stage puts in report.json whether it ran or not (the grid stage: every patch's entry
  // and failure, traced or only designed). Called right after it, before the next stage.
  void (*report)(RunState&) = nullptr;
};

// An output the scene may ask for, and the stages it needs (their needs follow).
struct Output {
  std::string_view name;  // scene "outputs" entry
  std::vector<StageId> needs;
  std::string_view files;  // what it writes, for the scene reference
};

const std::vector<Stage>& stageTable();
const std::vector<Output>& outputTable();

// Whether an output the scene asks for needs `stage`, directly or through other stages' needs
// (docs/architecture.md: "outputs drive the graph").
bool stageNeeded(StageId stage, const std::vector<std::string>& outputs);

}  // namespace egg::pipeline
