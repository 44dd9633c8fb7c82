#include "pipeline/deployment_joining.hpp"

#include "core/errors.hpp"
#include "core/rods/simulation.hpp"

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// The joined network started where the patches' deployments ended, with every support they stood
// on: theirs in the finished structure, and the rest (the shoring along shared sides,
// simulation.hold_shared_sides) marked temporary.
struct JoiningInput {
  rods::RodNetwork network;
  int firstJoin = 0;
  std::vector<bool> temporary;
};

JoiningInput joiningInput(const RunState& state, const std::vector<JoiningPart>& parts) {
  const rods::JoinedNetwork& joined = *state.joinedNetwork;
  JoiningInput in{joined.network, joined.firstJoin, {}};
  in.temporary.assign(in.network.anchors.size(), false);
  rods::SimulationRun start;  // the patches' ends, in the joined network's order
  if (parts.size() != joined.firstRod.size())
    throw InvalidInput(fmt::format("joining: the joined network has {} patches, the deployment {}",
                                   joined.firstRod.size(), parts.size()));
  for (size_t k = 0; k < parts.size(); ++k) {
    const rods::SimulationRun& end = *parts[k].last;
    const int first = joined.firstRod[k];
    start.contactPoints.insert(start.contactPoints.end(), end.contactPoints.begin(),
                               end.contactPoints.end());
    start.normals.insert(start.normals.end(), end.normals.begin(), end.normals.end());
    start.boltPositionsM.insert(start.boltPositionsM.end(), end.boltPositionsM.begin(),
                                end.boltPositionsM.end());
    for (const rods::Anchor& a : parts[k].network->anchors) {
      const bool kept = std::any_of(joined.network.anchors.begin(), joined.network.anchors.end(),
                                    [&](const rods::Anchor& b) {
                                      return b.rod == first + a.rod && std::abs(b.sM - a.sM) < 1e-9;
                                    });
      if (kept) continue;
      rods::Anchor shoring = a;
      shoring.rod += first;
      in.network.anchors.push_back(shoring);
      in.temporary.push_back(true);
    }
  }
  for (size_t c = joined.firstJoin; c < in.network.connections.size(); ++c)
    start.boltPositionsM.push_back({in.network.connections[c].sAM, in.network.connections[c].sBM});
  rods::startFrom(in.network, start);  // throws when a patch's end does not match its rods
  return in;
}

}  // namespace

double contactRmsM(const std::vector<std::vector<Eigen::Vector3d>>& a,
                   const std::vector<std::vector<Eigen::Vector3d>>& b) {
  if (a.size() != b.size() || a.empty()) return -1.0;
  double sum = 0.0;
  long count = 0;
  for (size_t r = 0; r < a.size(); ++r) {
    if (a[r].size() != b[r].size()) return -1.0;
    for (size_t i = 0; i < a[r].size(); ++i, ++count) sum += (a[r][i] - b[r][i]).squaredNorm();
  }
  return std::sqrt(sum / std::max<long>(count, 1));
}

JoiningRun joinDeployed(const RunState& state, const std::vector<JoiningPart>& parts,
                        const rods::DeploymentOptions& options) {
  JoiningRun run;
  const Scene& scene = state.scene;
  if (!scene.deployment.joinPatches) {
    run.skipped = "the scene does not join the deployed patches (deployment.join_patches = false)";
    return run;
  }
  if (!state.joinedNetwork || !state.joined) {
    run.skipped = "no joined simulation to join the patches into (simulation.joined)";
    return run;
  }
  for (const JoiningPart& part : parts) {
    if (!part.last || !part.reached || !part.network) {
      run.skipped = fmt::format(
          "patch P{} has no standing state to join from (its deployment did not reach its "
          "supports; for a generalised patch, its own simulation did not converge)",
          part.id);
      return run;
    }
  }
  try {
    const JoiningInput in = joiningInput(state, parts);
    run.joints = static_cast<int>(in.network.connections.size()) - in.firstJoin;
    run.temporarySupports =
        static_cast<int>(std::count(in.temporary.begin(), in.temporary.end(), true));
    rods::JoiningOptions o;
    o.deployment = options;
    // One structure, one solve at a time: its stencils on every thread (as the joined simulation).
    o.deployment.solver.threads = std::max(1, tbb::this_task_arena::max_concurrency());
    // Every patch starts at an equilibrium of its own: no far-off guess to soften towards (as the
    // joined simulation's warm start).
    o.deployment.solver.stiffnessContinuation = false;
    // Like for like with the joined simulation, which carries self-weight when the scene says so.
    o.selfWeight = scene.simulation.rods.model.gravity;
    run.selfWeight = o.selfWeight;
    o.weightSteps = std::max(1, scene.deployment.steps / 2);
    o.joinSteps = o.releaseSteps = scene.deployment.steps;
    run.result = rods::joinDeployedPatches(in.network, in.firstJoin, in.temporary, o);
    // Against an equilibrium only: an unconverged joined simulation leaves the comparison null.
    if (state.joined->solver.converged)
      run.endVsSimulationRmsM =
          contactRmsM(run.result->last.contactPoints, state.joined->contactPoints);
    // The joined simulation's own joints, as its solve left them.
    const rods::SimulationRun& simulated = *state.joined;
    for (size_t c = in.firstJoin; c < simulated.boltGapsM.size(); ++c) {
      run.simulationJoinGapM = std::max(run.simulationJoinGapM, simulated.boltGapsM[c]);
      run.simulationJoinForceN = std::max(run.simulationJoinForceN, simulated.boltForcesN[c]);
    }
  } catch (const Error& e) {
    run.failure = e.what();
  }
  return run;
}

