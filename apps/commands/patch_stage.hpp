#pragma once
// The per-patch stages of `egg run`: the EGG solve of every patch (Chapter 2 per patch, 3.3) and
// the rod simulation of its grid (Section 2.5), with their report entries and files.
#include "apps/commands/scene.hpp"
#include "core/egg/solve_patch.hpp"
#include "core/rods/simulation.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace egg::app {

struct SolvedPatch {
  int id = 0;
  std::array<Eigen::Vector3d, 4> corners;
  std::optional<EggResult> egg;  // empty when the patch is infeasible
  std::string failure;           // why not (InfeasiblePatch / SolverFailure message)
  std::optional<rods::SimulationResult> simulation;
  std::string simulationFailure;  // why the simulation could not run (an error, not non-convergence)
};

// The EGG solver's options as the scene sets them (eta_max, slope bounds, map resolution,
// alpha_bar, member count, lamella width).
EggOptions eggOptionsFromScene(const Scene& scene);

// Solves every patch of the scene's layout. A patch the EGG criteria reject (InfeasiblePatch,
// SolverFailure) is kept with its reason; input errors propagate.
std::vector<SolvedPatch> solvePatches(const TriMesh& surface, const Scene& scene);

// Simulates the grid of every solved patch (with notches and, when the scene wants notches,
// also without, for RMS1/RMS2 of Section 2.6.2) against the design surface.
void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene);

// report.json entries (DESIGN.md "Report").
nlohmann::json patchEntry(const SolvedPatch& patch);
nlohmann::json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene);

// Files of one patch into `dir` (grid.json always; grid.obj, planar.svg and deployed.obj when the
// scene asks for previews).
void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir, const Scene& scene);

}  // namespace egg::app
