#include "core/rods/simulation.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace egg::rods {

namespace {
template <class... Args>
std::string formatMessage(const char* pattern, Args... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer), pattern, args...);
  return buffer;
}
}  // namespace

void SimulationOptions::validate() const {
  model.validate();
  solver.validate();
  if (gravitySteps < 0) throw InvalidInput("SimulationOptions.gravitySteps must be >= 0");
  if (!(collapseFraction >= 0.0))
    throw InvalidInput("SimulationOptions.collapseFraction must be >= 0");
  if (!(scaleFactor > 0.0)) throw InvalidInput("SimulationOptions.scaleFactor must be > 0");
  if (historyEvery < 0) throw InvalidInput("SimulationOptions.historyEvery must be >= 0");
}

void startFrom(RodNetwork& network, const SimulationRun& run) {
  if (run.contactPoints.size() != network.rods.size() ||
      run.normals.size() != network.rods.size()) {
    throw InvalidInput("startFrom: the run has " + std::to_string(run.contactPoints.size()) +
                       " rods, the network " + std::to_string(network.rods.size()));
  }
  for (size_t r = 0; r < network.rods.size(); ++r) {
    if (run.contactPoints[r].size() < 2 || run.contactPoints[r].size() != run.normals[r].size()) {
      throw InvalidInput("startFrom: rod " + std::to_string(r) +
                         " of the run has mismatched or too few vertices");
    }
    network.rods[r].guess = run.contactPoints[r];
    network.rods[r].guessNormals = run.normals[r];
  }
  // The bolts restart where the run left them in their notches (not where the guess curves
  // happen to cross, which a search of the notch finds only to its sampling: the joined run then
  // began with every fastened joint off its equilibrium).
  if (run.boltPositionsM.size() != network.connections.size()) {
    throw InvalidInput("startFrom: the run has " + std::to_string(run.boltPositionsM.size()) +
                       " bolts, the network " + std::to_string(network.connections.size()) +
                       " connections");
  }
  for (size_t c = 0; c < network.connections.size(); ++c) {
    Connection& con = network.connections[c];
    con.startAM = run.boltPositionsM[c][0];
    con.startBM = run.boltPositionsM[c][1];
  }
}

