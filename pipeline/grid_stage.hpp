#pragma once
// The grid stage (Sections 2.4.5-2.4.6): the members of every feasible design traced into its
// grid, with each patch's report entry and files.
#include "pipeline/patching_stage.hpp"
#include "pipeline/run_state.hpp"
#include "pipeline/scene.hpp"
#include "propagation/chain_tracing.hpp"
#include "propagation/layout_propagation.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace egg::pipeline {

// One entry per patch of the layout, with its id, corners and, for an infeasible design, why.
std::vector<SolvedPatch> layoutPatches(const PatchingRun& run);

// Traces the grid of every feasible design into `patches` (from layoutPatches). With `members`
// (several patches), the propagated ones, traced in member order so that neighbours' member ends
// coincide (the gaps go to `tracing`); without, each patch places its own (2.4.4), patches in
// parallel. Results do not depend on the thread count. A patch whose grid cannot be traced keeps
// its reason.
void tracePatches(PatchingRun& run, std::vector<SolvedPatch>& patches,
                  const propagation::LayoutPropagation* members = nullptr,
                  propagation::LayoutTracing* tracing = nullptr);

// report.json entry of one patch (docs/architecture.md "Report").
nlohmann::json patchEntry(const SolvedPatch& patch);

// report.json "patches" (the design's figures where no grid was traced, F_u and F_v where one
// was) and the run's failures of the patches that have no grid. The anchors counted are the
// grid's own (corners, curvature extrema), before the simulation adds supports.
void addPatchEntries(RunState& state);

// Files of one patch into `dir` (grid.json always; grid.obj, planar.svg and deployed.obj when the
// scene asks for previews).
void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir,
                     const Scene& scene);

// Stage table row: nothing to trace without a feasible design.
std::string gridSkipReason(const RunState& state);
void gridStage(RunState& state);

}  // namespace egg::pipeline
