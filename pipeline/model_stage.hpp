#pragma once
// The "model" output (issue 38): the whole structure as one 3D model in site coordinates, from
// what the run computed: lamellas along the joined structure's deployed centrelines when that ran,
// else every patch's own deployment, else the grid traced on the design surface (simulation off);
// bolts at the deployed connections; the support blocks of the fabrication stage placed on site.
// Writes model.glb, model.obj, model.3dm (skipped with the reason where Node.js or rhino3dm is
// missing), supports.glb and supports.stl into the run folder and report.json "model".
#include "core/timing.hpp"
#include "export/model.hpp"
#include "pipeline/run_state.hpp"

#include <future>

namespace egg::pipeline {

// The structure model of a run (state after the stages). Throws InvalidInput when the deployed
// state does not match the grids (rod or connection counts).
exporter::StructureModel structureModel(const RunState& state);

// Writing the model outputs in two halves: the constructor builds the model and starts model.3dm
// (a Node.js child that runs for seconds on a large structure: 4.4 s on the Yas) on its own
// thread; finish() writes the other files, waits for the 3dm and fills report.json "model". The
// run writes its patch files and plan in between. Destroyed unfinished (an exception on the
// way), it still waits for the child, so nothing outlives the run's staging folder.
class ModelOutputs {
 public:
  explicit ModelOutputs(RunState& state);
  ~ModelOutputs();
  ModelOutputs(const ModelOutputs&) = delete;
  ModelOutputs& operator=(const ModelOutputs&) = delete;
  void finish();

 private:
  RunState& state_;
  Stopwatch watch_;
  double modelS_ = 0.0;
  exporter::StructureModel model_;
  std::future<double> rhino_;  // node's seconds for model.3dm; invalid when not written
  Stopwatch rhinoWatch_;
};

}  // namespace egg::pipeline
