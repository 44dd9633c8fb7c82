// Workflow 2's automatic initial layout (see workflow2.hpp).
#include "patching/workflow2.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "patching/injectivity.hpp"
#include "patching/layout.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace egg::patching {

void Workflow2Options::validate() const {
  if (!(maxPatchSizeM > 0.0)) throw InvalidInput("patching.max_patch_size_m must be positive");
  if (!(holeMarginRelative >= 0.0 && holeMarginRelative < 1.0)) throw InvalidInput("workflow 2: hole margin must lie in [0, 1)");
  if (!(peakSnapFraction >= 0.0 && peakSnapFraction <= 0.5)) throw InvalidInput("workflow 2: peak snap fraction must lie in [0, 0.5]");
}

namespace {

using Vec2 = Eigen::Vector2d;
using Polygon = std::vector<Vec2>;

// The plan: the surface seen along its least-variance direction (z for a roof given z up).
struct Plan {
  Eigen::Vector3d origin, e1, e2, normal;
  Vec2 operator()(const Eigen::Vector3d& p) const { return {(p - origin).dot(e1), (p - origin).dot(e2)}; }
};

Plan planOf(const TriMesh& mesh) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto vh : mesh.vertices()) mean += toEigen(mesh.point(vh));
  mean /= static_cast<double>(mesh.n_vertices());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d d = toEigen(mesh.point(vh)) - mean;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  Plan plan;
  plan.origin = mean;
  // A roof given z up keeps its x and y (so the layout reads in the model's own axes).
  if (std::abs(n.z()) > 0.9) {
    plan.normal = Eigen::Vector3d::UnitZ(), plan.e1 = Eigen::Vector3d::UnitX(), plan.e2 = Eigen::Vector3d::UnitY();
  } else {
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
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x()) in = !in;
  }
  return in;
}

double distanceToPolygon(const Polygon& poly, const Vec2& q) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    const Vec2 d = b - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - q).norm());
  }
  return best;
}

struct Footprint {
  Polygon outer;               // counter-clockwise
  std::vector<Eigen::Vector3d> outer3d;  // the same boundary vertices in space
  std::vector<Polygon> holes;
  double tolerance = 0.0;      // "on the boundary" (half a mean edge length)
  bool contains(const Vec2& q) const {
    const bool inOuter = insidePolygon(outer, q) || distanceToPolygon(outer, q) <= tolerance;
    if (!inOuter) return false;
    for (const auto& h : holes)
      if (insidePolygon(h, q) && distanceToPolygon(h, q) > tolerance) return false;
    return true;
  }
  // The segment stays on the footprint (sampled), and off the holes.
  bool containsSegment(const Vec2& a, const Vec2& b) const {
    const int samples = 24;
    for (int k = 0; k <= samples; ++k)
      if (!contains(a + (b - a) * (static_cast<double>(k) / samples))) return false;
    return true;
  }
};

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
  if (loops.empty()) throw InvalidInput("workflow 2: the surface has no boundary (a closed surface cannot be laid out in plan)");
  std::vector<size_t> order(loops.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return std::abs(signedArea(loops[a])) > std::abs(signedArea(loops[b])); });
  Footprint f;
  f.outer = loops[order[0]];
  f.outer3d = loops3d[order[0]];
  if (signedArea(f.outer) < 0) std::reverse(f.outer.begin(), f.outer.end()), std::reverse(f.outer3d.begin(), f.outer3d.end());
  for (size_t i = 1; i < order.size(); ++i) f.holes.push_back(loops[order[i]]);
  f.tolerance = 0.5 * meanEdgeLength(mesh);
  return f;
}

