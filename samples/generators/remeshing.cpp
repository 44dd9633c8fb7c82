// Isotropic remeshing in the parameter domain. Geodesic and curvature oracles (docs/architecture.md
// "Validation references") are sensitive to slivers, so the footprint mesh from Delaunay refinement
// is equalised in 3D: on a steep height field or a stretched parametrisation a triangle that is
// nice in the domain is not nice on the surface.
#include "samples/generators/remeshing.hpp"

#include <cmath>
#include <numbers>

namespace egg::samples::detail {
namespace {

// Domain position as a vertex property; initialised, so OpenMesh's resize copies no garbage.
struct DomainPosition {
  Vec2 value = Vec2::Zero();
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

class DomainRemesher {
 public:
  DomainRemesher(const SurfaceSpec& spec, const DomainMesh& input, double target)
      : spec_(spec), target_(target) {
    mesh_.add_property(uv_);
    mesh_.add_property(locked_);
    std::vector<TriMesh::VertexHandle> handles;
    double extent = 0.0;
    for (size_t i = 0; i < input.domain.size(); ++i) {
      const auto v = mesh_.add_vertex(toOpenMesh(spec.position(input.domain[i])));
      mesh_.property(uv_, v).value = input.domain[i];
      mesh_.property(locked_, v) = input.locked[i];
      handles.push_back(v);
      extent = std::max(extent, input.domain[i].cwiseAbs().maxCoeff());
    }
    for (const auto& t : input.triangles) {
      mesh_.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
    }
    // Smallest accepted doubled domain area, relative to the domain scale: rejects moves that
    // would make a triangle (nearly) degenerate or inverted.
    minArea2_ = 1e-12 * std::max(1.0, extent * extent);
  }

  void run(const RemeshOptions& options) {
    const double high = 4.0 / 3.0 * target_, low = 4.0 / 5.0 * target_;
    for (int i = 0; i < options.iterations; ++i) {
      splitLongEdges(high);
      collapseShortEdges(low, high);
      flipToDelaunay();
      smooth();
      smooth();
    }
    for (int i = 0; i < options.finalSmoothing; ++i) {
      flipToDelaunay();
      smooth();
    }
    flipToDelaunay();
  }

  TriangleSoup soup() {
    mesh_.garbage_collection();
    TriangleSoup soup;
    for (auto v : mesh_.vertices()) soup.vertices.push_back(toEigen(mesh_.point(v)));
    for (auto f : mesh_.faces()) {
      std::array<int, 3> t{};
      int k = 0;
      for (auto v : mesh_.fv_range(f)) t[k++] = v.idx();
      if (spec_.reverseOrientation) std::swap(t[1], t[2]);
      soup.triangles.push_back(t);
    }
    return soup;
  }

 private:
  using VH = TriMesh::VertexHandle;
  using EH = TriMesh::EdgeHandle;
  using HH = TriMesh::HalfedgeHandle;

  Vec2 uv(VH v) const { return mesh_.property(uv_, v).value; }
  Vec3 point(VH v) const { return toEigen(mesh_.point(v)); }
  bool locked(VH v) const { return mesh_.property(locked_, v); }
  bool inDomain(const Vec2& u) const { return !spec_.inDomain || spec_.inDomain(u); }

  void place(VH v, const Vec2& u) {
    mesh_.property(uv_, v).value = u;
    mesh_.point(v) = toOpenMesh(spec_.position(u));
  }

  double length(EH e) const {
    const HH h = mesh_.halfedge_handle(e, 0);
    return (point(mesh_.to_vertex_handle(h)) - point(mesh_.from_vertex_handle(h))).norm();
  }

  // True if every face around v stays counter-clockwise in the domain with v at `u`. Faces that
  // contain `ignore` (they vanish in a collapse) are skipped.
  bool facesValidAt(VH v, const Vec2& u, VH ignore = VH()) const {
    for (auto f : mesh_.vf_range(v)) {
      Vec2 p[3];
      int k = 0;
      bool skip = false;
      for (auto w : mesh_.fv_range(f)) {
        if (w == ignore) skip = true;
        p[k++] = (w == v) ? u : uv(w);
      }
      if (skip) continue;
      if (cross2(p[1] - p[0], p[2] - p[0]) <= minArea2_) return false;
    }
    return true;
  }

  void splitLongEdges(double high) {
    for (int pass = 0; pass < 10; ++pass) {
      std::vector<EH> candidates;
      for (auto e : mesh_.edges()) {
        if (!mesh_.is_boundary(e) && length(e) > high) candidates.push_back(e);
      }
      if (candidates.empty()) return;
      for (EH e : candidates) {
        const HH h = mesh_.halfedge_handle(e, 0);
        const Vec2 mid = 0.5 * (uv(mesh_.from_vertex_handle(h)) + uv(mesh_.to_vertex_handle(h)));
        if (!inDomain(mid)) continue;
        const VH v = mesh_.split(e, toOpenMesh(spec_.position(mid)));
        mesh_.property(uv_, v).value = mid;
        mesh_.property(locked_, v) = false;
      }
    }
  }

