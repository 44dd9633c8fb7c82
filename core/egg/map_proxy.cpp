#include "core/egg/map_proxy.hpp"

#include "core/errors.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <queue>
#include <string>
#include <tuple>

namespace egg {

namespace {

// No collapse may turn a face normal by more than this (degrees): the proxy stays a faithful,
// fold-free copy of the surface (a fold would open short cuts for the geodesics).
constexpr double kMaxNormalDeviationDeg = 30.0;
// No collapse may leave a face whose longest edge exceeds this many times its height, unless the
// one-ring was already worse: slivers make the window propagation slow and its distances noisy.
constexpr double kMaxAspectRatio = 8.0;

double aspectRatio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area2 = (b - a).cross(c - a).norm();  // twice the area
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return area2 > 0.0 ? longest / area2 : INFINITY;  // longest edge / height
}

class ProxyDecimator {
 public:
  explicit ProxyDecimator(TriMesh& mesh)
      : mesh_(mesh), quadric_(mesh.n_vertices(), Eigen::Matrix4d::Zero()) {
    // Garland-Heckbert quadrics of the face planes, area weighted: the squared distance of a
    // point from the planes around a vertex; summed into the surviving vertex at each collapse.
    for (auto fh : mesh_.faces()) {
      auto fv = mesh_.cfv_begin(fh);
      const Eigen::Vector3d a = toEigen(mesh_.point(*fv)), b = toEigen(mesh_.point(*++fv)),
                            c = toEigen(mesh_.point(*++fv));
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double area = 0.5 * cross.norm();
      if (!(area > 0.0)) continue;
      Eigen::Vector4d plane;
      plane << cross / (2.0 * area), -cross.dot(a) / (2.0 * area);
      const Eigen::Matrix4d q = area * plane * plane.transpose();
      for (auto vh : mesh_.fv_range(fh)) quadric_[vh.idx()] += q;
    }
  }

  // Greedy halfedge collapses, cheapest first, until `target` vertices remain or none is legal
  // (Garland and Heckbert's order, on a lazy heap: each vertex holds its cheapest legal collapse
  // under a version number; a collapse v0 -> v1 re-ranks v1 and its new one-ring, whose quadrics
  // or faces changed, and a popped entry is tested again before it is applied). Deterministic:
  // ties go to the lower vertex id.
  void decimateTo(int target) {
    int alive = static_cast<int>(mesh_.n_vertices());
    using Entry = std::tuple<double, int, int, int>;  // cost, v0, halfedge, version
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
    std::vector<int> version(mesh_.n_vertices(), 0);
    std::vector<std::pair<double, int>> options;
    // The vertex's cheapest collapse; with `checked`, its cheapest legal one (the legality tests
    // run in order of cost until one passes). Unchecked entries are tested when popped, which
    // spares most tests: a collapse re-ranks ~7 vertices, and only the popped one is applied.
    const auto rank = [&](TriMesh::VertexHandle vh, bool checked) {
      const int v = vh.idx();
      ++version[v];
      if (mesh_.status(vh).deleted() || mesh_.status(vh).locked()) return;
      options.clear();
      for (auto h : mesh_.voh_range(vh)) options.emplace_back(cost(h), h.idx());
      std::sort(options.begin(), options.end());
      for (const auto& [c, halfedge] : options)
        if (!checked || legal(TriMesh::HalfedgeHandle(halfedge))) {
          heap.emplace(c, v, halfedge, version[v]);
          return;
        }
    };
    for (auto vh : mesh_.vertices()) rank(vh, false);
    while (alive > target && !heap.empty()) {
      const auto [c, v0, halfedge, stamp] = heap.top();
      heap.pop();
      if (stamp != version[v0]) continue;
      const auto h = TriMesh::HalfedgeHandle(halfedge);
      if (mesh_.status(mesh_.edge_handle(h)).deleted() || mesh_.from_vertex_handle(h).idx() != v0 ||
          !legal(h)) {
        rank(TriMesh::VertexHandle(v0), true);
        continue;
      }
      const auto v1 = mesh_.to_vertex_handle(h);
      quadric_[v1.idx()] += quadric_[v0];
      mesh_.collapse(h);
      ++version[v0];
      --alive;
      rank(v1, false);
      for (auto w : mesh_.vv_range(v1)) rank(w, false);
    }
  }

