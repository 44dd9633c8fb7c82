#pragma once
// After every patch stands (deployment_stage.cpp): the patches joined into the structure the
// joined simulation solved, as a crew would do it (core/rods/deployment.hpp,
// joinDeployedPatches): each patch where its deployment left it, on its supports and on the
// shoring of its shared sides; self-weight taken; the joints between boundary lamellas pulled
// closed and bolted; the shoring let go. docs/deployment.md.
#include "core/rods/deployment.hpp"
#include "pipeline/run_state.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

struct JoiningRun {
  std::string skipped;  // why it did not run (nothing else is set)
  std::string failure;  // an error before any step
  std::optional<rods::DeploymentResult> result;
  int joints = 0;             // bolts between patches
  int temporarySupports = 0;  // shoring let go at the end
  bool selfWeight = false;
  double endVsSimulationRmsM = -1.0;  // against the joined simulation's equilibrium
  double simulationJoinGapM = 0.0;    // the joined simulation's widest joint (RodModel::boltGap)
  double simulationJoinForceN = 0.0;  // and its largest joint force
};

// One patch of the joined network, in its order (the quads with a grid in layout order, then the
// generalised patches): what it stood on and where it stands before the joining (`last`: a quad's
// deployment end, a generalised patch's own simulated equilibrium; nullptr or !reached: none).
struct JoiningPart {
  int id = 0;
  const rods::RodNetwork* network = nullptr;
  const rods::SimulationRun* last = nullptr;
  bool reached = false;
};
JoiningRun joinDeployed(const RunState& state, const std::vector<JoiningPart>& parts,
                        const rods::DeploymentOptions& options);

// RMS distance (m) between two states' points, rod by rod and vertex by vertex; -1 when their
// shapes differ.
double contactRmsM(const std::vector<std::vector<Eigen::Vector3d>>& a,
                   const std::vector<std::vector<Eigen::Vector3d>>& b);

// One step of a path in report.json: t, convergence, energy, stresses, forces, crossing angles.
nlohmann::json stepJson(const rods::DeploymentStep& step);

// A path's totals in report.json (a patch's path and the joining alike): completed, timed_out,
// steps, iterations, seconds, snaps, jammed_steps, peak_t, peak_stress_ratio, end_stress_ratio.
nlohmann::json pathTotalsJson(const rods::DeploymentResult& result);

// report.json deployment.joined.
nlohmann::json joiningJson(const JoiningRun& run);

}  // namespace egg::pipeline