// A piece of the outer boundary between two of its vertices, counter-clockwise, by arc length.
struct Arc {
  std::vector<Vec2> points;
  std::vector<Eigen::Vector3d> points3d;
  std::vector<double> s;
  // Where arc parameter u falls: the segment's end index and the fraction along it.
  std::pair<size_t, double> locate(double u) const {
    const double target = std::clamp(u, 0.0, 1.0) * s.back();
    size_t hi = std::upper_bound(s.begin(), s.end(), target) - s.begin();
    hi = std::clamp<size_t>(hi, 1, s.size() - 1);
    const double span = s[hi] - s[hi - 1];
    return {hi, span > 0 ? (target - s[hi - 1]) / span : 0.0};
  }
  // The boundary point in space at u (the loop is the mesh's own boundary), and in the plan.
  Eigen::Vector3d at3d(double u) const {
    const auto [hi, t] = locate(u);
    return (1.0 - t) * points3d[hi - 1] + t * points3d[hi];
  }
  Vec2 at(double u) const {
    const auto [hi, t] = locate(u);
    return (1.0 - t) * points[hi - 1] + t * points[hi];
  }
};

Arc arcOf(const Footprint& foot, size_t from, size_t to) {
  const Polygon& loop = foot.outer;
  Arc arc;
  for (size_t i = from;; i = (i + 1) % loop.size()) {
    arc.points.push_back(loop[i]);
    arc.points3d.push_back(foot.outer3d[i]);
    if (i == to) break;
  }
  arc.s.push_back(0.0);
  for (size_t i = 1; i < arc.points.size(); ++i) arc.s.push_back(arc.s.back() + (arc.points[i] - arc.points[i - 1]).norm());
  return arc;
}

Vec2 lerp(const Vec2& a, const Vec2& b, double t) { return (1.0 - t) * a + t * b; }

// One block: four plan curves (side 0 corner0 -> corner1, side 1 corner1 -> corner2, side 2
// corner3 -> corner2 and side 3 corner0 -> corner3, i.e. the Coons patch's u and v directions) and
// its grid of nu x nv patches.
struct Block {
  std::function<Vec2(double)> bottom, top, left, right;  // C0(u), C2(u), D3(v), D1(v)
  std::function<Eigen::Vector3d(double)> bottom3d, top3d, left3d, right3d;  // the same in space, for sides on the boundary
  int nu = 1, nv = 1;
  bool bottomOnBoundary = false, topOnBoundary = false, leftOnBoundary = false, rightOnBoundary = false;
  Vec2 coons(double u, double v) const {
    const Vec2 p00 = bottom(0), p10 = bottom(1), p01 = top(0), p11 = top(1);
    return (1 - v) * bottom(u) + v * top(u) + (1 - u) * left(v) + u * right(v) -
           ((1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11);
  }
  double maxCellDiagonal(double stretch, bool& alongU) const {
    double worst = 0.0;
    alongU = true;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const Vec2 a = coons(double(i) / nu, double(j) / nv), b = coons(double(i + 1) / nu, double(j) / nv);
        const Vec2 c = coons(double(i + 1) / nu, double(j + 1) / nv), d = coons(double(i) / nu, double(j + 1) / nv);
        const double diag = stretch * std::max((c - a).norm(), (d - b).norm());
        if (diag > worst) worst = diag, alongU = (b - a).norm() + (c - d).norm() >= (d - a).norm() + (c - b).norm();
      }
    return worst;
  }
};

}  // namespace