json stepJson(const rods::DeploymentStep& s) {
  return {{"t", s.t},
          {"converged", s.status == rods::SolverStatus::Converged},
          {"iterations", s.iterations},
          {"energy_j", s.energyJ},
          {"stable", s.stable},
          {"snap", s.snap},
          {"max_stress_ratio", s.maxStressRatio},
          {"max_bending_stress_mpa", s.maxBendingStressPa * 1e-6},
          {"max_torsion_stress_mpa", s.maxTorsionStressPa * 1e-6},
          {"max_axial_stress_mpa", s.maxAxialStressPa * 1e-6},
          {"max_notch_force_n", s.maxNotchForceN},
          {"jammed_bolts", s.jammedBolts},
          {"max_notch_travel_m", s.maxNotchTravelM},
          {"crossing_angle_deg",
           {s.minCrossingAngleRad * 180.0 / M_PI, s.maxCrossingAngleRad * 180.0 / M_PI}},
          {"max_support_force_n", s.maxSupportForceN},
          {"max_vertex_move_m", s.maxVertexMoveM}};
}

json pathTotalsJson(const rods::DeploymentResult& r) {
  const auto& peak = r.steps[r.peakStep];
  return {{"completed", r.completed},
          {"timed_out", r.timedOut},
          {"steps", static_cast<int>(r.steps.size()) - 1},
          {"iterations", r.iterations},
          {"seconds", r.seconds},
          {"snaps", r.snaps},
          {"jammed_steps", r.jammedSteps},
          {"peak_t", peak.t},
          {"peak_stress_ratio", peak.maxStressRatio},
          {"end_stress_ratio", r.steps.back().maxStressRatio}};
}

json joiningJson(const JoiningRun& run) {
  if (!run.skipped.empty()) return {{"ran", false}, {"skipped_reason", run.skipped}};
  // The phases that ran, in order, each over one unit of t (joinDeployedPatches).
  std::vector<std::string> phases;
  if (run.selfWeight)
    phases.push_back(
        "the patches take their self-weight on their supports"
        " and shoring");
  if (run.joints > 0)
    phases.push_back(
        "the joints between their boundary lamellas are pulled closed and bolted (the bolts' "
        "stiffness raised geometrically from 1e-6 of its full value, as a clamp is tightened)");
  if (run.temporarySupports > 0)
    phases.push_back(
        "the shoring of the shared sides (and of generalised member ends bolted to a quad) is let "
        "go (its stiffness lowered so, then off, as jacks "
        "are lowered)");
  std::string described;
  for (size_t k = 0; k < phases.size(); ++k)
    described += fmt::format("{}t {}..{}: {}", k ? "; " : "", k, k + 1, phases[k]);
  json j{{"ran", true},
         {"phases", described},
         {"joints", run.joints},
         {"temporary_supports", run.temporarySupports},
         {"self_weight", run.selfWeight}};
  if (!run.failure.empty()) {
    j["completed"] = false;
    j["failure"] = run.failure;
    return j;
  }
  const rods::DeploymentResult& r = *run.result;
  double supportForce = 0.0, joinForce = 0.0, gapBefore = 0.0;
  json steps = json::array();
  for (const auto& s : r.steps) {
    supportForce = std::max(supportForce, s.maxSupportForceN);
    joinForce = std::max(joinForce, s.maxJoinForceN);
    // The widest joint before the bolts pull (the first phases' states, weight on).
    if (s.t <= (run.selfWeight ? 1.0 : 0.0) + 1e-12) gapBefore = std::max(gapBefore, s.maxJoinGapM);
    json step = stepJson(s);
    step["max_join_gap_m"] = s.maxJoinGapM;
    step["max_join_force_n"] = s.maxJoinForceN;
    steps.push_back(std::move(step));
  }
  j.update(pathTotalsJson(r));
  j.update({{"max_support_force_n", supportForce},
            {"max_join_force_n", joinForce},
            {"join_gap_before_m", gapBefore},
            {"end_join_gap_m", r.steps.back().maxJoinGapM},
            {"joined_simulation_join_gap_m", run.simulationJoinGapM},
            {"joined_simulation_join_force_n", run.simulationJoinForceN},
            {"end_vs_joined_simulation_rms_m",
             run.endVsSimulationRmsM >= 0.0 ? json(run.endVsSimulationRmsM) : json(nullptr)},
            {"path", steps}});
  if (!r.completed) j["reason"] = r.reason;
  return j;
}

}  // namespace egg::pipeline
