#include "core/rods/deployment.hpp"

#include "core/errors.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace egg::rods {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Normal `from` turned towards `to` by the fraction t of the angle between them.
Eigen::Vector3d turnNormal(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double t) {
  const Eigen::Quaterniond full = Eigen::Quaterniond::FromTwoVectors(from, to);
  return Eigen::Quaterniond::Identity().slerp(t, full) * from;
}

struct Measurer {
  const RodNetwork& network;
  const DeploymentOptions& options;
  // Connections from this index on are joints between patches (joinDeployedPatches): measured by
  // their gap and force, not as crossings of the grid (two boundary lamellas lie along each other).
  int firstJoin = std::numeric_limits<int>::max();

  void operator()(const RodModel& model, DeploymentStep& step) const {
    // The lamellas' own elastic energy (J): bending about both axes and twisting at every interior
    // vertex, stretching of every edge. Not the solver's energy, whose penalties and
    // pseudo-friction (Section 2.5) change as bolts move between edges without work being done.
    step.energyJ = 0.0;
    step.maxBendingStressPa = step.maxTorsionStressPa = step.maxAxialStressPa = 0.0;
    step.maxStressRatio = 0.0;
    std::vector<double> strains;
    for (int r = 0; r < model.rodCount(); ++r) {
      const Rod& rod = network.rods[r];
      const RodStiffness& k = model.stiffness(r);
      const double h = model.restEdgeLength(r), e = rod.material.youngsModulusPa;
      strains.clear();
      for (int i = 0; i + 1 < model.vertexCount(r); ++i) {
        strains.push_back((model.vertex(r, i + 1) - model.vertex(r, i)).norm() / h - 1.0);
        step.energyJ += 0.5 * k.stretching * h * strains.back() * strains.back();
        step.maxAxialStressPa = std::max(step.maxAxialStressPa, e * std::abs(strains.back()));
      }
      const std::vector<RodModel::VertexStrain> vertexStrains = model.vertexStrains(r);
      for (size_t v = 0; v < vertexStrains.size(); ++v) {  // interior vertex v + 1
        const RodModel::VertexStrain& s = vertexStrains[v];
        step.energyJ += 0.5 * h *
                        (k.bendingWeak * s.weakCurvature * s.weakCurvature +
                         k.bendingStrong * s.strongCurvature * s.strongCurvature +
                         k.twisting * s.twistRate * s.twistRate);
        const double bending = e * (std::abs(s.weakCurvature) * 0.5 * rod.section.thicknessM +
                                    std::abs(s.strongCurvature) * 0.5 * rod.section.widthM);
        // A path that pulls supports apart stretches the lamellas: their axial stress adds to the
        // bending stress at the extreme fibre (against f_m: the catalogue has no tensile
        // strength).
        const double sigma = bending + e * std::max(std::abs(strains[v]), std::abs(strains[v + 1]));
        const double tau =
            rod.material.shearModulusPa * rod.section.thicknessM * std::abs(s.twistRate);
        step.maxBendingStressPa = std::max(step.maxBendingStressPa, bending);
        step.maxTorsionStressPa = std::max(step.maxTorsionStressPa, tau);
        double ratio = 0.0;
        if (options.bendingStrengthPa > 0.0) ratio = sigma / options.bendingStrengthPa;
        if (options.shearStrengthPa > 0.0) ratio = std::max(ratio, tau / options.shearStrengthPa);
        if (ratio > step.maxStressRatio) {
          step.maxStressRatio = ratio;
          step.maxStressRod = r;
        }
      }
    }
    step.maxNotchForceN = step.maxNotchTravelM = 0.0;
    step.notchForcesN.clear();
    step.minCrossingAngleRad = std::min(firstJoin, model.boltCount()) > 0 ? M_PI : 0.0;
    step.maxCrossingAngleRad = 0.0;
    step.maxJoinGapM = step.maxJoinForceN = 0.0;
    for (int c = std::min(firstJoin, model.boltCount()); c < model.boltCount(); ++c) {
      step.maxJoinGapM = std::max(step.maxJoinGapM, model.boltGap(c).norm());
      step.maxJoinForceN = std::max(step.maxJoinForceN, model.boltForce(c).norm());
    }
    for (int c = 0; c < std::min(firstJoin, model.boltCount()); ++c) {
      const Connection& con = network.connections[c];
      for (int side = 0; side < 2; ++side) {
        const double force = model.notchEndForce(c, side);
        step.maxNotchForceN = std::max(step.maxNotchForceN, force);
        step.notchForcesN.push_back(force);
        const double flatS =
            side == 0 ? con.startAM.value_or(con.sAM) : con.startBM.value_or(con.sBM);
        step.maxNotchTravelM =
            std::max(step.maxNotchTravelM, std::abs(model.boltPosition(c, side) - flatS));
      }
      const double angle = model.crossingAngle(c);
      step.minCrossingAngleRad = std::min(step.minCrossingAngleRad, angle);
      step.maxCrossingAngleRad = std::max(step.maxCrossingAngleRad, angle);
    }
    step.supportForcesN.clear();
    step.maxSupportForceN = 0.0;
    for (int a = 0; a < model.anchorCount(); ++a) {
      step.supportForcesN.push_back(model.anchorForce(a));
      step.maxSupportForceN = std::max(step.maxSupportForceN, step.supportForcesN.back().norm());
    }
    step.contactPoints.clear();
    if (options.keepFrames) {
      for (int r = 0; r < model.rodCount(); ++r) {
        std::vector<Eigen::Vector3d> points;
        for (int i = 0; i < model.vertexCount(r); ++i) points.push_back(model.contactPoint(r, i));
        step.contactPoints.push_back(std::move(points));
      }
    }
  }
};

