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
  // noise of the exact polyhedral maps themselves (bench figures: docs/measurements.md). eta reads
  // exact fields, not the maps (uniqueness.hpp).
  double toleranceRelative = 1e-4;
  int initialNodes = 9;  // start-side samples with exact fields before refinement (>= 2)
  // Maps on a coarse proxy of the patch (map_proxy.hpp) when the patch mesh has more vertices
  // than this; 0 = always on the patch itself (bit-identical to the maps without a proxy). Scene
  // key grid.map_proxy_vertices. The sides (maps.sides, the planar quad's), alpha and the eta
  // check stay on the fine patch, and member tracing restores criterion (i) there; the maps steer
  // alpha_bar, F, C and the tracing guesses (Section 2.4.2).
  // Default 600: where the map error on the bench bump reaches the fine mesh's own noise (~1e-3 m)
  // at about a third of the CPU of maps on the patch; alpha_bar and eta do not change, members
  // move by a few cm (`egg bench grid --map-proxy`; figures: docs/measurements.md).
  int proxyVertices = 600;
  // The adaptive rows' tolerance on the proxy (relative, as toleranceRelative). 1e-3: the
  // proxy's own noise; tighter spends fields for no gain, looser misses kinks of the maps.
  double proxyToleranceRelative = 1e-3;
  // Near-flat saddle tolerance of the proxy's geodesic solver (DistanceSolverOptions). 3e-3
  // instead of the fine default 7e-4: less CPU, map errors unchanged (the proxy's own error is
  // ~1e-3 m). Figures for both: docs/measurements.md.
  double proxySaddleAngleTolerance = 3e-3;
  void validate() const;  // throws InvalidInput naming the field
};

// The patch side a family's start side (end = false) or end side runs along, and whether the
// family's parameter runs against the side's own direction (corner k -> k+1):
// u runs c0->c3 (side 3 backwards) to c1->c2 (side 1); v runs c0->c1 (side 0) to c3->c2 (side 2
// backwards).
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
geodesic::DistanceSolverOptions proxySolverOptions(const geodesic::DistanceSolver& solver,
                                                   const DistanceMapOptions& options);
// The maps on a given proxy of a patch (proxySolver built on proxy.patch.mesh), so the eta check
// can share it (solveEgg).
PatchDistanceMaps computeDistanceMaps(const MapProxy& proxy,
                                      const geodesic::DistanceSolver& proxySolver,
                                      const DistanceMapOptions& options);

}  // namespace egg