Workflow2Layout proposeLayout(const TriMesh& surface, const Workflow2Options& options, const geodesic::DistanceSolver* solver) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (surface.n_faces() == 0) throw InvalidInput("workflow 2: the surface has no faces");
  Workflow2Layout out;
  const Plan plan = planOf(surface);
  const Footprint foot = footprintOf(surface, plan);
  out.holes = static_cast<int>(foot.holes.size());
  if (foot.holes.size() > 1)
    throw InvalidInput(fmt::format("workflow 2: the surface has {} holes; the automatic layout handles at most one so far "
                                   "(give patching.patches, or close the holes)",
                                   foot.holes.size()));

  // Plan lengths understate surface lengths on a steep surface: scale by the square root of the
  // area ratio (a fair mean stretch).
  double planArea = std::abs(signedArea(foot.outer));
  for (const auto& h : foot.holes) planArea -= std::abs(signedArea(h));
  const double stretch = std::sqrt(std::max(1.0, surfaceArea(surface) / std::max(planArea, 1e-300)));

  // Outer corners: the boundary points extreme in the four diagonal directions of its box.
  Vec2 lo = foot.outer.front(), hi = foot.outer.front();
  for (const auto& p : foot.outer) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec2 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const std::array<Vec2, 4> quadrant{Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};
  // Only convex points of the boundary may be block corners (its convex hull's vertices): a corner
  // in a concave neck, as between the Lilium's lobes, would make its patch reflex there.
  std::vector<char> onHull(foot.outer.size(), 0);
  {
    std::vector<size_t> order(foot.outer.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return foot.outer[a].x() < foot.outer[b].x() || (foot.outer[a].x() == foot.outer[b].x() && foot.outer[a].y() < foot.outer[b].y());
    });
    const auto cross = [&](size_t o, size_t a, size_t b) {
      const Vec2 u = foot.outer[a] - foot.outer[o], w = foot.outer[b] - foot.outer[o];
      return u.x() * w.y() - u.y() * w.x();
    };
    std::vector<size_t> hull;
    for (int pass = 0; pass < 2; ++pass) {
      const size_t start = hull.size();
      for (size_t k = 0; k < order.size(); ++k) {
        const size_t i = pass == 0 ? order[k] : order[order.size() - 1 - k];
        while (hull.size() >= start + 2 && cross(hull[hull.size() - 2], hull.back(), i) <= 0) hull.pop_back();
        hull.push_back(i);
      }
      hull.pop_back();
    }
    for (size_t i : hull) onHull[i] = 1;
  }
  std::array<size_t, 4> cornerIndex{};
  for (int k = 0; k < 4; ++k) {
    double best = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < foot.outer.size(); ++i) {
      if (!onHull[i]) continue;
      const Vec2 d = (foot.outer[i] - centre).cwiseQuotient(half);
      const double score = quadrant[k].dot(d);
      if (score > best) best = score, cornerIndex[k] = i;
    }
  }
  std::array<Arc, 4> arcs;
  for (int k = 0; k < 4; ++k) arcs[k] = arcOf(foot, cornerIndex[k], cornerIndex[(k + 1) % 4]);

  std::vector<Block> blocks;
  if (foot.holes.empty()) {
    Block b;
    b.bottom = [a = arcs[0]](double u) { return a.at(u); };
    b.right = [a = arcs[1]](double v) { return a.at(v); };
    b.top = [a = arcs[2]](double u) { return a.at(1.0 - u); };
    b.left = [a = arcs[3]](double v) { return a.at(1.0 - v); };
    b.bottom3d = [a = arcs[0]](double u) { return a.at3d(u); };
    b.right3d = [a = arcs[1]](double v) { return a.at3d(v); };
    b.top3d = [a = arcs[2]](double u) { return a.at3d(1.0 - u); };
    b.left3d = [a = arcs[3]](double v) { return a.at3d(1.0 - v); };
    b.bottomOnBoundary = b.topOnBoundary = b.leftOnBoundary = b.rightOnBoundary = true;
    blocks.push_back(b);
    out.notes.push_back("one block between the four outer corners");
  } else {
    // The box tangent to the hole, inflated a little so that its sides clear the hole.
    Vec2 hlo = foot.holes[0].front(), hhi = foot.holes[0].front();
    for (const auto& p : foot.holes[0]) hlo = hlo.cwiseMin(p), hhi = hhi.cwiseMax(p);
    const Vec2 hc = 0.5 * (hlo + hhi), hh = 0.5 * (hhi - hlo) * (1.0 + options.holeMarginRelative);
    std::array<Vec2, 4> inner;
    for (int k = 0; k < 4; ++k) inner[k] = hc + quadrant[k].cwiseProduct(hh);
    for (int k = 0; k < 4; ++k) {
      const Vec2 o0 = arcs[k].points.front(), o1 = arcs[k].points.back(), i0 = inner[k], i1 = inner[(k + 1) % 4];
      Block b;
      b.bottom = [a = arcs[k]](double u) { return a.at(u); };
      b.bottom3d = [a = arcs[k]](double u) { return a.at3d(u); };
      b.top = [i0, i1](double u) { return lerp(i0, i1, u); };
      b.left = [o0, i0](double v) { return lerp(o0, i0, v); };
      b.right = [o1, i1](double v) { return lerp(o1, i1, v); };
      b.bottomOnBoundary = true;
      blocks.push_back(b);
    }
    out.notes.push_back("a ring of four blocks between the outer corners and the box tangent to the hole");
  }
  out.blocks = static_cast<int>(blocks.size());

  // Counts: grow the count along the longer direction of the worst cell until every cell's
  // diagonal fits. Around a hole the radial count (v) is shared by the ring's blocks.
  for (int guard = 0; guard < 200; ++guard) {
    bool changed = false;
    for (auto& b : blocks) {
      bool alongU = true;
      if (b.maxCellDiagonal(stretch, alongU) <= options.maxPatchSizeM) continue;
      if (alongU) ++b.nu;
      else {
        const int nv = b.nv + 1;
        for (auto& other : blocks)
          if (foot.holes.empty() ? &other == &b : true) other.nv = nv;
      }
      changed = true;
    }
    if (!changed) break;
  }

  // Nodes, shared where blocks meet (same plan point to rounding).
  const double mergeTolerance = 1e-6 * std::max(half.x(), half.y());
  std::vector<Vec2> nodes;
  std::vector<char> onBoundary, fixedNode;  // fixed: on the boundary or on the box around the hole
  std::vector<std::optional<Eigen::Vector3d>> onSurface;  // boundary nodes: their point of the boundary in space
  std::vector<std::optional<Eigen::Vector3d>> startedOn;  // boundary nodes: where they were before being pulled in
  const auto nodeId = [&](const Vec2& p, bool boundary) {
    for (size_t i = 0; i < nodes.size(); ++i)
      if ((nodes[i] - p).norm() <= mergeTolerance) {
        onBoundary[i] = onBoundary[i] || boundary;
        return static_cast<int>(i);
      }
    nodes.push_back(p);
    onBoundary.push_back(boundary);
    fixedNode.push_back(0);
    onSurface.emplace_back();
    startedOn.emplace_back();
    return static_cast<int>(nodes.size()) - 1;
  };
  std::vector<std::vector<std::vector<int>>> grid(blocks.size());
  std::vector<std::pair<int, int>> boundaryChords;  // consecutive boundary nodes
  std::vector<std::pair<int, int>> inwards;         // boundary node -> its neighbour one step inside
  for (size_t bi = 0; bi < blocks.size(); ++bi) {
    const Block& b = blocks[bi];
    grid[bi].assign(b.nu + 1, std::vector<int>(b.nv + 1));
    for (int i = 0; i <= b.nu; ++i)
      for (int j = 0; j <= b.nv; ++j) {
        const bool boundary = (j == 0 && b.bottomOnBoundary) || (j == b.nv && b.topOnBoundary) || (i == 0 && b.leftOnBoundary) ||
                              (i == b.nu && b.rightOnBoundary);
        const double u = double(i) / b.nu, v = double(j) / b.nv;
        const int id = grid[bi][i][j] = nodeId(b.coons(u, v), boundary);
        if (j == 0 && b.bottomOnBoundary) onSurface[id] = b.bottom3d(u);
        else if (j == b.nv && b.topOnBoundary) onSurface[id] = b.top3d(u);
        else if (i == 0 && b.leftOnBoundary) onSurface[id] = b.left3d(v);
        else if (i == b.nu && b.rightOnBoundary) onSurface[id] = b.right3d(v);
        if (onSurface[id]) startedOn[id] = onSurface[id];
        const bool onHoleBox = !foot.holes.empty() && j == b.nv;
        if (boundary || onHoleBox) fixedNode[grid[bi][i][j]] = 1;
      }
    const auto& g = grid[bi];
    for (int i = 0; i < b.nu; ++i) {
      if (b.bottomOnBoundary) boundaryChords.emplace_back(g[i][0], g[i + 1][0]);
      if (b.topOnBoundary) boundaryChords.emplace_back(g[i][b.nv], g[i + 1][b.nv]);
    }
    for (int j = 0; j < b.nv; ++j) {
      if (b.leftOnBoundary) boundaryChords.emplace_back(g[0][j], g[0][j + 1]);
      if (b.rightOnBoundary) boundaryChords.emplace_back(g[b.nu][j], g[b.nu][j + 1]);
    }
    // Where a boundary node moves when pulled in: towards the block's centre.
    for (int i = 0; i <= b.nu; ++i)
      for (int j = 0; j <= b.nv; ++j)
        if (onBoundary[g[i][j]]) {
          const int ii = std::clamp(i, 1, std::max(1, b.nu - 1)), jj = std::clamp(j, 1, std::max(1, b.nv - 1));
          const int to = (b.nu >= 2 || b.nv >= 2) ? g[std::min(ii, b.nu)][std::min(jj, b.nv)] : -1;
          inwards.emplace_back(g[i][j], to);
        }
  }
  const Vec2 blockCentre = [&] {
    Vec2 c = Vec2::Zero();
    for (const auto& p : nodes) c += p;
    return Vec2(c / static_cast<double>(nodes.size()));
  }();

  // Moves the marked boundary nodes 8 % of the way to their inward targets (they leave the
  // boundary); false when none is marked.
  std::vector<char> moved(nodes.size(), 0);
  const auto pullIn = [&](const std::vector<char>& bad) {
    if (std::none_of(bad.begin(), bad.end(), [](char c) { return c; })) return false;
    for (const auto& [node, towards] : inwards) {
      if (!bad[node]) continue;
      const Vec2 target = towards >= 0 && towards != node ? nodes[towards] : blockCentre;
      nodes[node] = lerp(nodes[node], target, 0.08);
      onSurface[node].reset();
      moved[node] = 1;
      ++out.nodesPulledIn;
    }
    return true;
  };

  // A chord along a concave stretch leaves the footprint: pull its ends inwards until it does not.
  for (int round = 0; round < 10; ++round) {
    std::vector<char> bad(nodes.size(), 0);
    for (const auto& [a, b] : boundaryChords)
      if (!foot.containsSegment(nodes[a], nodes[b])) bad[a] = bad[b] = 1;
    if (!pullIn(bad)) break;
  }

  // High K first (Algorithm 2): an interior node near a K peak becomes a corner at p_max.
  const auto peaks = findSurfacePeaks(surface);
  std::vector<char> snapped(nodes.size(), 0);
  double cell = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : boundaryChords) cell = std::min(cell, (nodes[a] - nodes[b]).norm());
  for (const auto& peak : peaks) {
    if (peak.onBoundary) continue;
    const Vec2 p = plan(peak.position);
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (fixedNode[i] || snapped[i]) continue;
      const double d = (nodes[i] - p).norm();
      if (d < bestDistance) bestDistance = d, best = static_cast<int>(i);
    }
    if (best >= 0 && bestDistance <= options.peakSnapFraction * cell) {
      nodes[best] = p;
      snapped[best] = 1;
      ++out.peaksSnapped;
    }
  }

  // Lift the nodes onto the surface. A node on the boundary is its point of the boundary in space;
  // any other the highest point of the surface over its plan point (the roof seen from above:
  // near a vertical wall, as at the Lilium's base, the plan can see the surface twice).
  int overhangs = 0;
  const auto lift = [&](size_t i) -> Eigen::Vector3d {
    if (onSurface[i]) return *onSurface[i];
    const Vec2& q = nodes[i];
    double bestOutside = std::numeric_limits<double>::infinity(), bestHeight = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    int containing = 0;
    for (auto fh : surface.faces()) {
      const auto ids = faceVertices(surface, fh.idx());
      std::array<Eigen::Vector3d, 3> p;
      std::array<Vec2, 3> r;
      for (int k = 0; k < 3; ++k) p[k] = toEigen(surface.point(TriMesh::VertexHandle(ids[k]))), r[k] = plan(p[k]);
      const Vec2 e1 = r[1] - r[0], e2 = r[2] - r[0], d = q - r[0];
      const double det = e1.x() * e2.y() - e1.y() * e2.x();
      if (std::abs(det) < 1e-300) continue;
      const double b1 = (d.x() * e2.y() - d.y() * e2.x()) / det, b2 = (e1.x() * d.y() - e1.y() * d.x()) / det, b0 = 1 - b1 - b2;
      const double outside = std::max({-b0, -b1, -b2, 0.0});
      if (outside <= 1e-9) {
        const Eigen::Vector3d point = b0 * p[0] + b1 * p[1] + b2 * p[2];
        // A corner pulled in from the boundary stays on the sheet of surface it came from (nearest
        // to its boundary point: not up an overhanging wall); any other takes the upper sheet.
        const double height = startedOn[i] ? -(point - *startedOn[i]).norm() : (point - plan.origin).dot(plan.normal);
        ++containing;
        if (height > bestHeight) bestHeight = height, best = point;
      } else if (containing == 0 && outside < bestOutside) {
        bestOutside = outside;
        const double c0 = std::max(b0, 0.0), c1 = std::max(b1, 0.0), c2 = std::max(b2, 0.0);
        best = (c0 * p[0] + c1 * p[1] + c2 * p[2]) / (c0 + c1 + c2);
      }
    }
    if (containing > 1) ++overhangs;
    return best;
  };
  std::vector<Eigen::Vector3d> lifted(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) lifted[i] = lift(i);

  // The plan test above cannot see a chord that hugs a wall (the Lilium's base is vertical): trace
  // each boundary chord on the surface, and where it bends round a boundary vertex, pull its ends
  // further in.
  if (solver) {
    const double turnTolerance = 1e-3;
    for (int round = 0; round < 12; ++round) {
      std::vector<char> bad(nodes.size(), 0);
      for (const auto& [a, b] : boundaryChords) {
        const auto path = solver->path(geodesic::snapToSurface(surface, lifted[a]), geodesic::snapToSurface(surface, lifted[b]));
        for (int v : path.bendVertices)
          if (surface.is_boundary(TriMesh::VertexHandle(v)) &&
              polylineTurnsAt(path.positions, toEigen(surface.point(TriMesh::VertexHandle(v))), turnTolerance))
            bad[a] = bad[b] = 1;
      }
      std::fill(moved.begin(), moved.end(), 0);
      if (!pullIn(bad)) break;
      for (size_t i = 0; i < nodes.size(); ++i)
        if (moved[i]) lifted[i] = lift(i);
    }
  }
  out.corners = lifted;
  if (overhangs) out.notes.push_back(fmt::format("{} corner(s) over a part of the surface that the plan sees twice: the upper one taken", overhangs));
  for (size_t bi = 0; bi < blocks.size(); ++bi)
    for (int i = 0; i < blocks[bi].nu; ++i)
      for (int j = 0; j < blocks[bi].nv; ++j) {
        const auto& g = grid[bi];
        out.quads.push_back({g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]});
      }
  std::string counts;
  for (const auto& b : blocks) counts += fmt::format("{}{}x{}", counts.empty() ? "" : ", ", b.nu, b.nv);
  out.notes.push_back(fmt::format("patches per block: {} (cells up to {:.3g} m across, plan lengths stretched by {:.3f})", counts,
                                  options.maxPatchSizeM, stretch));
  if (out.peaksSnapped) out.notes.push_back(fmt::format("{} grid corner(s) moved onto K peaks", out.peaksSnapped));
  if (out.nodesPulledIn) out.notes.push_back(fmt::format("boundary corners pulled inwards {} time(s) off concave stretches", out.nodesPulledIn));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::patching
