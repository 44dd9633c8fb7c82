#include "core/mesh/mesh.hpp"

#include "core/errors.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace egg {

std::array<int, 3> faceVertices(const TriMesh& mesh, int face) {
  std::array<int, 3> ids{-1, -1, -1};
  int k = 0;
  for (auto vh : mesh.fv_range(TriMesh::FaceHandle(face))) {
    if (k < 3) ids[k] = vh.idx();
    ++k;
  }
  return ids;
}

Eigen::Vector3d position(const TriMesh& mesh, const SurfacePoint& point) {
  const auto ids = faceVertices(mesh, point.face);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    p += point.barycentric[i] * toEigen(mesh.point(TriMesh::VertexHandle(ids[i])));
  return p;
}

TriMesh meshFromSoup(const TriangleSoup& soup) {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(soup.vertices.size());
  for (const auto& v : soup.vertices) handles.push_back(mesh.add_vertex(toOpenMesh(v)));
  const int n = static_cast<int>(soup.vertices.size());
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    for (int i : tri) {
      if (i < 0 || i >= n) {
        throw InvalidInput("triangle " + std::to_string(t) + " refers to vertex " +
                           std::to_string(i) + ", but there are only " + std::to_string(n) +
                           " vertices");
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw InvalidInput("triangle " + std::to_string(t) + " repeats a vertex (" +
                         std::to_string(tri[0]) + ", " + std::to_string(tri[1]) + ", " +
                         std::to_string(tri[2]) + ")");
    }
    // OpenMesh's own complex-edge/complex-vertex messages go to its log; silence them here and
    // report the triangle ourselves.
    auto fh = mesh.add_face(handles[tri[0]], handles[tri[1]], handles[tri[2]]);
    if (!fh.is_valid()) {
      throw InvalidInput(
          "triangle " + std::to_string(t) + " (" + std::to_string(tri[0]) + ", " +
          std::to_string(tri[1]) + ", " + std::to_string(tri[2]) +
          ") makes the mesh non-manifold (an edge shared by more than two triangles, "
          "or inconsistent orientation)");
    }
  }
  return mesh;
}

TriangleSoup soupFromMesh(const TriMesh& mesh) {
  TriangleSoup soup;
  soup.vertices.reserve(mesh.n_vertices());
  for (auto vh : mesh.vertices()) soup.vertices.push_back(toEigen(mesh.point(vh)));
  soup.triangles.reserve(mesh.n_faces());
  for (auto fh : mesh.faces()) soup.triangles.push_back(faceVertices(mesh, fh.idx()));
  return soup;
}

Eigen::Vector3d closestPointBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

BoundingBox boundingBox(const TriMesh& mesh) {
  BoundingBox box;
  if (mesh.n_vertices() == 0) return box;
  box.min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  box.max = -box.min;
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d p = toEigen(mesh.point(vh));
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

double surfaceArea(const TriMesh& mesh) {
  double area = 0.0;
  for (auto fh : mesh.faces()) {
    const auto ids = faceVertices(mesh, fh.idx());
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[0])));
    const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(ids[1])));
    const Eigen::Vector3d c = toEigen(mesh.point(TriMesh::VertexHandle(ids[2])));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

double meanEdgeLength(const TriMesh& mesh) {
  if (mesh.n_edges() == 0) return 0.0;
  double sum = 0.0;
  for (auto eh : mesh.edges()) sum += mesh.calc_edge_length(eh);
  return sum / static_cast<double>(mesh.n_edges());
}

double vertexAngleSum(const TriMesh& mesh, TriMesh::VertexHandle v) {
  double sum = 0.0;
  const Eigen::Vector3d p = toEigen(mesh.point(v));
  for (auto heh : mesh.voh_range(v)) {
    if (mesh.is_boundary(heh)) continue;
    const auto next = mesh.next_halfedge_handle(heh);
    const Eigen::Vector3d a = toEigen(mesh.point(mesh.to_vertex_handle(heh))) - p;
    const Eigen::Vector3d b = toEigen(mesh.point(mesh.to_vertex_handle(next))) - p;
    sum += std::atan2(a.cross(b).norm(), a.dot(b));
  }
  return sum;
}

namespace {
double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}
}  // namespace

double geodesicTurningAtBoundary(const TriMesh& mesh, TriMesh::VertexHandle v,
                                 const Eigen::Vector3d& before, const Eigen::Vector3d& after) {
  // The fan of faces round a boundary vertex is open: walk it from its first boundary edge,
  // measuring each direction by the angle swept through the faces so far.
  const Eigen::Vector3d p = toEigen(mesh.point(v));
  TriMesh::HalfedgeHandle start;
  for (auto heh : mesh.voh_range(v))
    if (mesh.is_boundary(mesh.opposite_halfedge_handle(heh)))
      start = heh;  // its face is the fan's first
  if (!start.is_valid()) return 0.0;
  const auto sweep = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d d = point - p;
    double swept = 0.0, bestSlack = std::numeric_limits<double>::infinity(), at = 0.0;
    for (auto heh = start; heh.is_valid() && !mesh.is_boundary(heh);) {
      const auto next = mesh.next_halfedge_handle(heh);
      const Eigen::Vector3d a = toEigen(mesh.point(mesh.to_vertex_handle(heh))) - p;
      const Eigen::Vector3d b = toEigen(mesh.point(mesh.to_vertex_handle(next))) - p;
      const double corner = angleBetween(a, b), toD = angleBetween(a, d);
      // d lies in this face's corner when the two part angles add up to the corner angle.
      const double slack = std::abs(toD + angleBetween(d, b) - corner);
      if (slack < bestSlack) bestSlack = slack, at = swept + toD;
      swept += corner;
      heh = mesh.opposite_halfedge_handle(
          mesh.prev_halfedge_handle(heh));  // round v to the next face
      if (heh == start) break;
    }
    return at;
  };
  return std::abs(sweep(after) - sweep(before)) - M_PI;
}

double boundaryWrapTurning(const TriMesh& mesh, const std::vector<Eigen::Vector3d>& polyline,
                           const std::vector<int>& vertices) {
  double total = 0.0;
  for (int id : vertices) {
    const auto vh = TriMesh::VertexHandle(id);
    if (!mesh.is_boundary(vh)) continue;
    const Eigen::Vector3d x = toEigen(mesh.point(vh));
    size_t i = 0;
    for (size_t k = 1; k < polyline.size(); ++k)
      if ((polyline[k] - x).squaredNorm() < (polyline[i] - x).squaredNorm()) i = k;
    if (i == 0 || i + 1 >= polyline.size()) continue;  // an end of the polyline
    size_t before = i - 1, after = i + 1;
    const double tiny = 1e-12 * (1.0 + x.squaredNorm());
    while (before > 0 && (polyline[before] - x).squaredNorm() <= tiny) --before;
    while (after + 1 < polyline.size() && (polyline[after] - x).squaredNorm() <= tiny) ++after;
    total += std::max(0.0, geodesicTurningAtBoundary(mesh, vh, polyline[before], polyline[after]));
  }
  return total;
}

}  // namespace egg