 private:
  // The topological test of an edge collapse (Dey et al.'s link condition): the only common
  // neighbours of v0 and v1 are the tips of the edge's faces, neither of which would be left
  // hanging on two boundary edges; and not the last interior collapse of a tetrahedron. (OpenMesh's
  // is_collapse_ok tests the same but looked up a property by name per call, 3/4 of the time.)
  bool linkConditionHolds(TriMesh::HalfedgeHandle h) const {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    const auto o = mesh_.opposite_halfedge_handle(h);
    TriMesh::VertexHandle vl, vr;
    if (!mesh_.is_boundary(h)) {
      vl = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
      if (mesh_.is_boundary(mesh_.edge_handle(mesh_.next_halfedge_handle(h))) &&
          mesh_.is_boundary(mesh_.edge_handle(mesh_.prev_halfedge_handle(h))))
        return false;
    }
    if (!mesh_.is_boundary(o)) {
      vr = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
      if (mesh_.is_boundary(mesh_.edge_handle(mesh_.next_halfedge_handle(o))) &&
          mesh_.is_boundary(mesh_.edge_handle(mesh_.prev_halfedge_handle(o))))
        return false;
    }
    if (vl == vr) return false;  // both invalid (an isolated edge) or a degenerate pair of faces
    // Two boundary vertices may only be joined along a boundary edge.
    if (mesh_.is_boundary(v0) && mesh_.is_boundary(v1) && !mesh_.is_boundary(mesh_.edge_handle(h)))
      return false;
    int common = 0;
    for (auto a : mesh_.vv_range(v0)) {
      if (a == v1) continue;
      for (auto b : mesh_.vv_range(v1))
        if (a == b) {
          if (a != vl && a != vr) return false;
          ++common;
        }
    }
    if (vl.is_valid() && vr.is_valid() && mesh_.valence(vl) == 3 && mesh_.valence(vr) == 3 &&
        common == 2) {
      for (auto a : mesh_.vv_range(vl))
        if (a == vr) return false;
    }
    return true;
  }

  // Quadric error of the kept position (m^4: area times squared distance). On flat stretches all
  // collapses cost ~0 and go first, which is right for geodesics (a flat region is exact with any
  // triangles); the aspect-ratio test keeps them from turning into slivers. Adding the edge length
  // to the fourth times 1e-3 or 1e-2 (to coarsen flat parts evenly) made the maps worse:
  // 1.5e-3 / 3.3e-3 m instead of 1.0e-3 m on the 3.4k bench patch at 600 vertices.
  double cost(TriMesh::HalfedgeHandle h) const {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    Eigen::Vector4d x;
    x << toEigen(mesh_.point(v1)), 1.0;
    return x.dot((quadric_[v0.idx()] + quadric_[v1.idx()]) * x);
  }

