#include "pipeline/stages.hpp"

#include "pipeline/deployment_stage.hpp"
#include "pipeline/fabrication_stage.hpp"
#include "pipeline/grid_stage.hpp"
#include "pipeline/patching_stage.hpp"
#include "pipeline/propagation_stage.hpp"
#include "pipeline/simulation_stage.hpp"
#include "pipeline/surface_stage.hpp"
#include "pipeline/verification_stage.hpp"

#include <algorithm>

namespace egg::pipeline {

const char* toString(StageId stage) {
  switch (stage) {
    case StageId::Surface: return "surface";
    case StageId::Patching: return "patching";
    case StageId::Design: return "design";
    case StageId::Propagation: return "propagation";
    case StageId::Grid: return "grid";
    case StageId::Simulation: return "simulation";
    case StageId::Fabrication: return "fabrication";
    case StageId::Verification: return "verification";
    case StageId::Deployment: return "deployment";
  }
  return "unknown";
}

const std::vector<StageId>& allStages() {
  static const std::vector<StageId> stages{
      StageId::Surface,     StageId::Patching,     StageId::Design,
      StageId::Propagation, StageId::Grid,         StageId::Simulation,
      StageId::Fabrication, StageId::Verification, StageId::Deployment};
  return stages;
}

const std::vector<Stage>& stageTable() {
  using S = StageId;
  static const std::vector<Stage> table{
      {S::Surface, {}, 0.0, nullptr, nullptr, surfaceStage},
      {S::Patching, {S::Surface}, 0.1, nullptr, nullptr, patchingStage},
      {S::Design, {S::Patching}, 0.1, nullptr, nullptr, nullptr},
      {S::Propagation, {S::Design}, 0.25, nullptr, propagationSkipReason, propagationStage},
      {S::Grid,
       {S::Design, S::Propagation},
       0.3,
       nullptr,
       gridSkipReason,
       gridStage,
       addPatchEntries},
      {S::Simulation, {S::Grid}, 0.6, simulationDisabled, simulationSkipReason, simulationStage},
      // Stresses come from the deployed centrelines when the simulation ran, else from the design.
      {S::Fabrication,
       {S::Grid},
       0.8,
       fabricationDisabled,
       fabricationSkipReason,
       fabricationStage},
      // The FE check of the deployed structure with CalculiX (docs/verification.md).
      {S::Verification, {S::Simulation}, 0.9, nullptr, verificationSkipReason, verificationStage},
      // The path from the flat grid to the deployed one, patch by patch (docs/deployment.md).
      {S::Deployment, {S::Simulation}, 0.95, nullptr, deploymentSkipReason, deploymentStage},
  };
  return table;
}

const std::vector<Output>& outputTable() {
  using S = StageId;
  static const std::vector<Output> table{
      {"report",
       {S::Grid, S::Simulation},
       "report.json, report.html, deployed.svg, elevations.svg, patch_NNN/grid.json"},
      {"previews",
       {S::Grid, S::Simulation},
       "report.html's PNG previews, patch_NNN/grid.obj, planar.svg, deployed.obj"},
      {"plan", {S::Design}, "patches.json, plan.svg, curvature.svg"},
      {"cut_files", {S::Fabrication}, "cut/sheet_NN.svg, .dxf, sheets.pdf, bom.csv"},
      {"stickers", {S::Fabrication}, "cut/stickers_NN.svg, .dxf, stickers.pdf"},
      {"supports", {S::Fabrication}, "supports/supports.csv, supports/support_NNN.stl"},
      {"deployment",
       {S::Deployment},
       "deployment.csv, deployment.svg, deployment.glb (the path from the flat grid)"},
      {"fem", {S::Verification}, "fem/model.inp, fem/<case>.inp, .dat, .frd, fem/buckle.*"},
      // The supports come from the fabrication stage (none when it is off).
      {"model",
       {S::Grid, S::Simulation, S::Fabrication},
       "model.glb, model.3dm, model.obj, supports.glb, supports.stl"},
  };
  return table;
}

namespace {

bool reaches(StageId from, StageId target) {
  if (from == target) return true;
  const auto& table = stageTable();
  const auto row =
      std::find_if(table.begin(), table.end(), [&](const Stage& s) { return s.id == from; });
  return std::any_of(row->needs.begin(), row->needs.end(),
                     [&](StageId need) { return reaches(need, target); });
}

}  // namespace

bool stageNeeded(StageId stage, const std::vector<std::string>& outputs) {
  for (const Output& output : outputTable()) {
    if (std::find(outputs.begin(), outputs.end(), output.name) == outputs.end()) continue;
    for (StageId need : output.needs)
      if (reaches(need, stage)) return true;
  }
  return false;
}

}  // namespace egg::pipeline
