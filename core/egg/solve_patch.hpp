#pragma once
// One patch, end to end (Chapter 2, summarised in 3.3): patch -> uniqueness check (eta, with
// smoothing when needed) -> distance maps -> Problem 2.3 -> members -> grid with notches and anchors.
#include "core/egg/alpha_bar.hpp"
#include "core/egg/grid.hpp"
#include "core/egg/members.hpp"
#include "core/egg/patch.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/egg/uniqueness.hpp"

#include <array>

namespace egg {

struct EggOptions {
  PatchOptions patch;            // cutting the quad out of the surface
  UniquenessOptions uniqueness;  // eta check and smoothing (2.3.3, 3.4.1)
  DistanceMapOptions maps;       // distance map resolution
  AlphaBarOptions alphaBar;      // Problem 2.3 and the choice of alpha_bar
  MemberOptions members;         // member placement
  GridOptions grid;              // tracing, notches, anchors
  void validate() const;
};

// Wall times (seconds) of the parts of one solve. distanceMaps includes the eta check's K peaks
// and its peak and p1 fields, which run alongside the maps; uniqueness is the solver set-up, the check on
// the maps and any smoothing (with its own checks); sqp is Problem 2.3; tracing builds the grid.
struct EggTimings {
  double patch = 0.0, uniqueness = 0.0, distanceMaps = 0.0, sqp = 0.0, members = 0.0, tracing = 0.0, total = 0.0;
};

struct EggResult {
  Patch patch;                 // the (possibly smoothed) patch the grid was built on
  UniquenessReport uniqueness;
  PatchDistanceMaps maps;
  AlphaBarResult alphaBar;
  FamilyMembers membersU, membersV;
  EggGrid grid;
  EggTimings seconds;
  int propagations = 0;        // distance propagations (fields and paths) over all stages: a load-independent work measure
};

// Throws InfeasiblePatch (the patching stage splits the patch) or InvalidInput with the reason.
EggResult solveEgg(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& corners, const EggOptions& options = {});

}  // namespace egg
