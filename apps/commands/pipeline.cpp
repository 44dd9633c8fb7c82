#include "apps/commands/pipeline.hpp"

#include "apps/commands/surface_loading.hpp"
#include "core/errors.hpp"

#include <chrono>

namespace egg::app {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options) {
  const auto start = Clock::now();
  auto progress = [&](const std::string& stage, double fraction) {
    if (options.progress) options.progress(stage, fraction);
  };
  RunReport report(sceneToJson(scene));

  // Surface (Section 4.4.1): everything downstream measures on this mesh.
  progress("surface", 0.0);
  const auto surfaceStart = Clock::now();
  LoadedSurface surface = loadSurface(scene.surface);
  report.section("surface") = surfaceSummary(surface);
  report.stageRan("surface", secondsSince(surfaceStart));
  for (const auto& w : surface.warnings) report.warn("surface: " + w);

  // Nothing has been written so far: input errors above leave no trace. From here on, files go
  // to a staging folder that replaces the run folder only when the run completes.
  StagedDirectory out(options.out_dir);
  PipelineResult result;
  result.seconds = secondsSince(start);
  result.report = report.finish(result.seconds);
  if (scene.wants("report")) {
    writeFileAtomically(out.staging() / "report.json", result.report.dump(2) + "\n");
  }
  out.commit();
  result.out_dir = std::filesystem::absolute(options.out_dir);
  progress("done", 1.0);
  return result;
}

}  // namespace egg::app
