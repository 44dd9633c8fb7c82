#include "pipeline/simulation_stage.hpp"

#include "pipeline/deployed_view.hpp"
#include "pipeline/elevations.hpp"

#include "assembly/boundary_members.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "core/rods/surface_distance.hpp"
#include "core/timing.hpp"
#include "pipeline/deviation_plan.hpp"
#include "pipeline/error_time_plot.hpp"
#include "pipeline/infill_stage.hpp"
#include "pipeline/joined_simulation.hpp"

#include <fmt/core.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <vector>

namespace egg::pipeline {

using nlohmann::json;

rods::SimulationOptions rodsOptions(const Scene& scene) {
  rods::SimulationOptions options = scene.simulation.rods;
  options.historyEvery = kErrorHistoryEvery;
  return options;
}

assembly::GridToRodsOptions gridToRodsOptions(const Scene& scene) {
  assembly::GridToRodsOptions convert;
  convert.section.widthM = scene.lamella.widthM;
  convert.section.thicknessM = scene.lamella.thicknessM;
  convert.material = materialByName(scene.lamella.material);
  convert.notches = true;
  return convert;
}

void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene,
                     bool holdSharedSides, const std::function<void(int, int)>& patchDone) {
  // Notches on: the simulation switches them off itself for the comparison run.
  const assembly::GridToRodsOptions convert = gridToRodsOptions(scene);
  // Patches in parallel, each simulation on one thread when there are several (the rods code's
  // own threads would only compete with TBB's); the simulation is bit-identical for any count.
  const int solved = solvedCount(patches);
  std::atomic<int> done{0};
  auto simulateOne = [&](size_t i) {
    auto& patch = patches[i];
    // One patch's failure must not discard the others' results: record it and go on.
    try {
      rods::RodNetwork network = assembly::rodNetworkFromGrid(patch.egg->grid, convert);
      if (holdSharedSides) network = assembly::holdEverySide(std::move(network), patch.egg->grid);
      rods::SimulationOptions options = rodsOptions(scene);
      // RMS1 (plain holes) beside RMS2 (notches), Section 2.6.2: a second full run per patch,
      // only when the scene asks for the comparison (and only meaningful with notches).
      options.compareWithoutNotches = options.model.notches && options.compareWithoutNotches;
      // NRMSE of Section 3.5.2 divides by a scale: the patch's bounding-box diagonal, so that the
      // figure compares patches and scenes of any size.
      options.scaleFactor = boundingBox(patch.egg->patch.mesh).size().norm();
      if (solved > 1) options.solver.threads = 1;
      // Where the exact Hessian is indefinite, project every stencil as the joined run does
      // (rod_solver.hpp): the full-stiffness stage after the continuation starts next to the
      // weightless equilibrium, and its indefiniteness is transient (bolts pulled into place,
      // edges compressed on the way). Measured in docs/measurements.md (issue 36).
      options.solver.projectAllWhenIndefinite = true;
      patch.simulation = rods::simulateGrid(network, surface, options);
      patch.network = std::move(network);
    } catch (const Error& e) {
      patch.simulationFailure = e.what();
    }
    if (patchDone) patchDone(++done, solved);
  };
  // Largest grids first (by bolts), each worker taking the next patch when it is free (longest
  // first): a split of the index range fixes which thread gets which patches, whatever their
  // sizes, and the last patch can then run alone on one core while the other waits.
  std::vector<size_t> order;
  for (size_t i = 0; i < patches.size(); ++i)
    if (patches[i].egg) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return patches[a].egg->grid.connections.size() > patches[b].egg->grid.connections.size();
  });
  std::atomic<size_t> next{0};
  const int workers = std::max(
      1, std::min(static_cast<int>(order.size()), tbb::this_task_arena::max_concurrency()));
  tbb::parallel_for(0, workers, [&](int) {
    for (size_t k = next++; k < order.size(); k = next++) simulateOne(order[k]);
  });
}

json phasesJson(const rods::SolverPhases& phases) {
  return {{"derivatives", phases.derivativesS},
          {"symbolic_analysis", phases.analysisS},
          {"factorisation", phases.factorS},
          {"line_search", phases.lineSearchS}};
}