  // Can `from` be collapsed into `to` along halfedge h without inverting, lengthening past
  // `high`, or moving the boundary?
  bool collapseAllowed(HH h, double high) {
    const VH from = mesh_.from_vertex_handle(h), to = mesh_.to_vertex_handle(h);
    if (locked(from)) return false;
    if (mesh_.is_boundary(from) && !mesh_.is_boundary(mesh_.edge_handle(h))) return false;
    if (!mesh_.is_collapse_ok(h)) return false;
    for (auto n : mesh_.vv_range(from)) {
      if (n != to && (point(n) - point(to)).norm() > high) return false;
    }
    return facesValidAt(from, uv(to), to);
  }

  void collapseShortEdges(double low, double high) {
    std::vector<EH> candidates;
    for (auto e : mesh_.edges()) {
      if (length(e) < low) candidates.push_back(e);
    }
    for (EH e : candidates) {
      if (mesh_.status(e).deleted() || length(e) >= low) continue;
      HH h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
      // Prefer removing an interior vertex: boundary vertices are samples of the exact curve.
      if (mesh_.is_boundary(mesh_.from_vertex_handle(h0))) std::swap(h0, h1);
      if (collapseAllowed(h0, high)) {
        mesh_.collapse(h0);
      } else if (collapseAllowed(h1, high)) {
        mesh_.collapse(h1);
      }
    }
  }

  static double angleAt(const Vec3& apex, const Vec3& a, const Vec3& b) {
    const Vec3 u = a - apex, w = b - apex;
    return std::atan2(u.cross(w).norm(), u.dot(w));
  }

  // Flips every interior edge whose opposite 3D angles sum past pi (the intrinsic Delaunay test,
  // which maximises the smallest angle), when the flipped pair stays valid in the domain.
  void flipToDelaunay() {
    for (int pass = 0; pass < 20; ++pass) {
      int flips = 0;
      for (auto e : mesh_.edges()) {
        if (mesh_.is_boundary(e)) continue;
        const HH h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
        const VH a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
        const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
        const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
        const double opposite =
            angleAt(point(c), point(a), point(b)) + angleAt(point(d), point(a), point(b));
        if (opposite <= std::numbers::pi + 1e-9) continue;
        if (!mesh_.is_flip_ok(e)) continue;
        if (mesh_.valence(a) <= 3 || mesh_.valence(b) <= 3) continue;
        // Faces (a, b, c) and (b, a, d) are counter-clockwise; after the flip (c, a, d), (d, b, c).
        if (cross2(uv(a) - uv(c), uv(d) - uv(c)) <= minArea2_) continue;
        if (cross2(uv(b) - uv(d), uv(c) - uv(d)) <= minArea2_) continue;
        mesh_.flip(e);
        ++flips;
      }
      if (flips == 0) return;
    }
  }

  // Tangential smoothing: move each free interior vertex toward the centroid of its neighbours,
  // through the domain (one Gauss-Newton step of projecting the centroid onto the surface), so
  // the vertex stays on the surface exactly.
  void smooth() {
    const double step = 1e-6 * target_;
    for (auto v : mesh_.vertices()) {
      if (locked(v) || mesh_.is_boundary(v)) continue;
      Vec3 centroid = Vec3::Zero();
      int count = 0;
      for (auto n : mesh_.vv_range(v)) {
        centroid += point(n);
        ++count;
      }
      if (count == 0) continue;
      centroid /= count;
      const Vec2 u = uv(v);
      Eigen::Matrix<double, 3, 2> jacobian;
      for (int k = 0; k < 2; ++k) {
        Vec2 delta = Vec2::Zero();
        delta[k] = step;
        jacobian.col(k) = (spec_.position(u + delta) - spec_.position(u - delta)) / (2.0 * step);
      }
      const Eigen::Matrix2d normal = jacobian.transpose() * jacobian;
      if (std::abs(normal.determinant()) < 1e-20) continue;
      Vec2 move = normal.ldlt().solve(jacobian.transpose() * (centroid - point(v)));
      for (int attempt = 0; attempt < 4; ++attempt, move *= 0.5) {
        const Vec2 candidate = u + move;
        if (inDomain(candidate) && facesValidAt(v, candidate)) {
          place(v, candidate);
          break;
        }
      }
    }
  }

  const SurfaceSpec& spec_;
  double target_;
  double minArea2_ = 0.0;
  TriMesh mesh_;
  OpenMesh::VPropHandleT<DomainPosition> uv_;
  OpenMesh::VPropHandleT<bool> locked_;
};

}  // namespace

TriangleSoup remeshInDomain(const SurfaceSpec& spec, const DomainMesh& input,
                            const RemeshOptions& options) {
  DomainRemesher remesher(spec, input, options.targetEdge);
  remesher.run(options);
  return remesher.soup();
}

}  // namespace egg::samples::detail
