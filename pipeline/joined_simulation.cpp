#include "pipeline/joined_simulation.hpp"

#include "assembly/grid_to_rods.hpp"
#include "assembly/patch_joins.hpp"
#include "core/errors.hpp"
#include "core/timing.hpp"
#include "pipeline/error_time_plot.hpp"
#include "pipeline/simulation_stage.hpp"

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

JoinedRun simulateJoined(const PatchingRun& run, const std::vector<SolvedPatch>& patches,
                         const TriMesh& surface, const Scene& scene,
                         const JoinedGeneralised& generalised) {
  const Stopwatch watch;
  JoinedRun out;
  try {
    const std::vector<const EggGrid*> grids = gridsOf(patches);
    out.swapped = assembly::layerSwaps(run.graph, grids);
    // Coinciding ends: C0 leaves them ~1e-15 m apart; a tenth of the lamella width separates them
    // from the next member on the side by far.
    assembly::PatchJoins joins =
        assembly::patchJoins(run.graph, grids, out.swapped, 0.1 * scene.lamella.widthM);
    out.joins = std::move(joins.bolts);
    out.sidesJoined = joins.sidesJoined;
    out.sidesSkipped = joins.sidesSkipped;
    assembly::GridToRodsOptions convert = gridToRodsOptions(scene);
    // Every patch keeps a network (empty for one without a grid) so that rod indices stay per
    // patch.
    std::vector<rods::RodNetwork> networks;
    std::vector<int> solvedIndex(patches.size(), -1);
    for (size_t p = 0; p < patches.size(); ++p) {
      if (!patches[p].egg) continue;
      convert.swapLayers = out.swapped[p];
      solvedIndex[p] = static_cast<int>(networks.size());
      networks.push_back(assembly::rodNetworkFromGrid(patches[p].egg->grid, convert));
    }
    // Warm start: every patch's own equilibrium under self-weight (held along all its sides) is
    // next to the joined one, which only lets go of the shared sides' supports and bolts the
    // boundary lamellas together; from the design surface the joined solve needs the weightless
    // solve, the load steps and the stiffness continuation again (GC: 70 iterations of the
    // weightless step alone).
    out.warmStart = std::all_of(patches.begin(), patches.end(), [](const SolvedPatch& p) {
      return !p.egg || (p.simulation && p.simulation->converged);
    });
    if (generalised.patches)
      for (const auto& patch : *generalised.patches) {
        const auto& own = (*generalised.runs)[patch.piece];
        out.warmStart = out.warmStart && own && own->converged;
      }
    if (out.warmStart) {
      for (size_t p = 0; p < patches.size(); ++p) {
        if (!patches[p].egg) continue;
        rods::startFrom(networks[solvedIndex[p]], patches[p].simulation->deployed);
      }
    }
    for (auto& j : out.joins) j.patchA = solvedIndex[j.patchA], j.patchB = solvedIndex[j.patchB];
    // The generalised patches after the quads, their ends on a quad's side bolted to its
    // boundary lamella (which stays supported: a free side of the quad layout).
    std::vector<int> generalisedId;
    if (generalised.patches) {
      for (size_t g = 0; g < generalised.patches->size(); ++g) {
        const assembly::GeneralisedPatch& patch = (*generalised.patches)[g];
        const int index = static_cast<int>(networks.size());
        assembly::RingBeamJoins ring = patch.ring;  // matched when the patch was designed
        for (auto& bolt : ring.bolts) bolt.patchB = index;
        rods::RodNetwork network = patch.network;
        std::vector<char> released(network.anchors.size(), 0);
        for (int a : ring.releasedAnchors) released[a] = 1;
        network.anchors.clear();
        for (size_t a = 0; a < patch.network.anchors.size(); ++a)
          if (!released[a]) network.anchors.push_back(patch.network.anchors[a]);
        if (out.warmStart) rods::startFrom(network, (*generalised.runs)[patch.piece]->deployed);
        networks.push_back(std::move(network));
        generalisedId.push_back(patch.patchId);
        for (auto j : ring.bolts) {
          j.patchA = solvedIndex[j.patchA];
          out.joins.push_back(j);
        }
        ++out.generalisedPatches;
        out.ringBeamBolts += static_cast<int>(ring.bolts.size());
        out.ringBeamSameLayer += ring.sameLayer;
        out.ringBeamUnmatched += ring.unmatched;
        out.ringBeamMaxGapM = std::max(out.ringBeamMaxGapM, ring.maxGapM);
      }
    }
    const rods::JoinedNetwork joined = rods::joinPatches(networks, out.joins);
    const int quadNetworks = static_cast<int>(networks.size() - generalisedId.size());
    const auto layoutId = [&](int network) {
      if (network >= quadNetworks) return generalisedId[network - quadNetworks];
      return static_cast<int>(std::find(solvedIndex.begin(), solvedIndex.end(), network) -
                              solvedIndex.begin());
    };
    for (size_t k = 0; k < out.joins.size(); ++k) {  // back to patch ids for the report
      out.joins[k].patchA = layoutId(out.joins[k].patchA);
      out.joins[k].patchB = layoutId(out.joins[k].patchB);
    }
    rods::SimulationOptions options = rodsOptions(scene);
    options.compareWithoutNotches = false;  // RMS1/RMS2 stay a per-patch figure
    options.scaleFactor = boundingBox(surface).size().norm();
    // One structure, one solve: its stencils on every thread TBB may use (egg run --threads).
    options.solver.threads = std::max(1, tbb::this_task_arena::max_concurrency());
    if (out.warmStart) {
      options.gravitySteps = 0;                      // the start carries its weight already
      options.solver.stiffnessContinuation = false;  // and is no far-off guess to soften towards
      // Next to the joined equilibrium, indefinite only while the joints are pulled together:
      // projected Newton on every stencil (Great Court 31 -> 6 iterations, rod_solver.hpp).
      options.solver.projectAllWhenIndefinite = true;
    }
    out.simulation = rods::simulateGrid(joined.network, surface, options);
    out.network = joined;
  } catch (const Error& e) {
    out.failure = e.what();
  }
  out.seconds = watch.seconds();
  return out;
}