json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene) {
  const rods::SimulationOptions& options = scene.simulation.rods;
  // Errors over all patches pooled by point count, so a big patch weighs as much as its points.
  double sumSquares = 0.0, sumSquaresPlain = 0.0, maxError = 0.0, nrmseWorst = 0.0;
  long points = 0, pointsPlain = 0;
  int iterations = 0;
  bool converged = true;
  std::string reason;
  json perPatch = json::array();
  for (const auto& patch : patches) {
    if (!patch.simulationFailure.empty()) {
      converged = false;
      if (reason.empty()) reason = fmt::format("patch {}: {}", patch.id, patch.simulationFailure);
      perPatch.push_back(
          {{"patch", patch.id}, {"converged", false}, {"failure", patch.simulationFailure}});
      continue;
    }
    if (!patch.simulation) continue;
    const auto& sim = *patch.simulation;
    converged = converged && sim.converged;
    if (!sim.converged && reason.empty())
      reason = fmt::format("patch {}: {}", patch.id, sim.reason);
    iterations += sim.deployed.solver.iterations;
    json entry{
        {"patch", patch.id},
        {"converged", sim.converged},
        {"iterations", sim.deployed.solver.iterations},
        {"status", rods::toString(sim.deployed.solver.status)},
        {"energy_j", sim.deployed.solver.energy},
        {"gradient_norm_n_nm",
         sim.deployed.solver.gradientNorm},              // over positions (N) and twists (N m)
        {"decrement_j", sim.deployed.solver.decrement},  // last Newton decrement g^T H^-1 g
        {"unknowns", sim.deployed.unknowns},
        {"factorisations", sim.deployed.solver.factorisations},  // Cholesky, shift trials included
        {"energy_evaluations", sim.deployed.solver.energyEvaluations},  // line-search trials
        {"seconds", sim.seconds},
        {"phases_s", phasesJson(sim.deployed.solver.phases)},
        {"symbolic_analyses", sim.deployed.solver.phases.analyses},
        {"derivative_passes", sim.deployed.solver.phases.derivativePasses}};
    // Under self-weight, how far the grid sagged from its weightless equilibrium (a "collapsed"
    // status means it fell through: Section 3.5.2, Fig. 3.11).
    if (scene.simulation.rods.model.gravity) entry["max_sag_m"] = sim.deployed.maxSagM;
    if (sim.deployed.deviation) {
      const auto& d = *sim.deployed.deviation;
      sumSquares += d.rmseM * d.rmseM * d.points;
      points += d.points;
      maxError = std::max(maxError, d.maxM);
      nrmseWorst = std::max(nrmseWorst, d.nrmse);
      entry.update({{"rmse_m", d.rmseM}, {"max_error_m", d.maxM}, {"nrmse", d.nrmse}});
    }
    // Error against run time (issue 18): the deployed run's deviation every few iterations.
    entry["history"] = historyJson(sim.deployed.history);
    entry["history_measuring_s"] = sim.deployed.historySeconds;
    if (sim.withoutNotches && sim.withoutNotches->deviation) {
      const auto& d = *sim.withoutNotches->deviation;
      sumSquaresPlain += d.rmseM * d.rmseM * d.points;
      pointsPlain += d.points;
      entry["rmse_no_notches_m"] = d.rmseM;
    }
    perPatch.push_back(entry);
  }
  json section{{"ran", true},
               {"converged", converged},
               {"rmse_m", points ? json(std::sqrt(sumSquares / points)) : json(nullptr)},
               {"max_error_m", points ? json(maxError) : json(nullptr)},
               {"nrmse", points ? json(nrmseWorst) : json(nullptr)},
               {"nrmse_normalised_by", "patch bounding-box diagonal (worst patch)"},
               {"rmse_no_notches_m",
                pointsPlain ? json(std::sqrt(sumSquaresPlain / pointsPlain)) : json(nullptr)},
               {"gravity", options.model.gravity},
               {"bolts_fastened_under_load", options.model.gravity && options.fastenBoltsUnderLoad},
               {"notches", options.model.notches},
               {"friction_mu", options.model.frictionMu},
               {"iterations", iterations},
               {"patches", perPatch}};
  if (!converged) section["reason"] = reason;
  return section;
}