double largestMove(const RodModel& before, const RodModel& after) {
  double largest = 0.0;
  for (int r = 0; r < after.rodCount(); ++r)
    for (int i = 0; i < after.vertexCount(r); ++i)
      largest = std::max(largest, (after.vertex(r, i) - before.vertex(r, i)).norm());
  return largest;
}

void placeSupports(RodModel& model, const SupportState& state) {
  if (static_cast<int>(state.positions.size()) != model.anchorCount() ||
      state.normals.size() != state.positions.size())
    throw InvalidInput("deployment: the path holds " + std::to_string(state.positions.size()) +
                       " supports (" + std::to_string(state.normals.size()) +
                       " normals), the grid has " + std::to_string(model.anchorCount()) +
                       " anchors");
  for (int a = 0; a < model.anchorCount(); ++a)
    model.setAnchor(a, state.positions[a], state.normals[a]);
}

// One phase of a path at a time: `control` sets the model's supports, bolts or loads for the
// phase's parameter u in (0, 1] and records them in the step; the step is solved from the last
// equilibrium, measured, and recorded as t = tOffset + u. Steps as (parameter, depth); a rejected
// step is replaced by its two halves.
struct PathRunner {
  using Control = std::function<void(RodModel&, double, DeploymentStep&)>;
  RodModel& model;
  DeploymentResult& result;
  const DeploymentOptions& options;
  const Measurer& measure;
  SolverOptions& solverOptions;
  std::chrono::steady_clock::time_point start;

