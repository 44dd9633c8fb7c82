#pragma once
// Surface distance maps of a patch (Section 2.4.2): D_u(u1, u2) and D_v(v1, v2) from the exact
// geodesic engine, measured inside the patch mesh, with the boundary parameters running at
// constant speed along the geodesic sides (criterion ii).
#include "core/egg/distance_map.hpp"
#include "core/egg/patch.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <utility>

namespace egg {

struct DistanceMapOptions {
  int resolution = 100;  // samples per side (the thesis uses ~100 x 100)
  void validate() const; // throws InvalidInput naming the field
};

// The patch side a family's start side (end = false) or end side runs along, and whether the
// family's parameter runs against the side's own direction (corner k -> k+1):
// u runs c0->c3 (side 3 backwards) to c1->c2 (side 1); v runs c0->c1 (side 0) to c3->c2 (side 2 backwards).
std::pair<int, bool> familySide(Family family, bool end);

// The boundary point at parameter x in [0,1] on the family's start side (end = false) or end side.
SurfacePoint familyBoundaryPoint(const Patch& patch, Family family, bool end, double x);
// Spatial length of that side.
double familySideLength(const Patch& patch, Family family, bool end);

// Both maps plus sides, diagonals and the corner angle alpha, ready for solveAlphaBar. One batch
// call per family (n sources on its start side, targets the n samples of its end side); the two
// run concurrently.
PatchDistanceMaps computeDistanceMaps(const Patch& patch, const geodesic::DistanceSolver& solver,
                                      const DistanceMapOptions& options = {});

}  // namespace egg
