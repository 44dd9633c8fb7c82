#include "apps/commands/pipeline.hpp"

#include "apps/commands/patch_stage.hpp"
#include "apps/commands/surface_loading.hpp"
#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
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
  PipelineResult result;

  // Files go to a staging folder that replaces the run folder only when the run completes; an
  // exception on the way (bad input included) removes it, so nothing half-written is left. It is
  // made first so that an unusable --out fails before minutes of work.
  StagedDirectory out(options.out_dir);

  // Surface (Section 4.4.1): everything downstream measures on this mesh.
  progress("surface", 0.0);
  const auto surfaceStart = Clock::now();
  LoadedSurface surface = [&] {
    try {
      return loadSurface(scene.surface);
    } catch (const InvalidInput& e) {
      throw InvalidInput(scene.path.string() + ": surface: " + e.what());
    }
  }();
  report.section("surface") = surfaceSummary(surface);
  report.stageRan("surface", secondsSince(surfaceStart));
  for (const auto& w : surface.warnings) report.warn("surface: " + w);

  // Patching (Section 3.4). A scene may give its layout; otherwise Workflow 1/2 would split the
  // surface.
  std::vector<SolvedPatch> patches;
  if (!scene.patching.patches.empty()) {
    report.stageSkipped("patching", "the scene gives its patch layout (patching.patches)");
    progress("egg_solve", 0.2);
    const auto eggStart = Clock::now();
    patches = solvePatches(surface.mesh, scene);
    double tracing = 0.0;
    for (const auto& p : patches) {
      if (p.egg) tracing += p.egg->seconds.tracing;
    }
    // solveEgg traces the grid (members, connections, notches, anchors) as its last part: report
    // that part as the grid stage.
    const double eggSeconds = secondsSince(eggStart);
    report.stageRan("egg_solve", eggSeconds - tracing);
    report.stageRan("grid", tracing);
  } else {
    report.stageSkipped("egg_solve", "needs patches: the scene gives no patching.patches and the automatic "
                                     "workflows are not implemented yet");
    report.stageSkipped("grid", "needs solved patches");
  }
  double coveredArea = 0.0;
  for (const auto& p : patches) {
    report.section("patches").push_back(patchEntry(p));
    if (p.egg) coveredArea += p.egg->patch.area;
    if (!p.egg) result.failures.push_back(fmt::format("patch {}: {}", p.id, p.failure));
  }
  if (!patches.empty()) {
    const double area = surfaceArea(surface.mesh);
    report.section("coverage") = {{"covered_area_m2", coveredArea}, {"fraction", area > 0 ? coveredArea / area : 0.0}};
  }
  const int solved = static_cast<int>(std::count_if(patches.begin(), patches.end(), [](const auto& p) { return p.egg.has_value(); }));
  if (solved == 1 && patches.size() == 1) {
    report.stageSkipped("propagation", "one patch: no boundary to continue members across");
  }

  // Simulation (Section 2.5): only when asked for and there is a grid to deploy.
  if (!scene.simulation.enabled) {
    report.stageSkipped("simulation", "the scene disables it (simulation.enabled = false)");
  } else if (solved == 0) {
    report.stageSkipped("simulation", "no solved patch grid to deploy");
  } else {
    progress("simulation", 0.6);
    const auto simStart = Clock::now();
    simulatePatches(patches, surface.mesh, scene);
    report.stageRan("simulation", secondsSince(simStart));
    report.section("simulation") = simulationSection(patches, scene);
    // A deployment that did not reach equilibrium is a failure of the run (exit 1), whose report
    // still carries every figure.
    if (!report.section("simulation")["converged"].get<bool>()) {
      result.failures.push_back("simulation: " + report.section("simulation").value("reason", std::string("did not converge")));
    }
  }

  progress("writing", 0.9);
  for (const auto& p : patches) writePatchFiles(p, out.staging() / fmt::format("patch_{:03d}", p.id), scene);
  result.seconds = secondsSince(start);
  result.report = report.finish(result.seconds);
  if (!result.failures.empty()) result.report["failures"] = result.failures;
  if (scene.wants("report")) {
    writeFileAtomically(out.staging() / "report.json", result.report.dump(2) + "\n");
  }
  out.commit();
  result.out_dir = std::filesystem::absolute(options.out_dir);
  progress("done", 1.0);
  return result;
}

}  // namespace egg::app
