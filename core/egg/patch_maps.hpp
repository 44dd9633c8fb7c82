#pragma once
// Surface distance maps of a patch (Section 2.4.2): D_u(u1, u2) and D_v(v1, v2) from the exact
// geodesic engine, measured inside the patch mesh, with the boundary parameters running at
// constant speed along the geodesic sides (criterion ii).
#include "core/egg/distance_map.hpp"
#include "core/egg/map_proxy.hpp"
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
  // It applies when proxyVertices = 0; otherwise the rows are the proxy's, or those of a patch no
  // larger than the proxy, which is its own proxy, and proxyToleranceRelative applies (such a
  // patch keeps its own solver, i.e. the patch's saddle tolerance, not proxySaddleAngleTolerance).
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
  // Maps on a coarse proxy of the patch (map_proxy.hpp) when the patch mesh has more vertices
  // than this; 0 = always on the patch itself (bit-identical to the maps without a proxy). Scene
  // key grid.map_proxy_vertices. The sides (maps.sides, the planar quad's), alpha and the eta
  // check stay on the fine patch, and member tracing restores criterion (i) there; the maps steer
  // alpha_bar, F, C and the tracing guesses (Section 2.4.2).
  // Default 600, measured by `egg bench grid --repeats 3 --map-proxy 0,300,400,600,800,1000`
  // (6 m bump, 1.1k/2.0k/3.4k-vertex patches; reference: exact maps on the patch; the fine
  // mesh's own noise, max |D_u - D_v| of the exact maps on this symmetric patch, is 8.3e-4/
  // 8.5e-4/8.4e-4 m): max |D - D_exact| 2.4/2.7/2.6e-3 m at 300, 1.7/1.4/1.8e-3 at 400,
  // 1.25/1.07/1.0e-3 at 600, 7.4/8.1/7.0e-4 at 800, 7.0/6.1/6.1e-4 at 1000 (fine adaptive rows
  // at 1e-4: 5.7/2.7/1.9e-4). CPU of the whole solve at 3.4k: 1.39 s on the patch, 0.44/0.44/
  // 0.48/0.51/0.51 s on the proxies (34-36 proxy fields, ~10 ms for the decimation). 600 is where
  // the map error reaches the fine mesh's noise; alpha_bar and eta do not change at any size; F
  // moves by 0.7-1.0e-3 m at 600. Members move by 3-6 cm at 600 (0.4-13 cm over all rows; 1-2 mm
  // with the fine adaptive maps): the extrema of C and of its curvature, and which of them win,
  // follow map errors of this size (members.hpp); the u/v member mismatch on the symmetric patch
  // stays 3-5 cm at 1.1k-2.0k and 4.6 mm at 3.4k.
  int proxyVertices = 600;
  // The adaptive rows' tolerance on the proxy (relative, as toleranceRelative). 1e-3: on the
  // bench bump every check passes (9 initial rows + 8 checks per family) and the error is within
  // 2 % of that of exact rows on the proxy; 3e-4 spends 44-68 fields for no gain (the proxy's own
  // noise is ~1e-3 m), and 3e-3 misses kinks of the 2 m bump's maps (1.2e-2 m against 2.2e-3).
  double proxyToleranceRelative = 1e-3;
  // Near-flat saddle tolerance of the proxy's geodesic solver (DistanceSolverOptions). 3e-3
  // instead of the fine default 7e-4: 20-35 % less CPU for the proxy maps on the 1 m bump, map
  // errors unchanged to 3 digits there and on the 2 m bump (the proxy's own error is ~1e-3 m).
  double proxySaddleAngleTolerance = 3e-3;
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
// True when the maps are read on a proxy of the patch (options.proxyVertices, map_proxy.hpp).
bool mapsUseProxy(const Patch& patch, const DistanceMapOptions& options);
// The proxy solver's options: the patch solver's, with options.proxySaddleAngleTolerance.
geodesic::DistanceSolverOptions proxySolverOptions(const geodesic::DistanceSolver& solver, const DistanceMapOptions& options);
// The maps on a given proxy of a patch (proxySolver built on proxy.patch.mesh), so the eta check
// can share it (solveEgg).
PatchDistanceMaps computeDistanceMaps(const MapProxy& proxy, const geodesic::DistanceSolver& proxySolver,
                                      const DistanceMapOptions& options);

}  // namespace egg