SimulationRun simulateRods(const RodNetwork& network, const SurfaceDistance* surface,
                           const SimulationOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  RodModel model(network, options.model);
  SimulationRun run;
  run.notches = options.model.notches;

  // Self-weight is applied in steps after a weightless solve: a large or soft grid may sag far
  // from the deployed guess (Section 3.5.2), and Newton is reliable only from nearby states.
  const int steps = options.model.gravity ? options.gravitySteps : 0;
  const bool fromStart = options.model.gravity && steps == 0;  // sag measured from the start state
  SolverOptions solverOptions = options.solver;
  int iterations = 0, switches = 0, step = 0, factorisations = 0, evaluations = 0;
  SolverPhases phases;
  // Error against run time: the solver's observer, shifted to the run's iterations and clock (a
  // load step's minimiseEnergy counts from zero), measures the contact points when asked.
  double observing = 0.0;  // seconds spent in the observer so far, left out of the samples' clock
  double callStart =
      0.0;  // the current load step's minimiseEnergy started then (run clock, measuring left out)
  int lastObserved =
      -1;  // a load step starts at the state the previous one ended with: seen already
  const bool recordHistory = options.historyEvery > 0 && surface;
  if (recordHistory || options.solver.observer) {
    if (recordHistory) solverOptions.observeEvery = options.historyEvery;
    solverOptions.observer = [&](const SolverProgress& progress, const RodModel& observed) {
      if (progress.iteration + iterations == lastObserved) return;
      lastObserved = progress.iteration + iterations;
      const auto before = std::chrono::steady_clock::now();
      SolverProgress shifted = progress;
      shifted.iteration += iterations;
      shifted.seconds = callStart + progress.seconds;
      if (recordHistory) {
        std::vector<Eigen::Vector3d> contact;
        for (int r = 0; r < observed.rodCount(); ++r)
          for (int i = 0; i < observed.vertexCount(r); ++i)
            contact.push_back(observed.contactPoint(r, i));
        const DeviationStats d = measureDeviation(contact, *surface, options.scaleFactor);
        run.history.push_back({shifted.iteration, step, shifted.seconds, d.rmseM, d.maxM});
      }
      if (options.solver.observer) options.solver.observer(shifted, observed);
      const double spent =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
      observing += spent;
      if (recordHistory) run.historySeconds += spent;
    };
  }
  std::vector<Eigen::Vector3d> weightless;  // vertices at the weightless equilibrium (or the start)
  double extent = 0.0;                      // its bounding-box diagonal
  auto recordReference = [&]() {
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    for (int r = 0; r < model.rodCount(); ++r) {
      for (int i = 0; i < model.vertexCount(r); ++i) {
        weightless.push_back(model.vertex(r, i));
        low = low.cwiseMin(weightless.back());
        high = high.cwiseMax(weightless.back());
      }
    }
    extent = (high - low).norm();
  };
  if (fromStart) recordReference();
  if (fromStart && options.fastenBoltsUnderLoad) model.fastenBolts();
  auto largestDisplacement = [&]() {
    double largest = 0.0;
    size_t k = 0;
    for (int r = 0; r < model.rodCount(); ++r) {
      for (int i = 0; i < model.vertexCount(r); ++i)
        largest = std::max(largest, (model.vertex(r, i) - weightless[k++]).norm());
    }
    return largest;
  };
  SolverWorkspace workspace;  // the load steps share the Hessian's pattern and its analysis
  for (step = 0; step <= steps; ++step) {
    model.setLoadFactor(steps == 0 ? 1.0 : static_cast<double>(step) / steps);
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    solverOptions.timeLimitS = std::max(1e-3, options.solver.timeLimitS - spent);
    solverOptions.maxIterations = std::max(1, options.solver.maxIterations - iterations);
    callStart = spent - observing;
    run.solver = minimiseEnergy(model, solverOptions, workspace);
    // Later load steps start next to an equilibrium: no need to soften the stiff terms again.
    solverOptions.stiffnessContinuation = false;
    iterations = run.solver.iterations += iterations;
    switches = run.solver.boltEdgeSwitches += switches;
    factorisations = run.solver.factorisations += factorisations;
    evaluations = run.solver.energyEvaluations += evaluations;
    phases = run.solver.phases += phases;
    if (run.solver.status == SolverStatus::IterationLimit) {
      run.solver.reason = formatMessage("no convergence in %d iterations (decrement %.3g J)",
                                        iterations, run.solver.decrement);
    }
    // A load step that ran out of iterations or time far from the weightless equilibrium, still
    // going down: the grid is falling through, not converging slowly.
    const bool outOfBudget = run.solver.status == SolverStatus::IterationLimit ||
                             run.solver.status == SolverStatus::TimeLimit;
    if ((step > 0 || fromStart) && outOfBudget && options.collapseFraction > 0.0) {
      const double moved = largestDisplacement();
      if (moved > options.collapseFraction * extent) {
        run.solver.status = SolverStatus::Collapsed;
        run.solver.reason = formatMessage(
            "collapses under its own weight: after %d iterations a vertex has moved %.3g m (%.1f "
            "%% of the grid's "
            "extent %.3g m) from the %s and the energy is still decreasing (decrement %.3g J): "
            "no equilibrium near the design shape (Section 3.5.2, Fig. 3.11)",
            iterations, moved, 100.0 * moved / extent, extent,
            fromStart ? "start state" : "weightless equilibrium", run.solver.decrement);
      }
    }
    if (step == 0 && steps > 0) {
      recordReference();
      for (int r = 0; r < model.rodCount(); ++r) {
        std::vector<Eigen::Vector3d> points;
        for (int i = 0; i < model.vertexCount(r); ++i) points.push_back(model.contactPoint(r, i));
        run.weightlessContactPoints.push_back(std::move(points));
      }
      if (options.fastenBoltsUnderLoad && run.solver.converged) model.fastenBolts();
    }
    if (!run.solver.converged) {
      if (step < steps) {
        run.solver.reason = "at load step " + std::to_string(step) + " of " +
                            std::to_string(steps) + ": " + run.solver.reason;
      }
      break;
    }
  }
  if (!weightless.empty()) run.maxSagM = largestDisplacement();
  run.solver.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  recordState(model, run);
  if (surface) {
    std::vector<Eigen::Vector3d> contact;
    for (const auto& points : run.contactPoints)
      contact.insert(contact.end(), points.begin(), points.end());
    run.deviation = measureDeviation(contact, *surface, options.scaleFactor);
  }
  return run;
}

void recordState(const RodModel& model, SimulationRun& run) {
  run.unknowns = model.dofCount();
  run.vertices = 0;
  run.centrelines.clear();
  run.normals.clear();
  run.contactPoints.clear();
  run.boltPositionsM.clear();
  run.boltGapsM.clear();
  run.boltForcesN.clear();
  for (int r = 0; r < model.rodCount(); ++r) {
    run.centrelines.push_back(model.centreline(r));
    std::vector<Eigen::Vector3d> normals, points;
    for (int i = 0; i < model.vertexCount(r); ++i) {
      normals.push_back(model.vertexNormal(r, i));
      points.push_back(model.contactPoint(r, i));
    }
    run.normals.push_back(std::move(normals));
    run.contactPoints.push_back(std::move(points));
    run.vertices += model.vertexCount(r);
  }
  for (int c = 0; c < model.boltCount(); ++c) {
    run.boltPositionsM.push_back({model.boltPosition(c, 0), model.boltPosition(c, 1)});
    run.boltGapsM.push_back(model.boltGap(c).norm());
    run.boltForcesN.push_back(model.boltForce(c).norm());
  }
}

SimulationResult simulateGrid(const RodNetwork& network, const TriMesh& surface,
                              const SimulationOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  const SurfaceDistance distance(surface);
  SimulationResult result;
  result.deployed = simulateRods(network, &distance, options);
  result.converged = result.deployed.solver.converged;
  if (!result.converged) result.reason = "deployed run: " + result.deployed.solver.reason;
  if (options.compareWithoutNotches && options.model.notches) {
    SimulationOptions plain = options;
    plain.model.notches = false;
    plain.historyEvery =
        0;  // the error against run time is the deployed run's (a comparison needs only its end)
    result.withoutNotches = simulateRods(network, &distance, plain);
    if (!result.withoutNotches->solver.converged) {
      if (result.converged)
        result.reason = "run without notches: " + result.withoutNotches->solver.reason;
      result.converged = false;
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace egg::rods