namespace {

// deployed.svg and deployed.json: the joined structure when it ran, else every patch's own
// deployment (3.5.2).
void writeDeployedFigures(const rods::SimulationRun* joined, const rods::JoinedNetwork* network,
                          const std::vector<SolvedPatch>& patches,
                          const JoinedGeneralised& generalised, const TriMesh& surface,
                          const std::filesystem::path& folder) {
  // (run, layout patch id, first rod of the patch in the run), in rod order.
  struct Part {
    const rods::SimulationRun* run;
    int patch;
    int firstRod;
  };
  std::vector<Part> parts;
  if (joined) {
    // The joined network holds the patches with a grid, in layout order (joined_simulation.cpp).
    size_t k = 0;
    for (const auto& p : patches)
      if (p.egg) {
        parts.push_back(
            {joined, p.id, network && k < network->firstRod.size() ? network->firstRod[k] : -1});
        ++k;
      }
    // Then the generalised patches, when the joined run took them (its network says so).
    if (network && generalised.patches &&
        network->firstRod.size() == k + generalised.patches->size())
      for (const auto& g : *generalised.patches)
        parts.push_back({joined, g.patchId, network->firstRod[k++]});
  } else {
    for (const auto& p : patches)
      if (p.simulation) parts.push_back({&p.simulation->deployed, p.id, 0});
    if (generalised.patches)
      for (const auto& g : *generalised.patches)
        if (const auto& own = (*generalised.runs)[g.piece])
          parts.push_back({&own->deployed, g.patchId, 0});
  }
  if (parts.empty()) return;
  const rods::SurfaceDistance distance(surface);
  std::vector<DeployedRod> rods;
  const auto addRun = [&](const rods::SimulationRun& run, const std::vector<Part>& ofRun) {
    for (size_t r = 0; r < run.contactPoints.size(); ++r) {
      DeployedRod rod;
      rod.points = run.contactPoints[r];
      for (const auto& p : rod.points) rod.distanceM.push_back(distance.distance(p));
      // The last part starting at or before r owns it.
      for (const Part& part : ofRun)
        if (part.firstRod >= 0 && part.firstRod <= static_cast<int>(r))
          rod.patch = part.patch, rod.rod = static_cast<int>(r) - part.firstRod;
      rods.push_back(std::move(rod));
    }
  };
  if (joined) {
    addRun(*joined, parts);
  } else {
    for (const Part& part : parts) addRun(*part.run, {part});
  }
  const std::string caption =
      joined ? "Deployed grid (joined structure), coloured by the distance to the design surface"
             : "Deployed grid (each patch on its own supports), coloured by the distance to the "
               "design surface";
  writeFileAtomically(folder / "deployed.svg",
                      deployedPlanSvg(rods, caption + ", seen from above"));
  writeFileAtomically(folder / "elevations.svg",
                      elevationsSvg(surface, rods,
                                    joined ? "Elevations and sections of the deployed grid (joined "
                                             "structure) against the design surface"
                                           : "Elevations and sections of the deployed grid (each "
                                             "patch on its own supports) against the design "
                                             "surface"));
  writeFileAtomically(folder / "deployed.json",
                      deployedViewJson(rods, surface, caption).dump() + "\n");
}

}  // namespace

std::string simulationDisabled(const Scene& scene) {
  return scene.simulation.enabled ? std::string()
                                  : "the scene disables it (simulation.enabled = false)";
}

std::string simulationSkipReason(const RunState& state) {
  return solvedCount(state.patches) == 0 ? "no solved patch grid to deploy" : std::string();
}

void simulationStage(RunState& state) {
  const Scene& scene = state.scene;
  const Stopwatch watch;
  const SupportChoice supports = scene.simulation.supports;
  const bool boundarySupports =
      supports == SupportChoice::DesignBoundary ||
      (supports == SupportChoice::Auto && state.patching->layout.patches.size() > 1);
  if (boundarySupports)
    state.report.document()["supports"] = {
        {"design_boundary_anchors",
         assembly::supportDesignBoundary(state.patching->graph, editableGridsOf(state.patches))}};
  // Patch by patch, each patch is held along all its sides, as the thesis simulated them (Fig.
  // 3.17); the joined run holds the design boundary only and its bolts do the rest.
  const bool heldAllRound = boundarySupports && scene.simulation.holdSharedSides;
  std::mutex progressMutex;  // patches finish on TBB's threads
  simulatePatches(state.patches, state.surface->mesh, scene, heldAllRound,
                  [&](int done, int total) {
                    const std::lock_guard<std::mutex> lock(progressMutex);
                    state.progress(fmt::format("simulation: patch {} of {}", done, total),
                                   0.6 + 0.12 * done / std::max(total, 1));
                  });
  if (scene.simulation.joinPatches && state.members.has_value())
    state.progress("simulation: joined", 0.72);
  json& section = state.report.section("simulation");
  section = simulationSection(state.patches, scene);
  section["seconds"] = watch.seconds();  // patch by patch (wall, patches in parallel)
  simulateInfill(state);  // each generalised patch on its own first: the joined run's warm start
  state.joined = addJoinedSimulation(*state.patching, state.patches, state.surface->mesh, scene,
                                     state.members.has_value(), solvedCount(state.patches), section,
                                     heldAllRound, &state.joinedNetwork,
                                     {&state.generalised, &state.infillSimulations});
  if (scene.wants("report"))
    writeDeployedFigures(state.joined ? &*state.joined : nullptr,
                         state.joinedNetwork ? &*state.joinedNetwork : nullptr, state.patches,
                         {&state.generalised, &state.infillSimulations}, state.surface->mesh,
                         state.staging);
  // A deployment that did not reach equilibrium is a failure of the run (exit 1), whose report
  // still carries every figure.
  if (!section["converged"].get<bool>())
    state.failures.push_back("simulation: " +
                             section.value("reason", std::string("did not converge")));
  const auto& joinedReport = section["joined"];
  if (joinedReport["ran"].get<bool>() && !joinedReport["converged"].get<bool>())
    state.failures.push_back(
        "joined simulation: " +
        joinedReport.value("failure",
                           joinedReport.value("reason", std::string("did not converge"))));
}

}  // namespace egg::pipeline
