#pragma once
// Bolting neighbouring patches together along their shared boundary lamellas (beyond the paper,
// whose patches were simulated apart, 3.7.1; "adjacent grids can be simply connected along their
// common lamellae", 3.5.3). Their member ends coincide where propagation made the members C0
// (Section 3.4.4). Two lamellas bolted face to face must lie in different layers, so patches swap
// their layers (u on top) where needed: a two-colouring of the patch adjacency. A side whose two
// lamellas still share a layer (an odd cycle of patches) is left unbolted and counted.
// Grids are passed per layout patch id; nullptr marks a patch without a grid.
#include "core/egg/grid.hpp"
#include "core/rods/joined_network.hpp"
#include "patching/patch_graph.hpp"

#include <vector>

namespace egg::assembly {

// Per patch: 1 where its layers are swapped (v members below u) so that neighbours' boundary
// lamellas lie in different layers. Breadth first over the whole shared sides from each
// unvisited patch with a grid; where a cycle disagrees, the first choice stands.
std::vector<char> layerSwaps(const patching::PatchGraph& graph,
                             const std::vector<const EggGrid*>& grids);

struct PatchJoins {
  std::vector<rods::PatchJoin> bolts;  // patch ids are layout patch ids, rods as rodNetworkFromGrid
  int sidesJoined = 0;                 // whole shared sides carrying at least one bolt
  int sidesSkipped = 0;                // whole shared sides whose lamellas fell in one layer
};

// The join bolts: per whole shared side (both patches with a grid, lamellas in different layers),
// each connection on patch A's boundary lamella whose nearest connection on B's lies within
// `toleranceM` metres.
PatchJoins patchJoins(const patching::PatchGraph& graph, const std::vector<const EggGrid*>& grids,
                      const std::vector<char>& swapped, double toleranceM);

}  // namespace egg::assembly
