// The plan view of Workflow 2 (see footprint.hpp).
#include "patching/footprint.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace egg::patching {

Plan planOf(const TriMesh& mesh) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto vh : mesh.vertices()) mean += toEigen(mesh.point(vh));
  mean /= static_cast<double>(std::max<size_t>(mesh.n_vertices(), 1));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d d = toEigen(mesh.point(vh)) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d n = eig.eigenvectors().col(0);
  Plan plan;
  plan.origin = mean;
  // A roof given z up keeps its x and y (so the layout reads in the model's own axes).
  if (std::abs(n.z()) <= 0.9) {
    plan.normal = n.normalized();
    plan.e1 = eig.eigenvectors().col(2).normalized();
    plan.e2 = plan.normal.cross(plan.e1);
  }
  return plan;
}

double signedArea(const Polygon& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2 &u = p[i], &v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}

bool insidePolygon(const Polygon& poly, const Vec2& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

double distanceToPolygon(const Polygon& poly, const Vec2& q) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    const Vec2 d = b - a;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - q).norm());
  }
  return best;
}

std::vector<char> convexHullMarks(const Polygon& polygon) {
  // Andrew's monotone chain; collinear points are not hull vertices.
  std::vector<size_t> order(polygon.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return polygon[a].x() < polygon[b].x() ||
           (polygon[a].x() == polygon[b].x() && polygon[a].y() < polygon[b].y());
  });
  const auto cross = [&](size_t o, size_t a, size_t b) {
    const Vec2 u = polygon[a] - polygon[o], w = polygon[b] - polygon[o];
    return u.x() * w.y() - u.y() * w.x();
  };
  std::vector<size_t> hull;
  for (int pass = 0; pass < 2 && polygon.size() >= 3; ++pass) {
    const size_t start = hull.size();
    for (size_t k = 0; k < order.size(); ++k) {
      const size_t i = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (hull.size() >= start + 2 && cross(hull[hull.size() - 2], hull.back(), i) <= 0)
        hull.pop_back();
      hull.push_back(i);
    }
    hull.pop_back();
  }
  std::vector<char> marks(polygon.size(), 0);
  for (size_t i : hull) marks[i] = 1;
  return marks;
}

bool Footprint::contains(const Vec2& q) const {
  const bool inOuter = insidePolygon(outer, q) || distanceToPolygon(outer, q) <= tolerance;
  if (!inOuter) return false;
  for (const auto& h : holes)
    if (insidePolygon(h, q) && distanceToPolygon(h, q) > tolerance) return false;
  return true;
}

bool Footprint::containsSegment(const Vec2& a, const Vec2& b) const {
  const int samples = 24;
  for (int k = 0; k <= samples; ++k)
    if (!contains(a + (b - a) * (static_cast<double>(k) / samples))) return false;
  return true;
}

Footprint footprintOf(const TriMesh& mesh, const Plan& plan) {
  std::vector<Polygon> loops;
  std::vector<std::vector<Eigen::Vector3d>> loops3d;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto heh : mesh.halfedges()) {
    if (!mesh.is_boundary(heh) || seen[heh.idx()]) continue;
    Polygon loop;
    std::vector<Eigen::Vector3d> loop3d;
    auto h = heh;
    do {
      seen[h.idx()] = 1;
      loop3d.push_back(toEigen(mesh.point(mesh.from_vertex_handle(h))));
      loop.push_back(plan(loop3d.back()));
      h = mesh.next_halfedge_handle(h);
    } while (h != heh && !seen[h.idx()]);
    loops.push_back(std::move(loop));
    loops3d.push_back(std::move(loop3d));
  }
  if (loops.empty())
    throw InvalidInput(
        "workflow 2: the surface has no boundary (a closed surface cannot be laid out in plan)");
  std::vector<size_t> order(loops.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::abs(signedArea(loops[a])) > std::abs(signedArea(loops[b]));
  });
  Footprint f;
  f.outer = loops[order[0]];
  f.outer3d = loops3d[order[0]];
  if (signedArea(f.outer) < 0)
    std::reverse(f.outer.begin(), f.outer.end()), std::reverse(f.outer3d.begin(), f.outer3d.end());
  for (size_t i = 1; i < order.size(); ++i) f.holes.push_back(loops[order[i]]);
  // Four corners and four arcs between them need an outline of some vertices: a one-triangle mesh
  // gave arcs of one point, read past their end (issue 40, found under ASan).
  constexpr size_t kFewestOutlineVertices = 8;
  if (f.outer.size() < kFewestOutlineVertices)
    throw InvalidInput(fmt::format(
        "workflow 2: the surface's outline has only {} vertices, too few to place four corners "
        "and their sides on; mesh it finer (surface.edge_length_m) or give patching.patches",
        f.outer.size()));
  f.tolerance = 0.5 * meanEdgeLength(mesh);
  return f;
}

std::pair<size_t, double> Arc::locate(double u) const {
  const double target = std::clamp(u, 0.0, 1.0) * s.back();
  size_t hi = std::upper_bound(s.begin(), s.end(), target) - s.begin();
  hi = std::clamp<size_t>(hi, 1, s.size() - 1);
  const double span = s[hi] - s[hi - 1];
  return {hi, span > 0 ? (target - s[hi - 1]) / span : 0.0};
}

Vec2 Arc::at(double u) const {
  if (points.size() < 2) return points.empty() ? Vec2::Zero() : points.front();
  const auto [hi, t] = locate(u);
  return (1.0 - t) * points[hi - 1] + t * points[hi];
}

Eigen::Vector3d Arc::at3d(double u) const {
  if (points3d.size() < 2) return points3d.empty() ? Eigen::Vector3d::Zero() : points3d.front();
  const auto [hi, t] = locate(u);
  return (1.0 - t) * points3d[hi - 1] + t * points3d[hi];
}

