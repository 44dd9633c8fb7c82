#pragma once
// The "model" output (issue 38): the whole structure as one 3D model in site coordinates, from
// what the run computed: lamellas along the joined structure's deployed centrelines when that ran,
// else every patch's own deployment, else the grid traced on the design surface (simulation off);
// bolts at the deployed connections; the support blocks of the fabrication stage placed on site.
// Writes model.glb, model.obj, model.3dm (skipped with the reason where Node.js or rhino3dm is
// missing), supports.glb and supports.stl into the run folder and report.json "model".
#include "export/model.hpp"
#include "pipeline/run_state.hpp"

namespace egg::pipeline {

// The structure model of a run (state after the stages). Throws InvalidInput when the deployed
// state does not match the grids (rod or connection counts).
exporter::StructureModel structureModel(const RunState& state);

void writeModelOutputs(RunState& state);

}  // namespace egg::pipeline