  void phase(const Control& control, double tOffset, int steps) {
    std::vector<std::pair<double, int>> pending;
    for (int k = steps; k >= 1; --k) pending.emplace_back(static_cast<double>(k) / steps, 0);
    double done = 0.0;
    while (!pending.empty()) {
      const auto [u, depth] = pending.back();
      pending.pop_back();
      const double t = tOffset + u;
      const double spent = secondsSince(start);
      if (spent > options.solver.timeLimitS) {
        result.completed = false;
        result.timedOut = true;
        result.reason = "time limit " + std::to_string(options.solver.timeLimitS) +
                        " s reached at t = " + std::to_string(tOffset + done);
        return;
      }
      solverOptions.timeLimitS = std::max(1e-3, options.solver.timeLimitS - spent);
      RodModel trial = model;
      DeploymentStep step;
      step.t = t;
      control(trial, u, step);
      const SolverResult solved = minimiseEnergy(trial, solverOptions);
      step.status = solved.status;
      step.iterations = solved.iterations;
      step.seconds = solved.seconds;
      step.stable = solved.stableEquilibrium;
      measure(trial, step);
      step.maxVertexMoveM = largestMove(model, trial);
      const DeploymentStep& previous = result.steps.back();
      // The energy the step should reach on a smooth path: the last step's rate carried on (a
      // path that unloads loses energy smoothly); a snap falls below it by a finite part at any
      // step.
      double predicted = previous.energyJ;
      if (result.steps.size() >= 2) {
        const DeploymentStep& before = result.steps[result.steps.size() - 2];
        if (previous.t > before.t)
          predicted +=
              (previous.energyJ - before.energyJ) / (previous.t - before.t) * (t - previous.t);
      }
      const double drop = std::min(previous.energyJ, predicted) - step.energyJ;
      const bool dropped =
          solved.converged &&
          drop > options.snapEnergyDrop * std::max(previous.energyJ, model.energyUnit());
      // Relative above the limit: a path at five times the strength is resolved to a unit, not to
      // a fifth of one (the refinement would otherwise multiply the steps of a hopeless path).
      const bool steep =
          solved.converged && std::abs(step.maxStressRatio - previous.maxStressRatio) >
                                  options.stressRatioStep * std::max(1.0, previous.maxStressRatio);
      if ((!solved.converged || dropped || steep) && depth < options.maxRefinements) {
        pending.emplace_back(u, depth + 1);
        pending.emplace_back(0.5 * (done + u), depth + 1);
        continue;
      }
      result.iterations += solved.iterations;
      if (!solved.converged) {
        result.completed = false;
        result.timedOut = solved.status == SolverStatus::TimeLimit;
        result.reason = "no equilibrium at t = " + std::to_string(t) + " (a step of " +
                        std::to_string(u - done) + "): " + solved.reason;
        result.last.solver = solved;
        return;
      }
      step.snap = dropped;
      step.jammedBolts = 0;
      for (size_t k = 0; k < step.notchForcesN.size(); ++k) {
        const double force = step.notchForcesN[k];
        if (force > options.jamForceN && force > 1.1 * previous.notchForcesN[k]) ++step.jammedBolts;
      }
      result.snaps += step.snap;
      result.jammedSteps += step.jammedBolts > 0;
      model = std::move(trial);
      result.last.solver = solved;
      done = u;
      result.steps.push_back(std::move(step));
    }
  }
};

// The state the path starts from, solved and measured as step 0 (t = 0). False when it does not
// settle (result says why and holds that state). Later steps start next to an equilibrium: no
// need to soften the stiff terms (rod_solver.hpp).
bool firstStep(RodModel& model, const Measurer& measure, std::vector<Eigen::Vector3d> supports,
               const std::string& what, SolverOptions& solverOptions,
               std::chrono::steady_clock::time_point start, DeploymentResult& result) {
  DeploymentStep first;
  result.last.solver = minimiseEnergy(model, solverOptions);
  first.status = result.last.solver.status;
  first.iterations = result.last.solver.iterations;
  first.stable = result.last.solver.stableEquilibrium;
  first.seconds = result.last.solver.seconds;
  first.supportPositionsM = std::move(supports);
  measure(model, first);
  result.iterations = first.iterations;
  result.steps.push_back(std::move(first));
  if (!result.last.solver.converged) {
    result.reason = what + " does not settle: " + result.last.solver.reason;
    result.timedOut = result.last.solver.status == SolverStatus::TimeLimit;
    recordState(model, result.last);
    result.seconds = secondsSince(start);
    return false;
  }
  solverOptions.stiffnessContinuation = false;
  return true;
}

// The peak step, the last state and the totals.
void finish(const RodModel& model, const DeploymentOptions& options,
            std::chrono::steady_clock::time_point start, DeploymentResult& result) {
  result.peakStep = 0;
  for (size_t k = 1; k < result.steps.size(); ++k) {
    const DeploymentStep& s = result.steps[k];
    const DeploymentStep& peak = result.steps[result.peakStep];
    const bool higher = options.bendingStrengthPa > 0.0 || options.shearStrengthPa > 0.0
                            ? s.maxStressRatio > peak.maxStressRatio
                            : s.maxBendingStressPa > peak.maxBendingStressPa;
    if (higher) result.peakStep = static_cast<int>(k);
  }
  recordState(model, result.last);
  result.last.solver.iterations = result.iterations;
  result.seconds = secondsSince(start);
  result.last.solver.seconds = result.seconds;
}

}  // namespace