nlohmann::json joinedSection(const JoinedRun& joined) {
  nlohmann::json j{{"ran", true},
                   {"bolts", joined.joins.size()},
                   {"sides_joined", joined.sidesJoined},
                   {"sides_skipped_same_layer", joined.sidesSkipped},
                   {"patches_swapped", std::count(joined.swapped.begin(), joined.swapped.end(), 1)},
                   {"start", joined.warmStart ? "patch_by_patch_equilibria" : "design_surface"},
                   {"seconds", joined.seconds}};
  if (joined.generalisedPatches > 0)
    j["generalised_patches"] = {
        {"patches", joined.generalisedPatches},
        {"ring_beam_bolts", joined.ringBeamBolts},
        {"ring_beam_max_gap_m", joined.ringBeamMaxGapM},
        {"patch_side_ends_anchored_same_layer", joined.ringBeamSameLayer},
        {"patch_side_ends_anchored_no_lamella", joined.ringBeamUnmatched},
        {"held_by",
         "member ends on a quad patch's side are bolted to its boundary lamella where they lie in "
         "the other layer; that lamella stays supported at its connections (a free side of the "
         "quad layout); ends in its own layer, on the design boundary, a hole's rim or a cut "
         "between pieces keep their anchors"}};
  if (!joined.failure.empty()) {
    j["converged"] = false;
    j["failure"] = joined.failure;
    return j;
  }
  const auto& run = joined.simulation->deployed;
  j["converged"] = joined.simulation->converged;
  j["iterations"] = run.solver.iterations;
  j["energy_j"] = run.solver.energy;
  j["gradient_norm_n_nm"] = run.solver.gradientNorm;  // over positions (N) and twists (N m)
  j["decrement_j"] = run.solver.decrement;            // last Newton decrement g^T H^-1 g
  j["max_sag_m"] =
      run.maxSagM;  // under self-weight, from the start state (warm) or the weightless equilibrium
  j["max_sag_from"] = joined.warmStart ? "patch_by_patch_equilibria" : "weightless_equilibrium";
  j["unknowns"] = run.unknowns;
  j["factorisations"] = run.solver.factorisations;         // Cholesky, shift trials included
  j["energy_evaluations"] = run.solver.energyEvaluations;  // line-search trials
  j["phases_s"] = phasesJson(run.solver.phases);
  j["symbolic_analyses"] = run.solver.phases.analyses;
  j["derivative_passes"] = run.solver.phases.derivativePasses;
  j["status"] = rods::toString(run.solver.status);
  if (!joined.simulation->converged) j["reason"] = joined.simulation->reason;
  if (run.deviation) {
    j["rmse_m"] = run.deviation->rmseM;
    j["max_error_m"] = run.deviation->maxM;
    j["nrmse"] = run.deviation->nrmse;
    j["nrmse_normalised_by"] = "surface bounding-box diagonal";
  }
  j["history"] = historyJson(run.history);  // error against run time (issue 18)
  j["history_measuring_s"] = run.historySeconds;
  return j;
}