  bool legal(TriMesh::HalfedgeHandle h) const {
    const auto v0 = mesh_.from_vertex_handle(h), v1 = mesh_.to_vertex_handle(h);
    // A boundary vertex may only slide along a boundary edge into its boundary neighbour: the
    // proxy's sides stay sub-polylines of the fine sides (Section 2.4.2 needs the boundary
    // parameters at constant speed along the sides, which the fine arc lengths provide).
    if (mesh_.is_boundary(v0) &&
        !(mesh_.is_boundary(mesh_.edge_handle(h)) && mesh_.is_boundary(v1)))
      return false;
    if (!linkConditionHolds(h)) return false;
    const Eigen::Vector3d p0 = toEigen(mesh_.point(v0)), p1 = toEigen(mesh_.point(v1));
    const double cosMax = std::cos(kMaxNormalDeviationDeg * M_PI / 180.0);
    double worstBefore = 0.0, worstAfter = 0.0;
    for (auto fh : mesh_.vf_range(v0)) {
      std::array<Eigen::Vector3d, 3> p;
      int k = 0;
      bool hasV1 = false;
      for (auto vh : mesh_.fv_range(fh)) {
        hasV1 = hasV1 || vh == v1;
        p[k++] = toEigen(mesh_.point(vh));
      }
      worstBefore = std::max(worstBefore, aspectRatio(p[0], p[1], p[2]));
      if (hasV1) continue;  // this face disappears
      const Eigen::Vector3d before = (p[1] - p[0]).cross(p[2] - p[0]);
      for (auto& q : p)
        if (q == p0) q = p1;
      const Eigen::Vector3d after = (p[1] - p[0]).cross(p[2] - p[0]);
      if (!(after.norm() > 0.0) || before.dot(after) < cosMax * before.norm() * after.norm())
        return false;
      worstAfter = std::max(worstAfter, aspectRatio(p[0], p[1], p[2]));
    }
    return !(worstAfter > kMaxAspectRatio && worstAfter > worstBefore);
  }

  TriMesh& mesh_;
  std::vector<Eigen::Matrix4d> quadric_;
};

}  // namespace

MapProxy makeMapProxy(const Patch& patch, int targetVertices) {
  if (targetVertices < 8)
    throw InvalidInput(
        "grid.map_proxy_vertices must be 0 (maps on the patch itself) or at least 8, got " +
        std::to_string(targetVertices));
  TriMesh mesh = patch.mesh;
  OpenMesh::VPropHandleT<int> fineId;
  mesh.add_property(fineId);
  for (auto vh : mesh.vertices()) mesh.property(fineId, vh) = vh.idx();
  for (int corner : patch.cornerVertices)
    mesh.status(TriMesh::VertexHandle(corner)).set_locked(true);
  ProxyDecimator(mesh).decimateTo(targetVertices);
  mesh.garbage_collection();

  MapProxy proxy;
  proxy.fineVertex.resize(mesh.n_vertices());
  std::vector<int> proxyOf(patch.mesh.n_vertices(), -1);
  for (auto vh : mesh.vertices()) {
    const int fine = mesh.property(fineId, vh);
    proxy.fineVertex[vh.idx()] = fine;
    proxyOf[fine] = vh.idx();
  }
  mesh.remove_property(fineId);

  Patch& p = proxy.patch;
  p.corners = patch.corners;
  p.cornerOffsets = patch.cornerOffsets;
  p.sideLengths = patch.sideLengths;
  p.innerAngles = patch.innerAngles;
  for (int k = 0; k < 4; ++k) {
    p.cornerVertices[k] = proxyOf[patch.cornerVertices[k]];
    if (p.cornerVertices[k] < 0)
      throw SolverFailure("map proxy: corner " + std::to_string(k) + " was collapsed");
    // The surviving vertices of the fine side, in order, with their fine arc lengths.
    const auto& chain = patch.sides[k];
    for (size_t i = 0; i < chain.size(); ++i) {
      const int v = proxyOf[chain[i]];
      if (v < 0) continue;
      p.sides[k].push_back(v);
      p.sideArcLength[k].push_back(patch.sideArcLength[k][i]);
    }
    for (size_t i = 0; i + 1 < p.sides[k].size(); ++i) {
      const auto from = TriMesh::VertexHandle(p.sides[k][i]),
                 to = TriMesh::VertexHandle(p.sides[k][i + 1]);
      const auto h = mesh.find_halfedge(from, to);
      if (!h.is_valid() || !mesh.is_boundary(mesh.edge_handle(h)))
        throw SolverFailure("map proxy: side " + std::to_string(k) +
                            " lost its boundary edge after decimation");
    }
  }
  p.mesh = std::move(mesh);
  p.area = surfaceArea(p.mesh);
  return proxy;
}

}  // namespace egg