void DeploymentOptions::validate() const {
  model.validate();
  solver.validate();
  if (steps < 1) throw InvalidInput("DeploymentOptions.steps must be >= 1");
  if (engageSteps < 1) throw InvalidInput("DeploymentOptions.engageSteps must be >= 1");
  if (maxRefinements < 0 || maxRefinements > 12)
    throw InvalidInput("DeploymentOptions.maxRefinements must be in 0..12");
  if (!(snapEnergyDrop > 0.0 && snapEnergyDrop < 1.0))
    throw InvalidInput("DeploymentOptions.snapEnergyDrop must be in (0, 1)");
  if (!(stressRatioStep > 0.0)) throw InvalidInput("DeploymentOptions.stressRatioStep must be > 0");
  if (!(jamForceN > 0.0)) throw InvalidInput("DeploymentOptions.jamForceN must be > 0");
  if (!(bendingStrengthPa >= 0.0) || !(shearStrengthPa >= 0.0))
    throw InvalidInput("DeploymentOptions strengths must be >= 0");
}

SupportPath straightSupportPath(const SupportState& from, const SupportState& to) {
  if (from.positions.size() != to.positions.size() ||
      from.normals.size() != from.positions.size() || to.normals.size() != to.positions.size())
    throw InvalidInput("straightSupportPath: the two support states differ in size");
  for (size_t a = 0; a < from.normals.size(); ++a) {
    const Eigen::Vector3d n0 = from.normals[a].normalized(), n1 = to.normals[a].normalized();
    if (!n0.allFinite() || !n1.allFinite() || n0.dot(n1) < -0.999)
      throw InvalidInput("straightSupportPath: support " + std::to_string(a) +
                         " would turn its normal by half a turn (or has none)");
  }
  return [from, to](double t) {
    SupportState state;
    for (size_t a = 0; a < from.positions.size(); ++a) {
      state.positions.push_back((1.0 - t) * from.positions[a] + t * to.positions[a]);
      state.normals.push_back(
          turnNormal(from.normals[a].normalized(), to.normals[a].normalized(), t));
    }
    return state;
  };
}

DeploymentResult deploy(const RodNetwork& flat, const SupportPath& path,
                        const DeploymentOptions& options) {
  options.validate();
  if (!path) throw InvalidInput("deployment: no support path");
  const auto start = std::chrono::steady_clock::now();
  ModelOptions modelOptions = options.model;
  modelOptions.gravity = false;
  RodModel model(flat, modelOptions);
  const Measurer measure{flat, options};
  DeploymentResult result;

  if (!options.movedSupports.empty() &&
      static_cast<int>(options.movedSupports.size()) != model.anchorCount())
    throw InvalidInput("deployment: movedSupports names " +
                       std::to_string(options.movedSupports.size()) + " supports, the grid has " +
                       std::to_string(model.anchorCount()) + " anchors");
  const auto moved = [&](int a) {
    return options.movedSupports.empty() || options.movedSupports[a];
  };
  for (int a = 0; a < model.anchorCount(); ++a) model.setAnchorActive(a, moved(a));
  const SupportState flatSupports = path(0.0);
  placeSupports(model, flatSupports);
  SolverOptions solverOptions = options.solver;
  // The flat grid is its own equilibrium (zero energy, Section 2.3): this solve only settles the
  // discretisation.
  if (!firstStep(model, measure, flatSupports.positions, "the flat grid", solverOptions, start,
                 result))
    return result;
  result.completed = true;
  PathRunner runner{model, result, options, measure, solverOptions, start};
  const auto follow = [](const SupportPath& phasePath) {
    return [phasePath](RodModel& m, double u, DeploymentStep& step) {
      const SupportState supports = phasePath(u);
      placeSupports(m, supports);
      step.supportPositionsM = supports.positions;
    };
  };
  runner.phase(follow(path), 0.0, options.steps);
  // The supports held only at the end: switched on where the grid now is, then moved to their
  // places.
  std::vector<int> engaged;
  for (int a = 0; a < model.anchorCount(); ++a)
    if (!moved(a)) engaged.push_back(a);
  if (result.completed && !engaged.empty()) {
    const SupportState end = path(1.0);
    SupportState from = end;
    for (int a : engaged) {
      model.anchorPlace(a, from.positions[a], from.normals[a]);
      model.setAnchorActive(a, true);
    }
    result.engagedFromT = 1.0;
    runner.phase(follow(straightSupportPath(from, end)), 1.0, std::max(1, options.engageSteps));
  }
  finish(model, options, start, result);
  return result;
}

