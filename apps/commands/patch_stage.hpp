#pragma once
// The per-patch stages of `egg run`: the EGG solve of every patch (Chapter 2 per patch, 3.3) and
// the rod simulation of its grid (Section 2.5), with their report entries and files.
#include "apps/commands/patching_stage.hpp"
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
  std::array<int, 4> cornerIds{};             // corners in the layout (patches.json)
  std::array<Eigen::Vector3d, 4> corners;     // snapped onto the surface
  std::optional<EggResult> egg;  // empty when the patch is infeasible
  std::string failure;           // why not (InfeasiblePatch / SolverFailure message)
  std::optional<rods::SimulationResult> simulation;
  std::string simulationFailure;  // why the simulation could not run (an error, not non-convergence)
};

// The grid stage: members placed on every feasible design (Section 2.4.4, per patch until
// propagation exists) and traced into its grid (2.4.5-2.4.6), patches in parallel (results do not
// depend on the thread count). A patch whose grid cannot be traced keeps its reason.
std::vector<SolvedPatch> tracePatches(PatchingRun& run, const Scene& scene);

// Supports along the design boundary (Section 3.5.3: "supports at anchors and boundary
// connections"): every connection on a side of the layout that no other patch shares (the
// building's walls, the rim of a hole) becomes an anchor too. A multi-patch roof rests on its
// whole boundary, not on a few anchors per patch: the Great Court's 80 m patches fall through
// under their own weight when held at their corners and curvature extrema alone. Shared sides are
// held by the neighbouring grid, not by supports. Returns the anchors added.
int supportDesignBoundary(std::vector<SolvedPatch>& patches, const patching::PatchGraph& graph);

// Simulates the grid of every solved patch (with notches and, when the scene wants notches,
// also without, for RMS1/RMS2 of Section 2.6.2) against the design surface, patches in parallel
// (each simulation then on one thread: results do not depend on the thread count).
void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene);

// report.json entries (DESIGN.md "Report").
nlohmann::json patchEntry(const SolvedPatch& patch);
nlohmann::json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene);

// Files of one patch into `dir` (grid.json always; grid.obj, planar.svg and deployed.obj when the
// scene asks for previews).
void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir, const Scene& scene);

}  // namespace egg::app
