#pragma once
// A coarse copy of a patch mesh on which the distance maps of Section 2.4.2 are computed.
//
// The maps only steer design choices (the alpha_bar range of Problem 2.3, the cladding functions
// F, the C function of member placement, the start guesses x2 of member tracing); criterion (i)
// is restored on the fine patch by member tracing, which moves x2 until the geodesic length on
// the fine mesh equals the planar length. An exact field costs roughly in proportion to the
// vertices, so the maps are read on a decimated copy (timings: docs/measurements.md).
//
// The proxy is the fine patch mesh simplified by halfedge collapses in quadric-error order
// (Garland and Heckbert; no face normal turned by more than 30 degrees, no new sliver): every
// proxy vertex IS a fine vertex at its fine position (a halfedge collapse removes a vertex and
// moves none), the four corners are locked, and a boundary vertex may only collapse along a
// boundary edge into its boundary neighbour, so each proxy side is a sub-polyline of the fine
// geodesic side: the same corners, a subset of its vertices, chords in between. Each proxy side
// vertex keeps its FINE arc length, so the boundary point at fine arc length s maps to the proxy
// boundary point at the same s (linear between the bracketing proxy side vertices, which is what
// sidePoint does), and the map parameters x1, x2 mean the same boundary points on both meshes up
// to the chords' sagitta (criterion ii: constant speed along the fine sides).
// The proxy's distances differ from the fine ones in both directions, so no global rescaling is
// applied: scaling the maps to the fine side lengths at the corners helped on some meshes, hurt on
// others, and never moved members or F measurably (docs/measurements.md).
// Not OpenMesh's Decimater: its generic modules cost more than a fine field (docs/measurements.md).
#include "core/egg/patch.hpp"

#include <vector>

namespace egg {

struct MapProxy {
  // The coarse patch: mesh, corners and side chains in proxy vertex ids; sideArcLength[k][i] is
  // the FINE arc length of the i-th proxy vertex of side k; sideLengths, innerAngles, corners and
  // cornerOffsets are the fine patch's; area is the proxy's own.
  Patch patch;
  std::vector<int> fineVertex;  // fine vertex id of each proxy vertex
};

// Decimates the patch mesh to `targetVertices` vertices (more when the tests forbid further
// collapses). Deterministic. Throws InvalidInput naming grid.map_proxy_vertices when
// targetVertices < 8, and SolverFailure when a side lost an edge (cannot happen: boundary
// collapses stay on the boundary).
MapProxy makeMapProxy(const Patch& patch, int targetVertices);

}  // namespace egg
