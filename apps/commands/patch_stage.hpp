#pragma once
// The per-patch stages of `egg run`: the EGG solve of every patch (Chapter 2 per patch, 3.3) and
// the rod simulation of its grid (Section 2.5), with their report entries and files.
#include "apps/commands/patching_stage.hpp"
#include "apps/commands/scene.hpp"
#include "core/egg/solve_patch.hpp"
#include "core/rods/simulation.hpp"
#include "propagation/chain_tracing.hpp"
#include "propagation/layout_propagation.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
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
  rods::SolverStatus deployedStatus() const { return simulation->deployed.solver.status; }  // needs simulation
};

// The propagation stage (Problem 3.3, Section 3.4.4): the members of every chain of patches,
// C0 at their shared sides. Empty for a single patch, which places its own (2.4.4).
std::optional<propagation::LayoutPropagation> propagateMembers(const PatchingRun& run, const Scene& scene);

// The grid stage: the members of every feasible design traced into its grid (2.4.5-2.4.6). With
// `members` (several patches), the propagated ones, traced in member order so that neighbours'
// member ends coincide (the gaps go to `tracing`); without, each patch places its own (2.4.4),
// patches in parallel. Results do not depend on the thread count. A patch whose grid cannot be
// traced keeps its reason.
std::vector<SolvedPatch> tracePatches(PatchingRun& run, const Scene& scene, const propagation::LayoutPropagation* members = nullptr,
                                      propagation::LayoutTracing* tracing = nullptr);

// report.json propagation{}: c0_max_gap_m, evenness before/after Problem 3.3, per chain and side.
nlohmann::json propagationSection(const propagation::LayoutPropagation& members, const propagation::LayoutTracing& tracing);

// Supports along the design boundary (Section 3.5.3: "supports at anchors and boundary
// connections"): every connection on a side of the layout that no other patch shares (the
// building's walls, the rim of a hole) becomes an anchor too. A multi-patch roof rests on its
// whole boundary, not on a few anchors per patch: the Great Court's 80 m patches fall through
// under their own weight when held at their corners and curvature extrema alone. Shared sides are
// held by the neighbouring grid, not by supports. Returns the anchors added.
int supportDesignBoundary(std::vector<SolvedPatch>& patches, const patching::PatchGraph& graph);

// The patch's rod network with a support at every connection on its four sides that is not an
// anchor already (Section 3.5.2, strategy iv: "a support at every connection on the boundary").
rods::RodNetwork holdEverySide(rods::RodNetwork network, const EggGrid& grid);

// Simulates the grid of every solved patch (with notches and, when the scene asks for
// simulation.compare_without_notches, also without, for RMS1/RMS2 of Section 2.6.2) against the
// design surface, patches in parallel (each simulation then on one thread: results do not depend
// on the thread count). `holdSharedSides`: each patch alone is also held along the sides it
// shares with a neighbour, as the thesis simulated its multi-patch designs (patches apart, on
// supports along all their boundaries: Fig. 3.17, 3.7.1). Without, a patch's lamellas end in free
// cantilevers at a shared side, where in the built structure the neighbour holds them: a 20 m
// cantilever of 25 x 4 cm poplar sags w L^4 / (8 EI) ~ 80 m in linear theory, i.e. it hangs down.
// `patchDone(done, total)` (optional) is called after each patch, from the worker thread that ran it.
void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene, bool holdSharedSides = false,
                     const std::function<void(int, int)>& patchDone = {});

// report.json entries (DESIGN.md "Report").
nlohmann::json patchEntry(const SolvedPatch& patch);
nlohmann::json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene);

// Files of one patch into `dir` (grid.json always; grid.obj, planar.svg and deployed.obj when the
// scene asks for previews).
void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir, const Scene& scene);

}  // namespace egg::app
