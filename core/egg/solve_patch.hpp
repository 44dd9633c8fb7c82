#pragma once
// One patch, end to end (Chapter 2, summarised in 3.3): patch -> uniqueness check (eta, with
// smoothing when needed) -> distance maps -> Problem 2.3 -> members -> grid with notches and
// anchors. It is makePatch + the design step + the grid step of patch_design.hpp, which the
// multi-patch flow calls separately.
#include "core/egg/patch_design.hpp"

#include <array>

namespace egg {

struct EggResult {
  Patch patch;  // the (possibly smoothed) patch the grid was built on
  UniquenessReport uniqueness;
  PatchDistanceMaps maps;
  AlphaBarResult alphaBar;
  FamilyMembers membersU, membersV;
  EggGrid grid;
  EggTimings seconds;
  int propagations = 0;  // distance propagations (fields and paths) over all stages: a
                         // load-independent work measure
};

// Throws InfeasiblePatch (the patching stage splits the patch) or InvalidInput with the reason.
EggResult solveEgg(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& corners,
                   const EggOptions& options = {});

}  // namespace egg
