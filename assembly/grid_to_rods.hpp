#pragma once
// From the grid of the EGG solver (core/egg) to the input of the rod simulation (core/rods):
// members become straight lamellas of their planar (cut) length, connections become bolts with
// the notches l = s - s_bar of Section 2.4.5, anchors hold connections on the design surface
// (Section 2.4.6). Kept out of core so that core/egg and core/rods stay independent.
#include "core/egg/grid.hpp"
#include "core/materials/materials.hpp"
#include "core/rods/rod_network.hpp"

namespace egg::assembly {

struct GridToRodsOptions {
  rods::CrossSection section;   // lamella section w x t
  MaterialProperties material;  // E, G, rho
  bool notches = true;          // false: plain holes (the comparison run without notches)
  // u members on top (layer 1) and v below: a joined structure swaps every other patch so that
  // two neighbours' boundary lamellas along a shared side lie face to face (3.5.3).
  bool swapLayers = false;
};

// u members become rods 0 .. u-1 (layer 0), v members rods u .. u+v-1 (layer 1); swapLayers
// exchanges the layers.
rods::RodNetwork rodNetworkFromGrid(const EggGrid& grid, const GridToRodsOptions& options);

// `network` (of `grid`) with a support at every connection on the four sides that is not an
// anchor already (Section 3.5.2, strategy iv: "a support at every connection on the boundary").
rods::RodNetwork holdEverySide(rods::RodNetwork network, const EggGrid& grid);

}  // namespace egg::assembly
