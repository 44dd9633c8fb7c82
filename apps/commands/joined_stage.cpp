#include "apps/commands/joined_stage.hpp"

#include "apps/commands/error_time_plot.hpp"
#include "apps/commands/grid_to_rods.hpp"
#include "core/errors.hpp"
#include "core/materials/materials.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace egg::app {
namespace {

bool whole(const patching::Boundary& b) { return b.kind == "shared" && b.uses.size() == 2; }

// The boundary member along side k (Section 2.4.4: the sides are members): side 0 = u member 0,
// side 2 = the last u member, side 3 = v member 0, side 1 = the last v member.
struct SideLamella {
  Family family;
  int member;  // index in its family
  int rod;     // index in rodNetworkFromGrid's network
};
SideLamella sideLamella(const EggGrid& grid, int side) {
  const Family family = side % 2 == 0 ? Family::U : Family::V;
  const int count = static_cast<int>(family == Family::U ? grid.u.size() : grid.v.size());
  const int member = (side == 0 || side == 3) ? 0 : count - 1;
  return {family, member, family == Family::U ? member : static_cast<int>(grid.u.size()) + member};
}

int layerOf(Family family, bool swapped) { return (family == Family::U ? 0 : 1) ^ (swapped ? 1 : 0); }

}  // namespace

std::vector<char> layerSwaps(const PatchingRun& run, const std::vector<SolvedPatch>& patches) {
  // Breadth first over the shared sides: a neighbour gets the swap that puts its lamella on the
  // side in the other layer; the first choice stands when a cycle disagrees.
  std::vector<char> swapped(patches.size(), 0), seen(patches.size(), 0);
  for (size_t root = 0; root < patches.size(); ++root) {
    if (seen[root] || !patches[root].egg) continue;
    std::vector<int> queue{static_cast<int>(root)};
    seen[root] = 1;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int p = queue[q];
      for (const auto& b : run.graph.boundaries) {
        if (!whole(b)) continue;
        for (int i = 0; i < 2; ++i) {
          const auto &mine = b.uses[i], &other = b.uses[1 - i];
          if (mine.patch != p || !patches[other.patch].egg || seen[other.patch]) continue;
          const Family fa = sideLamella(patches[p].egg->grid, mine.side).family;
          const Family fb = sideLamella(patches[other.patch].egg->grid, other.side).family;
          swapped[other.patch] = layerOf(fa, swapped[p]) == layerOf(fb, false) ? 1 : 0;
          seen[other.patch] = 1;
          queue.push_back(other.patch);
        }
      }
    }
  }
  return swapped;
}

std::vector<rods::PatchJoin> patchJoins(const PatchingRun& run, const std::vector<SolvedPatch>& patches,
                                        const std::vector<char>& swapped, double tolerance, int* sidesJoined, int* sidesSkipped) {
  std::vector<rods::PatchJoin> joins;
  int joined = 0, skipped = 0;
  for (const auto& b : run.graph.boundaries) {
    if (!whole(b)) continue;
    const auto &ua = b.uses[0], &ub = b.uses[1];
    if (!patches[ua.patch].egg || !patches[ub.patch].egg) continue;
    const EggGrid& ga = patches[ua.patch].egg->grid;
    const EggGrid& gb = patches[ub.patch].egg->grid;
    const SideLamella la = sideLamella(ga, ua.side), lb = sideLamella(gb, ub.side);
    if (layerOf(la.family, swapped[ua.patch]) == layerOf(lb.family, swapped[ub.patch])) {
      ++skipped;
      continue;
    }
    // The connections along a lamella: where the other family's members end on it.
    const auto along = [](const EggGrid& g, const SideLamella& l) {
      std::vector<std::pair<Eigen::Vector3d, double>> out;  // position, s_bar along the lamella
      for (const auto& c : g.connections) {
        if (l.family == Family::U && c.memberU == l.member) out.push_back({c.spatial, c.sBarU});
        if (l.family == Family::V && c.memberV == l.member) out.push_back({c.spatial, c.sBarV});
      }
      return out;
    };
    const auto ca = along(ga, la), cb = along(gb, lb);
    const double lengthA = (la.family == Family::U ? ga.u : ga.v)[la.member].planarLength;
    const double lengthB = (lb.family == Family::U ? gb.u : gb.v)[lb.member].planarLength;
    int bolts = 0;
    for (const auto& [pa, sa] : ca) {
      const auto nearest = std::min_element(cb.begin(), cb.end(), [&](const auto& x, const auto& y) {
        return (x.first - pa).squaredNorm() < (y.first - pa).squaredNorm();
      });
      if (nearest == cb.end() || (nearest->first - pa).norm() > tolerance) continue;
      joins.push_back({ua.patch, la.rod, std::clamp(sa, 0.0, lengthA), ub.patch, lb.rod, std::clamp(nearest->second, 0.0, lengthB)});
      ++bolts;
    }
    joined += bolts > 0;
  }
  if (sidesJoined) *sidesJoined = joined;
  if (sidesSkipped) *sidesSkipped = skipped;
  return joins;
}

