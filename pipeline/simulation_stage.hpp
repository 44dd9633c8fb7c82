#pragma once
// The simulation stage (Section 2.5): every solved patch's grid deployed with discrete elastic
// rods against the design surface, patch by patch, then the joined structure
// (joined_simulation.hpp), with the report's figures and deployed.svg.
#include "assembly/grid_to_rods.hpp"
#include "core/rods/simulation.hpp"
#include "pipeline/run_state.hpp"
#include "pipeline/scene.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace egg::pipeline {

// The rod solver's options as the scene sets them (notches, gravity, fastened bolts, friction,
// Newton tolerance, time limit), with the error history of the report: the one translation of the
// scene's simulation keys, for the patch-by-patch and the joined runs.
rods::SimulationOptions rodsOptions(const Scene& scene);
// The lamella's section and material for the rod network, notches on.
assembly::GridToRodsOptions gridToRodsOptions(const Scene& scene);

// Simulates the grid of every solved patch (with notches and, when the scene asks for
// simulation.compare_without_notches, also without, for RMS1/RMS2 of Section 2.6.2) against the
// design surface, patches in parallel (each simulation then on one thread: results do not depend
// on the thread count). `holdSharedSides`: each patch alone is also held along the sides it
// shares with a neighbour, as the thesis simulated its multi-patch designs (patches apart, on
// supports along all their boundaries: Fig. 3.17, 3.7.1). Without, a patch's lamellas end in free
// cantilevers at a shared side, where in the built structure the neighbour holds them: a 20 m
// cantilever of 25 x 4 cm poplar sags w L^4 / (8 EI) ~ 80 m in linear theory, i.e. it hangs down.
// `patchDone(done, total)` (optional) is called after each patch, from the worker thread that ran
// it.
void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene,
                     bool holdSharedSides = false,
                     const std::function<void(int, int)>& patchDone = {});

// Where a solve's wall time went (report.json `phases_s`, per patch and for the joined run).
nlohmann::json phasesJson(const rods::SolverPhases& phases);

// report.json simulation{} of the patch-by-patch runs (errors pooled over all patches).
nlohmann::json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene);

// Stage table row: the scene may switch it off; nothing to deploy without a solved grid.
std::string simulationDisabled(const Scene& scene);
std::string simulationSkipReason(const RunState& state);
void simulationStage(RunState& state);

}  // namespace egg::pipeline
