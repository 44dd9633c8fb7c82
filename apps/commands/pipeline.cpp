#include "apps/commands/pipeline.hpp"

#include "apps/commands/cladding_plot.hpp"
#include "apps/commands/deviation_plan.hpp"
#include "apps/commands/fabrication_stage.hpp"
#include "apps/commands/joined_stage.hpp"
#include "apps/commands/patch_stage.hpp"
#include "apps/commands/patching_stage.hpp"
#include "apps/commands/report_html.hpp"
#include "apps/commands/surface_loading.hpp"
#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/io/atomic_file.hpp"
#include "core/rods/surface_distance.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>

namespace egg::app {
namespace {

// deployed.svg: the joined structure when it ran, else every patch's own deployment (Section 3.5.2).
void writeDeployedPlan(const rods::SimulationRun* joined, const std::vector<SolvedPatch>& patches, const TriMesh& surface,
                       const std::filesystem::path& file) {
  std::vector<const rods::SimulationRun*> runs;
  if (joined) runs.push_back(joined);
  else
    for (const auto& p : patches)
      if (p.simulation) runs.push_back(&p.simulation->deployed);
  if (runs.empty()) return;
  const rods::SurfaceDistance distance(surface);
  std::vector<DeployedRod> rods;
  for (const rods::SimulationRun* run : runs)
    for (const auto& points : run->contactPoints) {
      DeployedRod rod;
      rod.points = points;
      for (const auto& p : points) rod.distance_m.push_back(distance.distance(p));
      rods.push_back(std::move(rod));
    }
  writeFileAtomically(file, deployedPlanSvg(rods, joined ? "Deployed grid (joined structure), seen from above, coloured by the distance to the design surface"
                                                         : "Deployed grid (each patch on its own supports), seen from above, coloured by the distance to the design surface"));
}

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The boundary lamellas two patches share (Section 3.5.3: "adjacent grids can be simply
// connected along their common lamellae"): a side shared whole by both patches is one lamella that
// carries the holes of both grids. Side k of a patch is its boundary member: side 0 = u member 0
// (running c0 -> c1, with the side), side 2 = the last u member (c3 -> c2, against it), side 3 = v
// member 0 (c0 -> c3, against it), side 1 = the last v member (c1 -> c2, with it).
std::vector<fabrication::SharedBoundary> sharedLamellae(const PatchingRun& run, const std::vector<SolvedPatch>& patches) {
  std::vector<fabrication::SharedBoundary> out;
  const auto member = [&](const patching::BoundaryUse& use, Family& family, int& index, bool& againstSegment) {
    const EggGrid& grid = patches[use.patch].egg->grid;
    family = use.side % 2 == 0 ? Family::U : Family::V;
    const int count = static_cast<int>(family == Family::U ? grid.u.size() : grid.v.size());
    index = (use.side == 0 || use.side == 3) ? 0 : count - 1;
    const bool againstSide = use.side == 2 || use.side == 3;
    againstSegment = againstSide != use.reversed;
  };
  for (const auto& b : run.graph.boundaries) {
    if (b.kind != "shared" || b.uses.size() != 2) continue;
    const auto &a = b.uses[0], &c = b.uses[1];
    if (!patches[a.patch].egg || !patches[c.patch].egg) continue;
    fabrication::SharedBoundary shared;
    bool againstA = false, againstB = false;
    shared.patchA = a.patch, shared.patchB = c.patch;
    member(a, shared.familyA, shared.indexA, againstA);
    member(c, shared.familyB, shared.indexB, againstB);
    shared.reversed = againstA != againstB;
    out.push_back(shared);
  }
  return out;
}

}  // namespace

StageNeeds stageNeeds(const Scene& scene) {
  StageNeeds needs;
  const bool report = scene.wants("report"), previews = scene.wants("previews"), plan = scene.wants("plan");
  const bool fabrication = scene.wants("cut_files") || scene.wants("stickers") || scene.wants("supports");
  needs.grid = report || previews || fabrication;
  needs.patching = needs.grid || plan;
  needs.surface = needs.patching;
  needs.simulation = scene.simulation.enabled && (report || previews);
  needs.fabrication = fabrication;
  return needs;
}

void checkOutputsCanBeProduced(const Scene& scene) {
  const std::string origin = scene.path.string();
  for (const char* output : {"cut_files", "stickers", "supports"})
    if (scene.wants(output)) {
      if (!scene.fabrication.enabled)
        throw InvalidInput(fmt::format("{}: outputs: \"{}\" needs the fabrication stage, but fabrication.enabled is false", origin, output));
    }
}

PipelineResult runPipeline(const Scene& scene, const PipelineOptions& options) {
  const auto start = Clock::now();
  auto progress = [&](const std::string& stage, double fraction) {
    if (options.progress) options.progress(stage, fraction);
  };
  RunReport report(sceneToJson(scene));
  PipelineResult result;
  const StageNeeds needs = stageNeeds(scene);
  const std::string nothing = "no requested output needs it (outputs: " + nlohmann::json(scene.outputs).dump() + ")";
  if (scene.outputs.empty()) {
    for (const auto& stage : pipelineStages()) report.stageSkipped(stage, nothing);
    result.seconds = secondsSince(start);
    result.report = report.finish(result.seconds);
    result.nothingRequested = true;
    return result;
  }

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
  // A requested output that nothing can produce is bad input, found before any heavy work (and
  // the staging folder goes with the exception: nothing is written).
  checkOutputsCanBeProduced(scene);
  // Patching and design (Sections 3.3, 3.4): the layout, split by Workflow 1 if asked, and every
  // patch's design on it, in parallel.
  progress("patching", 0.1);
  const auto patchingStart = Clock::now();
  const geodesic::DistanceSolver surfaceSolver(surface.mesh);
  PatchingRun patching = runPatching(surface.mesh, surfaceSolver, scene);
  const double solverSeconds = secondsSince(patchingStart) - patching.layoutSeconds - patching.designSeconds;
  report.stageRan("patching", patching.layoutSeconds + solverSeconds);
  report.stageRan("design", patching.designSeconds);
  addPatchingReport(patching, report.document());

  std::vector<SolvedPatch> patches;
  std::optional<propagation::LayoutPropagation> members;  // propagated members (several patches)
  if (needs.grid) {
    const int designed = static_cast<int>(std::count_if(patching.layout.patches.begin(), patching.layout.patches.end(),
                                                        [](const auto& p) { return p.feasible(); }));
    // Propagation (Problem 3.3, Section 3.4.4): members continued across the shared sides.
    if (patching.layout.patches.size() == 1) {
      report.stageSkipped("propagation", "one patch: no boundary to continue members across");
    } else if (designed == 0) {
      report.stageSkipped("propagation", "no feasible patch design");
    } else {
      progress("propagation", 0.25);
      members = propagateMembers(patching, scene);
      report.stageRan("propagation", members->seconds);
    }
    progress("grid", 0.3);
    const auto gridStart = Clock::now();
    propagation::LayoutTracing tracing;
    patches = tracePatches(patching, scene, members ? &*members : nullptr, &tracing);
    if (members) report.section("propagation") = propagationSection(*members, tracing);
    if (designed > 0) report.stageRan("grid", secondsSince(gridStart));
    else report.stageSkipped("grid", "no feasible patch design");
  } else {
    report.stageSkipped("propagation", nothing);
    report.stageSkipped("grid", nothing);
    for (size_t i = 0; i < patching.layout.patches.size(); ++i) {
      SolvedPatch p;
      p.id = static_cast<int>(i);
      p.cornerIds = patching.layout.layout.patches[i];
      for (int k = 0; k < 4; ++k) p.corners[k] = patching.layout.layout.corners[p.cornerIds[k]];
      p.failure = patching.layout.patches[i].failure;
      patches.push_back(std::move(p));
    }
  }
  for (const auto& p : patches) {
    nlohmann::json entry = patchEntry(p);
    const auto& designed = patching.layout.patches[p.id];
    if (!p.egg && designed.design && designed.feasible()) {
      // Designed but not traced (no output needs the grid): the design's own figures.
      entry["feasible"] = true;
      entry["eta_u"] = designed.design->uniqueness.etaU;
      entry["eta_v"] = designed.design->uniqueness.etaV;
      entry["alpha_bar_rad"] = designed.design->alphaBar.alphaBar;
      entry["area_m2"] = designed.design->patch.area;
    }
    if (p.egg && designed.design) {
      // F_u, F_v with their members and the slope band they were kept in (Sections 2.4.3, 2.4.4).
      const EggResult& egg = *p.egg;
      const AlphaBarOptions& bounds = designed.design->options.alphaBar;
      const auto sides = [&](Family f) {
        return std::array<double, 2>{familySideLength(egg.patch, f, false), familySideLength(egg.patch, f, true)};
      };
      entry["cladding"] = claddingEntry(egg.alphaBar.claddingU, egg.alphaBar.claddingV, egg.membersU, egg.membersV, sides(Family::U),
                                        sides(Family::V), bounds.slopeMin, bounds.slopeMax, bounds.cladding.infiniteSlopeFactor);
    }
    report.section("patches").push_back(entry);
    if (!designed.feasible() || (needs.grid && !p.egg))
      result.failures.push_back(fmt::format("patch {}: {}", p.id, p.failure.empty() ? designed.failure : p.failure));
  }
  const int solved = static_cast<int>(std::count_if(patches.begin(), patches.end(), [](const auto& p) { return p.egg.has_value(); }));

  // Simulation (Section 2.5): only when asked for and there is a grid to deploy.
  if (!scene.simulation.enabled) {
    report.stageSkipped("simulation", "the scene disables it (simulation.enabled = false)");
  } else if (!needs.simulation) {
    report.stageSkipped("simulation", nothing);
  } else if (solved == 0) {
    report.stageSkipped("simulation", "no solved patch grid to deploy");
  } else {
    progress("simulation", 0.6);
    const auto simStart = Clock::now();
    const bool boundarySupports = scene.simulation.supports == "design_boundary" ||
                                  (scene.simulation.supports == "auto" && patching.layout.patches.size() > 1);
    if (boundarySupports) report.document()["supports"] = {{"design_boundary_anchors", supportDesignBoundary(patches, patching.graph)}};
    // Patch by patch, each patch is held along all its sides, as the thesis simulated them (Fig.
    // 3.17); the joined run holds the design boundary only and its bolts do the rest.
    std::mutex progressMutex;  // patches finish on TBB's threads
    simulatePatches(patches, surface.mesh, scene, boundarySupports && scene.simulation.hold_shared_sides, [&](int done, int total) {
      const std::lock_guard<std::mutex> lock(progressMutex);
      progress(fmt::format("simulation: patch {} of {}", done, total), 0.6 + 0.12 * done / std::max(total, 1));
    });
    if (scene.simulation.join_patches && members.has_value()) progress("simulation: joined", 0.72);
    report.section("simulation") = simulationSection(patches, scene);
    report.section("simulation")["seconds"] = secondsSince(simStart);  // patch by patch (wall, patches in parallel)
    const std::optional<rods::SimulationRun> joined = addJoinedSimulation(
        patching, patches, surface.mesh, scene, members.has_value(), solved, report.section("simulation"),
        boundarySupports && scene.simulation.hold_shared_sides);
    if (scene.wants("report")) writeDeployedPlan(joined ? &*joined : nullptr, patches, surface.mesh, out.staging() / "deployed.svg");
    report.stageRan("simulation", secondsSince(simStart));  // both runs, patch by patch and joined
    // A deployment that did not reach equilibrium is a failure of the run (exit 1), whose report
    // still carries every figure.
    if (!report.section("simulation")["converged"].get<bool>()) {
      result.failures.push_back("simulation: " + report.section("simulation").value("reason", std::string("did not converge")));
    }
    const auto& joinedReport = report.section("simulation")["joined"];
    if (joinedReport["ran"].get<bool>() && !joinedReport["converged"].get<bool>())
      result.failures.push_back("joined simulation: " +
                                joinedReport.value("failure", joinedReport.value("reason", std::string("did not converge"))));
  }
  // Fabrication (Section 3.5): cut files, stickers, supports and the BOM of the traced grids, with
  // stresses from the deployed centrelines where the simulation ran.
  if (!scene.fabrication.enabled) {
    report.stageSkipped("fabrication", "the scene disables it (fabrication.enabled = false)");
  } else if (!needs.fabrication || !fabricationWanted(scene)) {
    report.stageSkipped("fabrication", nothing);
  } else if (solved == 0) {
    report.stageSkipped("fabrication", "no solved patch grid to cut");
  } else {
    progress("fabrication", 0.8);
    const auto fabStart = Clock::now();
    std::vector<fabrication::FabricationPatch> grids;
    for (const auto& p : patches) {
      if (!p.egg) continue;
      fabrication::FabricationPatch entry{p.id, &p.egg->grid, std::nullopt};
      if (p.simulation) entry.deployedCentrelines = p.simulation->deployed.centrelines;
      entry.freeSides = freeSidesOf(patching.graph, p.id);  // supports only on the design boundary
      grids.push_back(std::move(entry));
    }
    // The grid decides whether its parts can be cut (a part wider than the sheet; a lamella whose
    // slots leave no place for a splice is left out and listed, fab.failures): a failure of this
    // run with its report, not bad input (the options themselves were checked when the scene was read).
    try {
      FabricationStageResult fab = runFabricationStage(scene, grids, out.staging(), sharedLamellae(patching, patches));
      report.stageRan("fabrication", secondsSince(fabStart));
      report.section("fabrication") = fab.report;
      result.failures.insert(result.failures.end(), fab.failures.begin(), fab.failures.end());
    } catch (const InvalidInput& e) {
      report.stageSkipped("fabrication", std::string("the grid cannot be cut with these settings: ") + e.what());
      result.failures.push_back(std::string("fabrication: ") + e.what());
    }
  }

  progress("writing", 0.9);
  if (scene.wants("previews") || scene.wants("report"))
    for (const auto& p : patches) writePatchFiles(p, out.staging() / fmt::format("patch_{:03d}", p.id), scene);
  if (scene.wants("plan")) {
    progress("plan", 0.95);
    writePatchesJson(patching, out.staging() / "patches.json");
    nlohmann::json plan;
    writePlan(patching, surface.mesh, surfaceSolver, scene, out.staging() / "plan.svg", plan);
    report.section("plan") = plan;
  }
  result.seconds = secondsSince(start);
  result.report = report.finish(result.seconds);
  if (!result.failures.empty()) result.report["failures"] = result.failures;
  if (scene.wants("report")) {
    // The same, for a person (issue 18), with PNG previews of its figures named in report.json.
    result.report["outputs"]["previews"] = writeReportHtml(out.staging(), result.report);
    writeFileAtomically(out.staging() / "report.json", result.report.dump(2) + "\n");
  }
  out.commit();
  result.out_dir = std::filesystem::absolute(options.out_dir);
  progress("done", 1.0);
  return result;
}

}  // namespace egg::app
