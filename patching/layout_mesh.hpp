#pragma once
// The layout mesh (Section 3.4): the design surface with every patch side of a layout inserted as
// a chain of mesh edges, built once for the whole layout. Patches are cut from it by a flood fill
// inside their own sides (layout_patch.hpp), so two patches that share a side share its vertices:
// their boundaries are the same polyline, bit for bit, and every patch costs O(patch) to cut.
//
// Every face of the layout mesh lies inside one face of the surface (parentFace), so anything on a
// patch maps back to the surface exactly. Each surface face that a side crosses is re-triangulated
// on its own, in its plane, by a constrained Delaunay triangulation (CGAL, kept inside the .cpp),
// with the face's edges, the points where sides cross them and the side steps as constraints.
#include "core/mesh/mesh.hpp"

#include <vector>

namespace egg::patching {

struct LayoutMesh {
  TriMesh mesh;
  std::vector<int> parentFace;           // per mesh face: the surface face it lies in
  std::vector<int> surfaceVertex;        // per mesh vertex: the surface vertex it is, or -1
  std::vector<int> pointVertices;        // per requested point: its mesh vertex
  std::vector<std::vector<int>> chains;  // per polyline: mesh vertices from its start to its end
};

// Inserts `points` (corners) and `polylines` (shortest geodesics traced on `surface`: consecutive
// points share a face, as DistanceSolver::path gives them) into `surface`. Points closer than
// `mergeFraction` of an edge to a vertex or of the edge to each other are merged. Polylines may
// meet and even cross (the crossing becomes a vertex of both chains); the layout decides whether
// that is allowed. Throws SolverFailure when a step of a polyline leaves its face.
LayoutMesh buildLayoutMesh(const TriMesh& surface, const std::vector<SurfacePoint>& points,
                           const std::vector<std::vector<SurfacePoint>>& polylines,
                           double mergeFraction = 1e-6);

}  // namespace egg::patching
