#pragma once
// From the grid of the EGG solver (core/egg) to the input of the rod simulation (core/rods):
// members become straight lamellas of their planar (cut) length, connections become bolts with
// the notches l = s - s_bar of Section 2.4.5, anchors hold connections on the design surface
// (Section 2.4.6). Kept out of core so that core/egg and core/rods stay independent.
#include "core/egg/grid.hpp"
#include "core/materials/materials.hpp"
#include "core/rods/rod_network.hpp"

namespace egg::app {

struct GridToRodsOptions {
  rods::CrossSection section;   // lamella section w x t
  MaterialProperties material;  // E, G, rho
  bool notches = true;          // false: plain holes (the comparison run without notches)
};

// u members become rods 0 .. u-1 (layer 0), v members rods u .. u+v-1 (layer 1).
rods::RodNetwork rodNetworkFromGrid(const EggGrid& grid, const GridToRodsOptions& options);

}  // namespace egg::app
