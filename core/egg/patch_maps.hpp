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
  // Adaptive rows (map_refinement.hpp): exact source fields only at some start-side samples, the
  // other rows by cubic interpolation in x1, refined where a check row misses by more than this
  // times the family's shorter side (relative, so a 0.9 m and a 40 m patch get the same relative
  // accuracy); 0 = an exact field at every sample. Scene key grid.map_tolerance_relative.
  // Default 1e-4: the accuracy bar of the geodesic engine (distance_solver.hpp), and below the
  // noise of the exact polyhedral maps themselves: on the symmetric bench bump the exact D_u and
  // D_v, equal on the smooth surface, differ by 1.4e-4 (1.1k-3.4k vertices) to 3.7e-4 (0.6k) of
  // the side. `egg bench grid --map-tolerance 2e-5,5e-5,1e-4,1.5e-4,3e-4` (6 m bump, 0.6k/1.1k/
  // 2.0k/3.4k vertices, saddle tolerance 1e-4) at 1e-4: 145/77/66/66 of 200 fields, CPU time of
  // the solve 0.71/0.50/0.41/0.37 of the exact maps', max |D - D_exact| 5.1/5.7/2.7/1.9e-4 m
  // (<= 0.95e-4 of the side), cladding functions within 1.5/4.3/1.8/0.6e-4 m, alpha_bar and eta
  // unchanged. 1.5e-4 saves fields on the two coarse meshes only (118/74); 3e-4 reaches the
  // 0.6k mesh's noise (1.9e-3 m); 5e-5 costs 200/166/76/71 fields. The bump scaled to a 0.86 m
  // patch: 101 fields, 1.0e-4 of the side. eta reads exact fields, not the maps (uniqueness.hpp).
  double toleranceRelative = 1e-4;
  int initialNodes = 9;  // start-side samples with exact fields before refinement (>= 2)
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

// Both maps plus sides, diagonals and the corner angle alpha, ready for solveAlphaBar. Per family,
// batch calls with sources on its start side and the n samples of its end side as targets (all n
// sources at once when toleranceRelative = 0, else the rounds of the adaptive refinement); the two
// families run concurrently.
PatchDistanceMaps computeDistanceMaps(const Patch& patch, const geodesic::DistanceSolver& solver,
                                      const DistanceMapOptions& options = {});

}  // namespace egg
