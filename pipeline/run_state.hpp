#pragma once
// What one `egg run` has computed so far: the stages of the stage table (stages.hpp) read and
// fill it in data-flow order (docs/architecture.md "Data flow"). Each stage's own work is a free
// function of its file taking plain inputs; the state only carries results between them.
#include "assembly/generalised_patch.hpp"
#include "core/egg/solve_patch.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/rods/joined_network.hpp"
#include "core/rods/simulation.hpp"
#include "fabrication/fabricate.hpp"
#include "patching/infill.hpp"
#include "pipeline/patching_stage.hpp"
#include "pipeline/report.hpp"
#include "pipeline/scene.hpp"
#include "pipeline/surface_stage.hpp"
#include "propagation/chain_tracing.hpp"
#include "propagation/layout_propagation.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

// One patch of the final layout through the grid and simulation stages.
struct SolvedPatch {
  int id = 0;
  std::array<int, 4> cornerIds{};          // corners in the layout (patches.json)
  std::array<Eigen::Vector3d, 4> corners;  // snapped onto the surface
  std::optional<EggResult> egg;            // empty when the patch is infeasible or not traced
  std::string failure;                     // why not (InfeasiblePatch / SolverFailure message)
  std::optional<rods::SimulationResult> simulation;
  std::string
      simulationFailure;  // why the simulation could not run (an error, not non-convergence)
  std::optional<rods::RodNetwork> network;  // what was simulated (the verification stage's input)
  rods::SolverStatus deployedStatus() const {
    return simulation->deployed.solver.status;
  }  // needs simulation
};

// Per layout patch id, the traced grid or nullptr (the assembly library's input).
std::vector<const EggGrid*> gridsOf(const std::vector<SolvedPatch>& patches);
std::vector<EggGrid*> editableGridsOf(std::vector<SolvedPatch>& patches);
// Patches with a traced grid.
int solvedCount(const std::vector<SolvedPatch>& patches);

struct RunState {
  RunState(const Scene& scene, std::filesystem::path staging,
           std::function<void(const std::string&, double)> progress);

  const Scene& scene;
  const std::filesystem::path staging;  // the run folder's staging folder: every file goes below it
  RunReport report;
  std::vector<std::string> failures;  // exit code 1, in the order the stages found them
  std::function<void(const std::string& stage, double fraction)> progress;  // never empty

  std::optional<LoadedSurface> surface;                   // surface
  std::optional<geodesic::DistanceSolver> surfaceSolver;  // patching (and the plan's circles)
  std::optional<PatchingRun> patching;                    // patching, design
  std::optional<propagation::LayoutPropagation> members;  // propagation (several patches)
  propagation::LayoutTracing tracing;                     // grid, with propagated members
  std::vector<SolvedPatch> patches;           // patching (ids, corners), grid, simulation
  std::optional<rods::SimulationRun> joined;  // simulation: the joined structure's deployment
  std::optional<rods::JoinedNetwork> joinedNetwork;          // simulation: what `joined` deployed
  std::optional<fabrication::FabricationResult> fabricated;  // fabrication (the model's supports)
  // grid: generalised patches in the quad layout's cut-offs; simulation: each one deployed alone
  // (one entry per piece, empty where it has no grid or the simulation did not run).
  std::optional<patching::InfillResult> infill;
  // The pieces with a grid as patches numbered after the quads (P<n + piece>), in piece order.
  std::vector<assembly::GeneralisedPatch> generalised;
  std::vector<std::optional<rods::SimulationResult>> infillSimulations;  // per piece
};

}  // namespace egg::pipeline