JoinedRun simulateJoined(const PatchingRun& run, const std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene) {
  const auto started = std::chrono::steady_clock::now();
  JoinedRun out;
  try {
    out.swapped = layerSwaps(run, patches);
    // Coinciding ends: C0 leaves them ~1e-15 m apart; a tenth of the lamella width separates them
    // from the next member on the side by far.
    out.joins = patchJoins(run, patches, out.swapped, 0.1 * scene.lamella.width_m, &out.sidesJoined, &out.sidesSkipped);
    GridToRodsOptions convert;
    convert.section.width_m = scene.lamella.width_m;
    convert.section.thickness_m = scene.lamella.thickness_m;
    convert.material = materialByName(scene.lamella.material);
    // Every patch keeps a network (empty for one without a grid) so that rod indices stay per patch.
    std::vector<rods::RodNetwork> networks;
    std::vector<int> solvedIndex(patches.size(), -1);
    for (size_t p = 0; p < patches.size(); ++p) {
      if (!patches[p].egg) continue;
      convert.swapLayers = out.swapped[p];
      solvedIndex[p] = static_cast<int>(networks.size());
      networks.push_back(rodNetworkFromGrid(patches[p].egg->grid, convert));
    }
    // Warm start: every patch's own equilibrium under self-weight (held along all its sides) is
    // next to the joined one, which only lets go of the shared sides' supports and bolts the
    // boundary lamellas together; from the design surface the joined solve needs the weightless
    // solve, the load steps and the stiffness continuation again (GC: 70 iterations of the
    // weightless step alone).
    out.warmStart = std::all_of(patches.begin(), patches.end(), [](const SolvedPatch& p) {
      return !p.egg || (p.simulation && p.simulation->converged);
    });
    if (out.warmStart) {
      for (size_t p = 0; p < patches.size(); ++p) {
        if (!patches[p].egg) continue;
        rods::startFrom(networks[solvedIndex[p]], patches[p].simulation->deployed);
      }
    }
    for (auto& j : out.joins) j.patchA = solvedIndex[j.patchA], j.patchB = solvedIndex[j.patchB];
    const rods::JoinedNetwork joined = rods::joinPatches(networks, out.joins);
    for (auto& j : out.joins) {  // back to layout patch ids for the report
      j.patchA = static_cast<int>(std::find(solvedIndex.begin(), solvedIndex.end(), j.patchA) - solvedIndex.begin());
      j.patchB = static_cast<int>(std::find(solvedIndex.begin(), solvedIndex.end(), j.patchB) - solvedIndex.begin());
    }
    rods::SimulationOptions options;
    options.model.notches = scene.simulation.notches;
    options.model.gravity = scene.simulation.gravity;
  options.fastenBoltsUnderLoad = scene.simulation.fasten_bolts;
    options.model.frictionMu = scene.simulation.friction_mu;
    options.solver.tolerance = scene.simulation.newton_tolerance;
    options.solver.timeLimit_s = scene.simulation.time_limit_s;
    options.compareWithoutNotches = false;  // RMS1/RMS2 stay a per-patch figure
    options.scaleFactor = boundingBox(surface).size().norm();
    options.historyEvery = kErrorHistoryEvery;
    if (out.warmStart) {
      options.gravitySteps = 0;                        // the start carries its weight already
      options.solver.stiffnessContinuation = false;   // and is no far-off guess to soften towards
    }
    out.simulation = rods::simulateGrid(joined.network, surface, options);
  } catch (const Error& e) {
    out.failure = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
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
  j["max_sag_m"] = run.maxSag_m;  // under self-weight, from the start state (warm) or the weightless equilibrium
  j["max_sag_from"] = joined.warmStart ? "patch_by_patch_equilibria" : "weightless_equilibrium";
  j["unknowns"] = run.unknowns;
  j["factorisations"] = run.solver.factorisations;        // Cholesky, shift trials included
  j["energy_evaluations"] = run.solver.energyEvaluations;  // line-search trials
  j["status"] = rods::toString(run.solver.status);
  if (!joined.simulation->converged) j["reason"] = joined.simulation->reason;
  if (run.deviation) {
    j["rmse_m"] = run.deviation->rmse_m;
    j["max_error_m"] = run.deviation->max_m;
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
          "patch {} collapses under its own weight even held at every connection of its four sides; the joined "
          "structure holds it on less (a neighbour instead of supports along the shared sides), so it cannot stand "
          "near the design either and is not simulated",
          p.id);
    }
  }
  return {};
}

std::optional<rods::SimulationRun> addJoinedSimulation(const PatchingRun& run, const std::vector<SolvedPatch>& patches, const TriMesh& surface,
                                                       const Scene& scene, bool propagated, int solved, nlohmann::json& simulation,
                                                       bool patchesHeldAllRound) {
  simulation["patch_by_patch"] = {{"rmse_m", simulation["rmse_m"]},
                                  {"max_error_m", simulation["max_error_m"]},
                                  {"converged", simulation["converged"]},
                                  {"iterations", simulation["iterations"]},  // summed over patches
                                  {"seconds", simulation.value("seconds", 0.0)}};
  std::string skipped;
  if (!scene.simulation.join_patches) skipped = "the scene does not join patches (simulation.join_patches = false)";
  else if (!propagated) skipped = "no propagated members: one patch, or no neighbours' member ends to bolt together";
  else if (solved < 2) skipped = "fewer than two solved patches";
  else if (patchesHeldAllRound) skipped = collapsedWhileHeld(patches);
  if (!skipped.empty()) {
    simulation["joined"] = {{"ran", false}, {"skipped_reason", skipped}};
    return std::nullopt;
  }
  JoinedRun joined = simulateJoined(run, patches, surface, scene);
  simulation["joined"] = joinedSection(joined);
  if (!joined.simulation) return std::nullopt;
  return std::move(joined.simulation->deployed);
}

}  // namespace egg::app
