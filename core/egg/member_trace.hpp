#pragma once
// Tracing one inner member so that criterion (i) holds exactly (Section 2.4.5): the end parameter
// x2 moves until the shortest geodesic from start(x1) to end(x2) is as long as the planar segment.
//
// The cladding function's x2 is exact only up to the interpolation of the distance maps. The
// geodesic to the guess is traced once; its faces unfold into a planar strip where the geodesic is
// a straight line, and the distance to any end point on the same boundary edge is a closed-form
// planar distance in that strip. The length equation is solved there, and the crossings of the
// straight line with the strip's edges give the exact geodesic to the matched end point, with no
// further propagation. Only when the matched end point leaves the strip (it lies on another
// boundary edge, or the line would leave a face) is the geodesic traced again, at the strip's
// estimate; a member that still does not settle falls back to root bracketing with exact fields.
#include "core/egg/grid.hpp"

#include <atomic>

namespace egg {

// Sets m.x2, m.spatial and m.normals of the inner member m (m.family, m.x1 and the guess m.x2
// given). Counts the propagations spent. Throws SolverFailure if it cannot be traced.
void traceInnerMember(const Patch& patch, const geodesic::DistanceSolver& solver,
                      const PlanarQuad& quad, GridMember& m, const GridOptions& options,
                      std::atomic<int>& propagations);

}  // namespace egg
