#pragma once
// CGAL Surface_mesh_shortest_path (Chen-Han / Xin-Wang exact algorithm on exact predicates) as a
// reference oracle for tests and the benchmark. It is far too slow to be the engine (about 0.5 s
// per source on a 4k-vertex patch), and it is kept behind this plain interface so CGAL headers
// stay in one translation unit.
#include "core/mesh/mesh.hpp"

#include <vector>

namespace egg::geodesic {

// Exact polyhedral distances from `source` to every vertex, by CGAL. Throws InvalidInput for an
// empty mesh or a bad source. Vertices in other connected components get +inf.
std::vector<double> referenceDistances(const TriMesh& mesh, const SurfacePoint& source);

}  // namespace egg::geodesic
