#pragma once
// The lamellas along the sides of the patches of a layout (Section 3.5.3): which boundary member
// runs along a side (core/egg/patch_side.hpp has the rule), which sides stand on the design
// boundary, which lamellas two neighbours share, and supports along the design boundary.
// Grids are passed per layout patch id; nullptr marks a patch without a grid (infeasible).
#include "core/egg/grid.hpp"
#include "core/egg/patch_side.hpp"
#include "fabrication/lamella_plan.hpp"
#include "patching/patch_graph.hpp"

#include <array>
#include <vector>

namespace egg::assembly {

// The boundary member along `side` of `grid`, and its rod in rodNetworkFromGrid's network
// (u members are rods 0 .. u-1, v members follow).
struct BoundaryLamella {
  Family family = Family::U;
  int member = 0;  // index in its family
  int rod = 0;
};
BoundaryLamella boundaryLamella(const EggGrid& grid, PatchSide side);

// The connections on the boundary member along `side`, in member order (indices into
// grid.connections, which hold u member i's connections at i * v + j).
std::vector<int> sideConnections(const EggGrid& grid, PatchSide side);

// A segment shared whole by exactly two patches (the sides propagation makes C0).
bool isWholeSharedSide(const patching::Boundary& boundary);

// The sides of `patch` the graph calls free (on the design surface's boundary, not shared with
// another patch): supports stand only there. All four when the graph does not know the patch (a
// single patch without a graph).
std::array<bool, 4> freeSides(const patching::PatchGraph& graph, int patch);

// The boundary lamellas two patches share whole ("adjacent grids can be simply connected along
// their common lamellae", 3.5.3): one lamella that carries the holes of both grids. Sides with a
// patch without a grid are left out.
std::vector<fabrication::SharedBoundary> sharedLamellae(const patching::PatchGraph& graph,
                                                        const std::vector<const EggGrid*>& grids);

// Supports along the design boundary (3.5.3: "supports at anchors and boundary connections"):
// every connection on a free side becomes an anchor ("design boundary support") unless it is one
// already. A multi-patch roof rests on its whole boundary, not on a few anchors per patch.
// Shared sides are held by the neighbouring grid. Returns the anchors added.
int supportDesignBoundary(const patching::PatchGraph& graph, const std::vector<EggGrid*>& grids);

}  // namespace egg::assembly