void JoiningOptions::validate() const {
  deployment.validate();
  if (weightSteps < 1 || joinSteps < 1 || releaseSteps < 1)
    throw InvalidInput("JoiningOptions: weightSteps, joinSteps and releaseSteps must be >= 1");
  if (!(minWeightFactor > 0.0 && minWeightFactor < 1.0))
    throw InvalidInput("JoiningOptions.minWeightFactor must be in (0, 1)");
}

DeploymentResult joinDeployedPatches(const RodNetwork& network, int firstJoin,
                                     const std::vector<bool>& temporarySupports,
                                     const JoiningOptions& options) {
  options.validate();
  const int connections = static_cast<int>(network.connections.size());
  if (firstJoin < 0 || firstJoin > connections)
    throw InvalidInput("joining: the joints start at connection " + std::to_string(firstJoin) +
                       " of " + std::to_string(connections));
  if (temporarySupports.size() != network.anchors.size())
    throw InvalidInput("joining: temporarySupports names " +
                       std::to_string(temporarySupports.size()) + " supports, the network has " +
                       std::to_string(network.anchors.size()) + " anchors");
  const DeploymentOptions& o = options.deployment;
  const auto start = std::chrono::steady_clock::now();
  ModelOptions modelOptions = o.model;
  modelOptions.gravity = options.selfWeight;
  RodModel model(network, modelOptions);
  Measurer measure{network, o};
  measure.firstJoin = firstJoin;
  DeploymentResult result;
  const auto supportPositions = [&](const RodModel& m) {
    std::vector<Eigen::Vector3d> positions(m.anchorCount());
    Eigen::Vector3d normal;
    for (int a = 0; a < m.anchorCount(); ++a) m.anchorPlace(a, positions[a], normal);
    return positions;
  };
  // t = 0: every patch where its deployment left it, on all its supports, weightless, the joints
  // open.
  model.setLoadFactor(0.0);
  for (int c = firstJoin; c < connections; ++c) model.setBoltWeight(c, 0.0);
  SolverOptions solverOptions = o.solver;
  if (!firstStep(model, measure, supportPositions(model), "the deployed patches", solverOptions,
                 start, result))
    return result;
  result.completed = true;
  PathRunner runner{model, result, o, measure, solverOptions, start};
  // Penalty weights change over decades: a geometric ramp closes a joint (or lets a support go)
  // evenly in the gap, where a linear one would do it all in its first step.
  const auto ramp = [&](double u) { return std::pow(options.minWeightFactor, 1.0 - u); };
  double t = 0.0;
  if (options.selfWeight) {
    runner.phase(
        [&](RodModel& m, double u, DeploymentStep& step) {
          m.setLoadFactor(u);
          step.supportPositionsM = supportPositions(m);
        },
        t, options.weightSteps);
    t += 1.0;
  }
  if (result.completed && firstJoin < connections) {
    runner.phase(
        [&](RodModel& m, double u, DeploymentStep& step) {
          for (int c = firstJoin; c < connections; ++c) m.setBoltWeight(c, ramp(u));
          step.supportPositionsM = supportPositions(m);
        },
        t, options.joinSteps);
    t += 1.0;
  }
  if (result.completed && std::find(temporarySupports.begin(), temporarySupports.end(), true) !=
                              temporarySupports.end()) {
    runner.phase(
        [&](RodModel& m, double u, DeploymentStep& step) {
          for (int a = 0; a < m.anchorCount(); ++a)
            if (temporarySupports[a]) m.setAnchorWeight(a, u < 1.0 ? ramp(1.0 - u) : 0.0);
          step.supportPositionsM = supportPositions(m);
        },
        t, options.releaseSteps);
  }
  finish(model, o, start, result);
  return result;
}

}  // namespace egg::rods
