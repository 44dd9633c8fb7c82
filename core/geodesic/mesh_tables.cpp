// The flat per-mesh tables of the window propagation (window_propagation.hpp): halfedge arrays,
// unfolded triangle frames, angle sums and which vertices are pseudo-sources.
#include "core/errors.hpp"
#include "core/geodesic/window_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace egg::geodesic::detail {

MeshTables buildTables(const TriMesh& mesh, const DistanceSolverOptions& options) {
  MeshTables t;
  t.vertexCount = static_cast<int>(mesh.n_vertices());
  t.faceCount = static_cast<int>(mesh.n_faces());
  t.halfedgeCount = static_cast<int>(mesh.n_halfedges());
  if (t.vertexCount == 0 || t.faceCount == 0) throw InvalidInput("geodesic: the mesh has no faces");
  t.positions.resize(t.vertexCount);
  for (auto vh : mesh.vertices()) t.positions[vh.idx()] = toEigen(mesh.point(vh));
  const int nh = t.halfedgeCount;
  std::vector<int> fromVertex(nh, -1), toVertex(nh, -1), face(nh, -1), next(nh, -1), prev(nh, -1);
  std::vector<double> length(nh, 0.0), oppositeX(nh, 0.0), oppositeY(nh, 0.0);
  std::vector<int> oppositeVertex(nh, -1);
  double edgeSum = 0.0;
  for (auto hh : mesh.halfedges()) {
    const int h = hh.idx();
    fromVertex[h] = mesh.from_vertex_handle(hh).idx();
    toVertex[h] = mesh.to_vertex_handle(hh).idx();
    face[h] = mesh.face_handle(hh).is_valid() ? mesh.face_handle(hh).idx() : -1;
    next[h] = mesh.next_halfedge_handle(hh).idx();
    prev[h] = mesh.prev_halfedge_handle(hh).idx();
    length[h] = (t.positions[toVertex[h]] - t.positions[fromVertex[h]]).norm();
    if ((h & 1) == 0) edgeSum += length[h];
  }
  t.meanEdgeLength = edgeSum / std::max<size_t>(1, mesh.n_edges());
  t.angleSum.assign(t.vertexCount, 0.0);
  for (int h = 0; h < nh; ++h) {
    if (face[h] < 0) continue;
    const int c = toVertex[next[h]];
    oppositeVertex[h] = c;
    const double L = length[h];
    const double la = length[prev[h]];  // |C A|
    const double lb = length[next[h]];  // |B C|
    if (!(L > 0.0) || !(la > 0.0) || !(lb > 0.0)) {
      throw InvalidInput("geodesic: face " + std::to_string(face[h]) + " has a zero-length edge");
    }
    const double x = (L * L + la * la - lb * lb) / (2.0 * L);
    const double y2 = la * la - x * x;
    // Heron-stable height from the cross product in 3D (the law of cosines loses digits on
    // slivers).
    const Eigen::Vector3d a = t.positions[fromVertex[h]];
    const double twiceArea = (t.positions[toVertex[h]] - a).cross(t.positions[c] - a).norm();
    const double y = twiceArea / L;
    if (!(y > 0.0) || y2 < -1e-6 * la * la) {
      throw InvalidInput("geodesic: face " + std::to_string(face[h]) +
                         " is degenerate (zero area)");
    }
    oppositeX[h] = x;
    oppositeY[h] = y;
    // Interior angle at the from-vertex, accumulated into its angle sum.
    t.angleSum[fromVertex[h]] += std::atan2(y, x);
  }
  t.he.resize(nh);
  for (int h = 0; h < nh; ++h) {
    t.he[h] = {length[h], oppositeX[h], oppositeY[h], fromVertex[h],    toVertex[h],
               face[h],   next[h],      prev[h],      oppositeVertex[h]};
  }
  t.faceVerts.resize(t.faceCount);
  t.faceHalfedge.resize(t.faceCount);
  for (auto fh : mesh.faces()) {
    const int f = fh.idx();
    t.faceVerts[f] = faceVertices(mesh, f);
    for (int i = 0; i < 3; ++i) t.faceHalfedge[f][i] = -1;
    for (auto hh : mesh.fh_range(fh)) {
      const int h = hh.idx();
      for (int i = 0; i < 3; ++i) {
        if (t.faceVerts[f][i] == fromVertex[h]) t.faceHalfedge[f][i] = h;
      }
    }
  }
  t.outgoingStart.assign(t.vertexCount + 1, 0);
  for (int h = 0; h < nh; ++h) ++t.outgoingStart[fromVertex[h] + 1];
  for (int v = 0; v < t.vertexCount; ++v) t.outgoingStart[v + 1] += t.outgoingStart[v];
  t.outgoing.assign(nh, -1);
  {
    std::vector<int> fill(t.outgoingStart.begin(), t.outgoingStart.end() - 1);
    for (int h = 0; h < nh; ++h) t.outgoing[fill[fromVertex[h]]++] = h;
  }
  // A skipped saddle's shadow is a wedge as wide as its excess times the distance travelled; it is
  // closed by bending at the saddle (pathBentAt, window_geometry.hpp) from the faces next to it,
  // which works while the wedge stays narrower than a face. Distances stay below twice the
  // bounding-box diagonal on any patch-like surface, so a saddle is skipped only if its excess
  // times that stays below a quarter of the shorter of its own shortest edge and the mesh's
  // 10th-percentile edge (faces along the shadow may be smaller than its own on a graded mesh). On
  // very fine meshes this takes over from the tolerance. (Bounding the whole bend cone, excess +
  // tolerance, instead would skip nothing past ~10k vertices: 3.5x slower at 17.7k on the bench.)
  Eigen::Vector3d lo = t.positions[0], hi = t.positions[0];
  for (const auto& p : t.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double reach = 2.0 * (hi - lo).norm();
  std::vector<double> edges;
  for (int h = 0; h < nh; h += 2) edges.push_back(length[h]);
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 10, edges.end());
  const double shortEdge = edges[edges.size() / 10];
  std::vector<double> shortestEdge(t.vertexCount, shortEdge);
  for (int h = 0; h < nh; ++h)
    shortestEdge[fromVertex[h]] = std::min(shortestEdge[fromVertex[h]], length[h]);
  t.boundaryVertex.assign(t.vertexCount, 0);
  t.pseudoSource.assign(t.vertexCount, 0);
  t.shadowCone.assign(t.vertexCount, 0.0);
  t.hasShadowCone.assign(t.vertexCount, 0);
  for (auto vh : mesh.vertices()) {
    const int v = vh.idx();
    t.boundaryVertex[v] = mesh.is_boundary(vh) ? 1 : 0;
    // A shortest path can only pass through a vertex that leaves at least pi of surface angle on
    // each side: interior saddles (angle sum > 2 pi) and reflex boundary vertices (> pi). Convex
    // and straight boundary vertices never bend a shortest path.
    // The tolerance applies to interior saddles only. A skipped reflex boundary vertex has no
    // windows on its far side to close its shadow (the boundary is there), and paths between
    // boundary points - the distance maps of Section 2.4.2 - graze along it: measured, skipping
    // them cost up to 3e-4 relative between boundary vertices of the samples.
    if (t.boundaryVertex[v]) {
      t.pseudoSource[v] = t.angleSum[v] > std::numbers::pi ? 1 : 0;
    } else {
      const double excess = t.angleSum[v] - 2.0 * std::numbers::pi;
      const double cone = excess + options.saddleAngleTolerance;
      const bool skipped =
          excess <= options.saddleAngleTolerance && excess * reach <= 0.25 * shortestEdge[v];
      t.pseudoSource[v] = excess > 0.0 && !skipped ? 1 : 0;
      if (excess > 0.0 && skipped) {
        t.shadowCone[v] = cone;
        t.hasShadowCone[v] = 1;
      }
    }
  }
  return t;
}

}  // namespace egg::geodesic::detail
