#include "pipeline/pipeline.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/timing.hpp"
#include "pipeline/acceptance.hpp"
#include "pipeline/grid_stage.hpp"
#include "pipeline/infill_stage.hpp"
#include "pipeline/model_stage.hpp"
#include "pipeline/report_html.hpp"
#include "pipeline/run_folder.hpp"
#include "pipeline/stages.hpp"

#include <fmt/core.h>

#include <optional>

namespace egg::pipeline {
namespace {

// The stage's outcome when it does not run: switched off by the scene, needed by no requested
// output, or without what it needs (no feasible patch, no grid). Empty: it runs.
std::string skipReason(const Stage& stage, const RunState& state) {
  if (stage.disabled) {
    if (std::string why = stage.disabled(state.scene); !why.empty()) return why;
  }
  if (!stageNeeded(stage.id, state.scene.outputs))
    return "no requested output needs it (outputs: " + nlohmann::json(state.scene.outputs).dump() +
           ")";
  return stage.skipReason ? stage.skipReason(state) : std::string();
}

// The run folder's files that no stage writes itself: each patch's files, the plan, the report.
void writeOutputs(RunState& state) {
  const Scene& scene = state.scene;
  state.progress("writing", 0.9);
  // model.3dm's writer (a separate process) starts first and runs beside the files below.
  std::optional<ModelOutputs> model;
  if (scene.wants("model") && solvedCount(state.patches) > 0) model.emplace(state);
  if (scene.wants("previews") || scene.wants("report"))
    for (const auto& p : state.patches)
      writePatchFiles(p, state.staging / fmt::format("patch_{:03d}", p.id), scene);
  if (scene.wants("report")) writeInfillFiles(state, state.staging);
  if (scene.wants("plan")) {
    state.progress("plan", 0.95);
    writePatchesJson(*state.patching, state.staging / "patches.json");
    nlohmann::json plan;
    writePlan(state, state.staging, plan);
    state.report.section("plan") = plan;
  }
  if (model) model->finish();
}

}  // namespace

void checkOutputsCanBeProduced(const Scene& scene) {
  const std::string origin = scene.path.string();
  for (const char* output : {"cut_files", "stickers", "supports"})
    if (scene.wants(output) && !scene.fabrication.enabled)
      throw InvalidInput(fmt::format(
          "{}: outputs: \"{}\" needs the fabrication stage, but fabrication.enabled is false",
          origin, output));
}

PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options) {
  const Stopwatch total;
  const auto progress = [&](const std::string& stage, double fraction) {
    if (options.progress) options.progress(stage, fraction);
  };
  PipelineResult result;
  if (scene.outputs.empty()) {
    RunReport report(sceneToJson(scene));
    const std::string nothing = "no requested output needs it (outputs: [])";
    for (StageId stage : allStages()) report.stageSkipped(toString(stage), nothing);
    result.seconds = total.seconds();
    result.report = report.finish(result.seconds);
    result.nothingRequested = true;
    return result;
  }

  // A requested output that nothing can produce is bad input, found before anything is written.
  checkOutputsCanBeProduced(scene);
  // Files go to a staging folder that replaces the run folder only when the run completes; an
  // exception on the way (bad input included) removes it, so nothing half-written is left. It is
  // made first so that an unusable --out fails before minutes of work.
  StagedDirectory out(options.outDir);
  RunState state(scene, out.staging(), progress);
  for (const Stage& stage : stageTable()) {
    const char* name = toString(stage.id);
    // A stage without work of its own was recorded by the one that did it (patching: design).
    const std::string why = stage.run ? skipReason(stage, state) : std::string();
    if (!why.empty()) {
      state.report.stageSkipped(name, why);
    } else if (stage.run) {
      state.progress(name, stage.progress);
      const Stopwatch watch;
      stage.run(state);
      if (!state.report.recorded(name)) state.report.stageRan(name, watch.seconds());
    }
    if (stage.report) stage.report(state);
  }
  writeOutputs(state);

  result.seconds = total.seconds();
  result.report = state.report.finish(result.seconds);
  // The verdict: the finished figures against the scene's acceptance limits.
  const Verdict verdict = judgeRun(result.report, scene.acceptance);
  result.report["acceptance"] = verdictJson(verdict);
  for (const std::string& f : verdict.failures()) state.failures.push_back(f);
  result.failures = std::move(state.failures);
  if (!result.failures.empty()) result.report["failures"] = result.failures;
  if (scene.wants("report")) {
    // The same, for a person, with PNG previews of its figures named in report.json.
    std::vector<std::string> previewProblems;
    result.report["outputs"]["previews"] =
        writeReportHtml(out.staging(), result.report, &previewProblems);
    for (const std::string& p : previewProblems) result.report["warnings"].push_back(p);
    writeFileAtomically(out.staging() / "report.json", result.report.dump(2) + "\n");
  }
  out.commit();
  result.outDir = std::filesystem::absolute(options.outDir);
  progress("done", 1.0);
  return result;
}

}  // namespace egg::pipeline
