#pragma once
// Generalised patches in `egg run` (issue 41, Chapter 4): after the grid stage traced the quad
// grids, the layout's cut-offs (along holes and curved design boundaries) get generalised grids
// (patching/infill.hpp) at the quad grids' member spacing; the simulation stage deploys each one
// on its anchors. report.json: generalised_patches[] (kind, energies, eps_geo, planarisation,
// anchors by what holds them, deviation), and coverage counts them.
#include "pipeline/run_state.hpp"

#include <filesystem>

namespace egg::pipeline {

// Grid stage, when patching.generalised_infill (default: for the workflows' layouts, not a given
// one) and the coverage has cut-offs: designs the
// generalised patches into state.infill, writes report.json's generalised_patches[] and adds them
// to coverage{}. A piece that cannot take a grid is a warning in its entry, not a failure.
void designInfill(RunState& state);

// Simulation stage: each generalised patch deployed alone, held at its anchors, with the scene's
// rod options; its entry gets the deviation from the surface. Non-convergence is a run failure,
// as for a quad patch.
void simulateInfill(RunState& state);

// Per generalised patch with a grid, the folder generalised_G<i>/ below `folder`: lamellas.csv
// (the cut list: every lamella's id, family and layer, length, and its bolt holes at their planar
// positions with the notch each bolt slides along, mm) and planar.svg (the cut layout as bolted on
// the ground, mm). Throws WriteError when a file cannot be written.
void writeInfillFiles(const RunState& state, const std::filesystem::path& folder);

// The members of the generalised patches as polylines on the surface (plan.svg), by family.
struct InfillMemberLine {
  int piece = -1;
  int family = 0;
  std::vector<Eigen::Vector3d> points;
};
std::vector<InfillMemberLine> infillMemberLines(const RunState& state);

}  // namespace egg::pipeline
