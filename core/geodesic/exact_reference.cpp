// CGAL's exact shortest paths as a test and benchmark oracle (the only CGAL translation unit of
// core/geodesic: CGAL headers cost ~25 s and ~1 GB per unit to compile).
#include "core/geodesic/exact_reference.hpp"

#include "core/errors.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <limits>
#include <string>

namespace egg::geodesic {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, CgalMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
}  // namespace

std::vector<double> referenceDistances(const TriMesh& mesh, const SurfacePoint& source) {
  if (mesh.n_faces() == 0) throw InvalidInput("geodesic reference: the mesh has no faces");
  if (source.face < 0 || source.face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInput("geodesic reference: source face " + std::to_string(source.face) +
                       " is out of range");
  }
  CgalMesh cgal;
  std::vector<CgalMesh::Vertex_index> vertices;
  vertices.reserve(mesh.n_vertices());
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    vertices.push_back(cgal.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  }
  std::vector<CgalMesh::Face_index> faces;
  faces.reserve(mesh.n_faces());
  for (auto fh : mesh.faces()) {
    const auto ids = faceVertices(mesh, fh.idx());
    faces.push_back(cgal.add_face(vertices[ids[0]], vertices[ids[1]], vertices[ids[2]]));
    if (faces.back() == CgalMesh::null_face()) {
      throw InvalidInput("geodesic reference: CGAL rejected face " + std::to_string(fh.idx()));
    }
  }
  // CGAL's barycentric order starts at source(halfedge(f)); ours is OpenMesh's circulator order.
  const auto f = faces[source.face];
  const auto ids = faceVertices(mesh, source.face);
  auto h = cgal.halfedge(f);
  const int order[3] = {static_cast<int>(cgal.source(h)), static_cast<int>(cgal.target(h)),
                        static_cast<int>(cgal.target(cgal.next(h)))};
  ShortestPath::Barycentric_coordinates bc;
  double w[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) {
      if (ids[i] == order[k]) w[k] = source.barycentric[i];
    }
  }
  const double sum = w[0] + w[1] + w[2];
  bc = {w[0] / sum, w[1] / sum, w[2] / sum};
  ShortestPath paths(cgal);
  paths.add_source_point(f, bc);
  paths.build_sequence_tree();
  std::vector<double> result(mesh.n_vertices(), std::numeric_limits<double>::infinity());
  for (auto v : cgal.vertices()) {
    const double d = paths.shortest_distance_to_source_points(v).first;
    if (d >= 0.0) result[static_cast<size_t>(v)] = d;
  }
  return result;
}

}  // namespace egg::geodesic
