#pragma once
// The bolted flat grid a deployment starts from (issue 42, thesis 2.3.1: "the planar grid is
// deployed ... as the planar angle approaches the spatial angle"): every lamella straight where
// the planar grid puts it, every bolt where the planar members cross, every support at its flat
// place, and the straight support path from there to the deployed supports.
#include "core/egg/grid.hpp"
#include "core/rods/deployment.hpp"
#include "core/rods/rod_network.hpp"

namespace egg::assembly {

struct FlatGrid {
  rods::RodNetwork network;     // the deployed network's rods, bolts and anchors, laid flat
  rods::SupportState flat;      // the anchors on the flat grid
  rods::SupportState deployed;  // the anchors of the deployed network
  double placementRmsM = 0.0;   // the rigid placement's fit over the connections (m)
  // Largest distance, over the bolts, between the two straight lamellas' points where the bolt
  // sits (its flat position along each): how far the flat layout misses assembling without
  // strain, the planar grid's crossings against straight members of the rods' lengths (m).
  double boltMisfitMaxM = 0.0;
  int boltMisfitMaxConnection = -1;
};

// `deployed` is rodNetworkFromGrid(grid) (u members first, then v), possibly with more anchors
// (holdEverySide). The flat grid is placed where it best fits the deployed connections (a rigid
// motion, Kabsch), with its layer 1 side towards the deployed normals: a weightless deployment
// does not depend on that placement, which only sets how far the supports travel. Throws
// InvalidInput when the network does not match the grid.
FlatGrid flatGrid(const EggGrid& grid, const rods::RodNetwork& deployed);

}  // namespace egg::assembly
