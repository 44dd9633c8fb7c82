#pragma once
// The patching and design stages of `egg run` (Sections 3.3, 3.4): the scene's layout (given, or
// split by Workflow 1), every patch designed on it, the patch graph and the coverage; with their
// report entries and patches.json.
#include "patching/patch_graph.hpp"
#include "patching/workflow1.hpp"
#include "patching/workflow2.hpp"
#include "pipeline/scene.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace egg::pipeline {

struct RunState;

struct PatchingRun {
  std::string workflow;  // "given", "1" or "2"
  std::optional<patching::Workflow2Layout>
      initial;                    // Workflow 2's proposal, before Workflow 1's splits
  patching::LayoutDesign layout;  // final layout and each patch's design
  patching::PatchGraph graph;
  patching::Coverage coverage;
  double layoutSeconds =
      0.0;  // corners, sides, splits, layout mesh (the patching stage's own time)
  double designSeconds = 0.0;  // the patch designs, trial and final (the design stage)
};

// Throws InvalidInput naming the scene file and field (corners off the surface, bad indices).
PatchingRun runPatching(const TriMesh& surface, const geodesic::DistanceSolver& surfaceSolver,
                        const Scene& scene);

// report.json: patching{}, boundaries[], t_junctions[], chains[], coverage{}.
void addPatchingReport(const PatchingRun& run, nlohmann::json& report);

// plan.svg (patching/site_plan.hpp: the architect's plan, with the grids' members and the
// supports when those stages ran) and curvature.svg (patching/plan_svg.hpp: the K map, K peaks and
// injectivity circles, cut-offs). report: labels_left_out, peaks[], seconds.
void writePlan(const RunState& state, const std::filesystem::path& folder, nlohmann::json& report);

// patches.json: corners, sides (polylines), patches, boundaries, T-junctions, chains, splits.
void writePatchesJson(const PatchingRun& run, const std::filesystem::path& file);

// Stage table row: the layout and every patch's design (records "patching" and "design": Workflow
// 1 designs the patches while it splits them).
void patchingStage(RunState& state);
}  // namespace egg::pipeline