std::string collapsedWhileHeld(const std::vector<SolvedPatch>& patches) {
  for (const auto& p : patches) {
    if (p.simulation && p.deployedStatus() == rods::SolverStatus::Collapsed) {
      return fmt::format(
          "patch {} collapses under its own weight even held at every connection of its four "
          "sides; the joined "
          "structure holds it on less (a neighbour instead of supports along the shared sides), so "
          "it cannot stand "
          "near the design either and is not simulated",
          p.id);
    }
  }
  return {};
}

std::optional<rods::SimulationRun> addJoinedSimulation(
    const PatchingRun& run, const std::vector<SolvedPatch>& patches, const TriMesh& surface,
    const Scene& scene, bool propagated, int solved, nlohmann::json& simulation,
    bool patchesHeldAllRound, std::optional<rods::JoinedNetwork>* network,
    const JoinedGeneralised& generalised) {
  simulation["patch_by_patch"] = {{"rmse_m", simulation["rmse_m"]},
                                  {"max_error_m", simulation["max_error_m"]},
                                  {"converged", simulation["converged"]},
                                  {"iterations", simulation["iterations"]},  // summed over patches
                                  {"seconds", simulation.value("seconds", 0.0)}};
  std::string skipped;
  // Generalised patches bolt to the quads' boundary lamellas whether or not members were
  // propagated between quads (one quad in a generalised frame is a structure too).
  const int generalisedCount =
      generalised.patches ? static_cast<int>(generalised.patches->size()) : 0;
  if (!scene.simulation.joinPatches)
    skipped = "the scene does not join patches (simulation.join_patches = false)";
  else if (!propagated && generalisedCount == 0)
    skipped = "no propagated members: one patch, or no neighbours' member ends to bolt together";
  else if (solved + generalisedCount < 2 || solved == 0)
    skipped = "fewer than two solved patches (or no quad for generalised patches to bolt to)";
  else if (patchesHeldAllRound)
    skipped = collapsedWhileHeld(patches);
  if (!skipped.empty()) {
    simulation["joined"] = {{"ran", false}, {"skipped_reason", skipped}};
    return std::nullopt;
  }
  JoinedRun joined = simulateJoined(run, patches, surface, scene, generalised);
  simulation["joined"] = joinedSection(joined);
  if (!joined.simulation) return std::nullopt;
  if (network) *network = std::move(joined.network);
  return std::move(joined.simulation->deployed);
}

}  // namespace egg::pipeline
