#pragma once
// Several patches as one structure (beyond the paper, which simulated each patch alone and named
// the joined structure future work, 3.7.1): the patches' rod networks side by side, plus bolts
// between the shared boundary lamellas of adjacent patches ("adjacent grids can be simply
// connected along their common lamellae", 3.5.3). The joined network is simulated like any other.
#include "core/rods/rod_network.hpp"
#include "core/rods/simulation.hpp"

#include <vector>

namespace egg::rods {

// A bolt through the boundary lamella rodA of patch patchA and rodB of patch patchB. The two
// lamellas lie face to face, so they must be in different layers (one on top of the other); the
// bolt is a plain hole (boundary members have no notches, 3.5.3).
struct PatchJoin {
  int patchA = -1;
  int rodA = -1;
  double sAM = 0.0;
  int patchB = -1;
  int rodB = -1;
  double sBM = 0.0;
};

struct JoinedNetwork {
  RodNetwork network;
  std::vector<int> firstRod;  // per patch: index of its first rod in `network`
  // The patches' own connections come first, in patch order; the joins follow, from this index.
  int firstJoin = 0;
};

// Throws InvalidInput naming the join (bad patch/rod index, position outside the rod, lamellas in
// the same layer) or the patch whose network is invalid.
JoinedNetwork joinPatches(const std::vector<RodNetwork>& patches,
                          const std::vector<PatchJoin>& joins);

// Both ways of simulating a multi-patch grid: every patch alone (as the paper did) and the joined
// structure. The pooled RMSE of the patch-by-patch runs is over all their points.
struct JoinedSimulation {
  std::vector<SimulationRun> perPatch;
  DeviationStats patchByPatch;  // pooled over all patches (nrmse with options.scaleFactor)
  SimulationRun joined;
  bool converged = false;  // every run converged
};

JoinedSimulation simulateJoinedPatches(const std::vector<RodNetwork>& patches,
                                       const std::vector<PatchJoin>& joins, const TriMesh& surface,
                                       const SimulationOptions& options);

}  // namespace egg::rods