Arc arcOf(const Footprint& foot, size_t from, size_t to) {
  const Polygon& loop = foot.outer;
  Arc arc;
  for (size_t i = from;; i = (i + 1) % loop.size()) {
    arc.points.push_back(loop[i]);
    arc.points3d.push_back(foot.outer3d[i]);
    if (i == to) break;
  }
  arc.s.push_back(0.0);
  for (size_t i = 1; i < arc.points.size(); ++i)
    arc.s.push_back(arc.s.back() + (arc.points[i] - arc.points[i - 1]).norm());
  return arc;
}

PlanLifter::PlanLifter(const TriMesh& surface, const Plan& plan) : plan_(plan) {
  faces_.reserve(surface.n_faces());
  planFaces_.reserve(surface.n_faces());
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (auto fh : surface.faces()) {
    const auto ids = faceVertices(surface, fh.idx());
    std::array<Eigen::Vector3d, 3> p;
    std::array<Vec2, 3> r;
    for (int k = 0; k < 3; ++k) {
      p[k] = toEigen(surface.point(TriMesh::VertexHandle(ids[k])));
      r[k] = plan(p[k]);
      lo = lo.cwiseMin(r[k]), hi = hi.cwiseMax(r[k]);
    }
    faces_.push_back(p);
    planFaces_.push_back(r);
  }
  if (faces_.empty()) return;
  // About two faces per bin.
  const Vec2 extent = (hi - lo).cwiseMax(Vec2::Constant(1e-9));
  const double binSide =
      std::sqrt(extent.x() * extent.y() * 2.0 / static_cast<double>(faces_.size()));
  nx_ = std::clamp(static_cast<int>(std::ceil(extent.x() / binSide)), 1, 4096);
  ny_ = std::clamp(static_cast<int>(std::ceil(extent.y() / binSide)), 1, 4096);
  lo_ = lo;
  cell_ = Vec2(extent.x() / nx_, extent.y() / ny_);
  bins_.assign(static_cast<size_t>(nx_) * ny_, {});
  for (size_t f = 0; f < planFaces_.size(); ++f) {
    Vec2 flo = planFaces_[f][0], fhi = flo;
    for (const auto& r : planFaces_[f]) flo = flo.cwiseMin(r), fhi = fhi.cwiseMax(r);
    const int x0 = std::clamp(static_cast<int>((flo.x() - lo_.x()) / cell_.x()), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>((fhi.x() - lo_.x()) / cell_.x()), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>((flo.y() - lo_.y()) / cell_.y()), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>((fhi.y() - lo_.y()) / cell_.y()), 0, ny_ - 1);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y)
        bins_[static_cast<size_t>(x) * ny_ + y].push_back(static_cast<int>(f));
  }
}

namespace {
// Barycentric coordinates of q in the plan triangle r (false: degenerate).
bool barycentric(const std::array<Vec2, 3>& r, const Vec2& q, double& b0, double& b1, double& b2) {
  const Vec2 e1 = r[1] - r[0], e2 = r[2] - r[0], d = q - r[0];
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  if (std::abs(det) < 1e-300) return false;
  b1 = (d.x() * e2.y() - d.y() * e2.x()) / det;
  b2 = (e1.x() * d.y() - e1.y() * d.x()) / det;
  b0 = 1 - b1 - b2;
  return true;
}
}  // namespace

std::optional<Eigen::Vector3d> PlanLifter::liftInBins(const Vec2& q,
                                                      const std::optional<Eigen::Vector3d>& near,
                                                      int* sheets) const {
  const int x = static_cast<int>(std::floor((q.x() - lo_.x()) / cell_.x())),
            y = static_cast<int>(std::floor((q.y() - lo_.y()) / cell_.y()));
  if (bins_.empty() || x < 0 || y < 0 || x >= nx_ || y >= ny_) return std::nullopt;
  std::optional<Eigen::Vector3d> best;
  double bestScore = -std::numeric_limits<double>::infinity();
  int containing = 0;
  for (int f : bins_[static_cast<size_t>(x) * ny_ + y]) {
    double b0, b1, b2;
    if (!barycentric(planFaces_[f], q, b0, b1, b2) || std::min({b0, b1, b2}) < -1e-9) continue;
    const auto& p = faces_[f];
    const Eigen::Vector3d point = b0 * p[0] + b1 * p[1] + b2 * p[2];
    const double score = near ? -(point - *near).norm() : plan_.height(point);
    ++containing;
    if (score > bestScore) bestScore = score, best = point;
  }
  if (sheets) *sheets = containing;
  return best;
}

Eigen::Vector3d PlanLifter::lift(const Vec2& q, const std::optional<Eigen::Vector3d>& near,
                                 int* sheets) const {
  if (auto inside = liftInBins(q, near, sheets)) return *inside;
  if (sheets) *sheets = 0;
  // Off the surface in plan: the nearest point of the face whose barycentric excess is least.
  double bestOutside = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  for (size_t f = 0; f < faces_.size(); ++f) {
    double b0, b1, b2;
    if (!barycentric(planFaces_[f], q, b0, b1, b2)) continue;
    const double outside = std::max({-b0, -b1, -b2, 0.0});
    if (outside < bestOutside) {
      bestOutside = outside;
      const double c0 = std::max(b0, 0.0), c1 = std::max(b1, 0.0), c2 = std::max(b2, 0.0);
      const auto& p = faces_[f];
      best = (c0 * p[0] + c1 * p[1] + c2 * p[2]) / (c0 + c1 + c2);
    }
  }
  return best;
}

}  // namespace egg::patching
