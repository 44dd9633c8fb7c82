// Workflow 2's automatic initial layout (see workflow2.hpp).
#include "patching/workflow2.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "patching/injectivity.hpp"
#include "patching/footprint.hpp"
#include "patching/layout.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>

namespace egg::patching {

void Workflow2Options::validate() const {
  if (!(maxPatchSizeM > 0.0)) throw InvalidInput("patching.max_patch_size_m must be positive");
  if (!(holeMarginRelative >= 0.0 && holeMarginRelative < 1.0)) throw InvalidInput("workflow 2: hole margin must lie in [0, 1)");
  if (!(peakSnapFraction >= 0.0 && peakSnapFraction <= 0.5)) throw InvalidInput("workflow 2: peak snap fraction must lie in [0, 0.5]");
}

namespace {

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
  // Node (i, j) of an nu x nv grid in space, when it lies on a boundary side of the design surface.
  std::optional<Eigen::Vector3d> boundaryPoint(int i, int j, int nu_, int nv_) const {
    const double u = double(i) / nu_, v = double(j) / nv_;
    if (j == 0 && bottomOnBoundary) return bottom3d(u);
    if (j == nv_ && topOnBoundary) return top3d(u);
    if (i == 0 && leftOnBoundary) return left3d(v);
    if (i == nu_ && rightOnBoundary) return right3d(v);
    return std::nullopt;
  }
};

// A peak of K as the grid sees it: its plan point and injectivity radius.
struct PlanPeak {
  Vec2 at;
  double radiusM;
};

// An nu x nv grid of one block tried before it is built: Algorithm 2's high-K regions first (the
// interior node nearest a peak moves onto it when within `snapFraction` of its cells), and the
// largest cell diagonal in space (chords between the nodes lifted onto the surface: a steep cell
// is measured as it is, not through a mean stretch of the plan).
struct GridTrial {
  std::vector<std::vector<Vec2>> plan;  // [i][j]
  double worstDiagonalM = 0.0;
  bool worstAlongU = true;        // the worst cell is longer along u
  std::vector<std::vector<char>> onPeak;  // [i][j]: the node moved onto a peak
  std::vector<char> peakOnNode;           // per peak
  int snapped = 0;
  int peaksLeftInside = 0;        // peaks not on a node whose circle is smaller than the cells
};

// Whether interior node (i, j) of plan grid g may move to `to`: its move along each grid direction
// stays within `fraction` of the shorter grid line from it in that direction, so that the four
// cells round it stay convex and none shrinks to a sliver.
bool snapAllowed(const std::vector<std::vector<Vec2>>& g, int i, int j, const Vec2& to, double fraction) {
  const Vec2 du = g[i + 1][j] - g[i - 1][j], dv = g[i][j + 1] - g[i][j - 1];
  const double su = std::min((g[i + 1][j] - g[i][j]).norm(), (g[i][j] - g[i - 1][j]).norm());
  const double sv = std::min((g[i][j + 1] - g[i][j]).norm(), (g[i][j] - g[i][j - 1]).norm());
  if (!(du.norm() > 0 && dv.norm() > 0)) return false;
  const Vec2 move = to - g[i][j];
  return std::abs(move.dot(du.normalized())) <= fraction * su && std::abs(move.dot(dv.normalized())) <= fraction * sv;
}

GridTrial tryGrid(const Block& b, int nu, int nv, const PlanLifter& lifter, const std::vector<PlanPeak>& peaks, double snapFraction) {
  GridTrial t;
  t.plan.assign(nu + 1, std::vector<Vec2>(nv + 1));
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) t.plan[i][j] = b.coons(double(i) / nu, double(j) / nv);
  t.onPeak.assign(nu + 1, std::vector<char>(nv + 1, 0));
  t.peakOnNode.assign(peaks.size(), 0);
  auto& taken = t.onPeak;
  auto& onNode = t.peakOnNode;
  for (size_t k = 0; k < peaks.size(); ++k) {
    int bi = -1, bj = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 1; i < nu; ++i)
      for (int j = 1; j < nv; ++j)
        if (!taken[i][j] && (t.plan[i][j] - peaks[k].at).norm() < best) best = (t.plan[i][j] - peaks[k].at).norm(), bi = i, bj = j;
    if (bi >= 0 && snapAllowed(t.plan, bi, bj, peaks[k].at, snapFraction)) {
      t.plan[bi][bj] = peaks[k].at;
      taken[bi][bj] = 1;
      onNode[k] = 1;
      ++t.snapped;
    }
  }
  // The other interior nodes even out the cells round the moved ones (Gauss-Seidel sweeps of the
  // grid Laplacian, in a fixed order: the same grid on any thread count).
  if (t.snapped)
    for (int sweep = 0; sweep < 40; ++sweep)
      for (int i = 1; i < nu; ++i)
        for (int j = 1; j < nv; ++j)
          if (!taken[i][j]) t.plan[i][j] = 0.25 * (t.plan[i - 1][j] + t.plan[i + 1][j] + t.plan[i][j - 1] + t.plan[i][j + 1]);
  std::vector<std::vector<Eigen::Vector3d>> space(nu + 1, std::vector<Eigen::Vector3d>(nv + 1));
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const auto onBoundary = taken[i][j] ? std::nullopt : b.boundaryPoint(i, j, nu, nv);
      space[i][j] = onBoundary ? *onBoundary : lifter.lift(t.plan[i][j]);
    }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto &a = space[i][j], &c = space[i + 1][j + 1], &bb = space[i + 1][j], &d = space[i][j + 1];
      const double diag = std::max((c - a).norm(), (d - bb).norm());
      if (diag > t.worstDiagonalM)
        t.worstDiagonalM = diag, t.worstAlongU = (bb - a).norm() + (c - d).norm() >= (d - a).norm() + (c - bb).norm();
    }
  // Expression 3.1 is "only useful as a quick check" (3.4.1): members cross a cell in about its
  // diagonal, and a 1.5 x 2 m cell of a bump whose circle is 2.51 m already fails η; hence the margin.
  const double peakReach = 1.5;
  for (size_t k = 0; k < peaks.size(); ++k)
    if (!onNode[k] && peaks[k].radiusM < peakReach * t.worstDiagonalM) ++t.peaksLeftInside;
  return t;
}

// How far the geodesic between two plan points stays outside the hole: the least signed plan
// distance of the traced path to the hole's outline (negative inside), -infinity when the path
// bends round a boundary vertex (it wraps the hole or hugs the boundary).
double holeClearance(const Vec2& from, const Vec2& to, const Polygon& hole, const Plan& plan, const PlanLifter& lifter,
                     const TriMesh& surface, const geodesic::DistanceSolver& solver) {
  const auto path = solver.path(geodesic::snapToSurface(surface, lifter.lift(from)), geodesic::snapToSurface(surface, lifter.lift(to)));
  for (int v : path.bendVertices)
    if (surface.is_boundary(TriMesh::VertexHandle(v)) && polylineTurnsAt(path.positions, toEigen(surface.point(TriMesh::VertexHandle(v))), 1e-3))
      return -std::numeric_limits<double>::infinity();
  double clearance = std::numeric_limits<double>::infinity();
  for (const auto& x : path.positions) {
    const Vec2 q = plan(x);
    clearance = std::min(clearance, insidePolygon(hole, q) ? -distanceToPolygon(hole, q) : distanceToPolygon(hole, q));
  }
  return clearance;
}

// Tangent sides round a hole (Section 3.4.3): the corners of the box round the hole move towards
// its centre until the traced sides just clear it, by `target`: first all four by one factor, then
// each alone. Geodesics bow away from the hole where K < 0 around it (the Great Court), so the
// plan's tangent box leaves more than the unavoidable ring between a square and its circle.
// Returns the final least clearance.
double tightenHoleBox(std::array<double, 4>& scale, const std::function<Vec2(int)>& cornerAt, const Polygon& hole, const Plan& plan,
                      const PlanLifter& lifter, const TriMesh& surface, const geodesic::DistanceSolver& solver, double target) {
  const auto sideClearance = [&](int k) { return holeClearance(cornerAt(k), cornerAt((k + 1) % 4), hole, plan, lifter, surface, solver); };
  const auto feasible = [&](std::initializer_list<int> sides) {
    for (int k : sides)
      if (!(sideClearance(k) >= target)) return false;
    return true;
  };
  const double floor = 0.5;  // half the box: its sides cut through the hole
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k < (pass == 0 ? 1 : 4); ++k) {
      const auto set = [&](double s) {
        if (pass == 0) scale.fill(s);
        else scale[k] = s;
      };
      const std::initializer_list<int> all{0, 1, 2, 3};
      const auto ok = [&] { return pass == 0 ? feasible(all) : feasible({(k + 3) % 4, k}); };
      double hi = scale[k], lo = floor;
      set(hi);
      if (!ok()) return -1.0;  // the inflated box itself does not clear the hole: leave it as it is
      for (int it = 0; it < 10; ++it) {
        const double mid = 0.5 * (lo + hi);
        set(mid);
        if (ok()) hi = mid;
        else lo = mid;
      }
      set(hi);
    }
  }
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) least = std::min(least, sideClearance(k));
  return least;
}

}  // namespace

Workflow2Layout proposeLayout(const TriMesh& surface, const Workflow2Options& options, const geodesic::DistanceSolver* solver) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (surface.n_faces() == 0) throw InvalidInput("workflow 2: the surface has no faces");
  Workflow2Layout out;
  const Plan plan = planOf(surface);
  const Footprint foot = footprintOf(surface, plan);
  const PlanLifter lifter(surface, plan);
  out.holes = static_cast<int>(foot.holes.size());
  if (foot.holes.size() > 1)
    throw InvalidInput(fmt::format("workflow 2: the surface has {} holes; the automatic layout handles at most one so far "
                                   "(give patching.patches, or close the holes)",
                                   foot.holes.size()));

  // Outer corners: the boundary points extreme in the four diagonal directions of its box. Only
  // convex points of the boundary may be block corners (its convex hull's vertices): a corner in a
  // concave neck, as between the Lilium's lobes, would make its patch reflex there.
  Vec2 lo = foot.outer.front(), hi = foot.outer.front();
  for (const auto& p : foot.outer) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec2 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const std::array<Vec2, 4> quadrant{Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};
  const std::vector<char> onHull = convexHullMarks(foot.outer);
  std::array<size_t, 4> cornerIndex{};
  for (int k = 0; k < 4; ++k) {
    double best = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < foot.outer.size(); ++i) {
      if (!onHull[i]) continue;
      const double score = quadrant[k].dot((foot.outer[i] - centre).cwiseQuotient(half));
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
    // The box tangent to the hole, inflated a little so that its sides clear the hole; with the
    // solver, its corners then move in until the traced sides just clear it.
    Vec2 hlo = foot.holes[0].front(), hhi = foot.holes[0].front();
    for (const auto& p : foot.holes[0]) hlo = hlo.cwiseMin(p), hhi = hhi.cwiseMax(p);
    const Vec2 hc = 0.5 * (hlo + hhi), hh = 0.5 * (hhi - hlo) * (1.0 + options.holeMarginRelative);
    std::array<double, 4> scale{1.0, 1.0, 1.0, 1.0};
    const auto cornerAt = [&](int k) { return Vec2(hc + scale[k] * quadrant[k].cwiseProduct(hh)); };
    if (solver) {
      const double clearance = tightenHoleBox(scale, cornerAt, foot.holes[0], plan, lifter, surface, *solver, foot.tolerance);
      if (clearance >= 0)
        out.notes.push_back(fmt::format("box round the hole tightened to sides {:.2f} m clear of it (corners at {:.3f}, {:.3f}, {:.3f}, {:.3f} of the "
                                        "tangent box)",
                                        clearance, scale[0], scale[1], scale[2], scale[3]));
    }
    std::array<Vec2, 4> inner;
    for (int k = 0; k < 4; ++k) inner[k] = cornerAt(k);
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

  const auto surfacePeaks = findSurfacePeaks(surface);
  std::vector<PlanPeak> peaks;
  for (const auto& peak : surfacePeaks)
    if (!peak.onBoundary) {
      peaks.push_back({plan(peak.position), peak.radiusM});
    }

  // Counts. One block: every grid up to a bound is screened and the one predicting the fewest
  // patches kept, a peak left inside a cell larger than its circle counting as the three more
  // patches Workflow 1's corner split will make (ties: the smaller cells). Around a hole the count
  // along the worst cell grows until every cell fits, the radial count (v) shared by the ring.
  if (foot.holes.empty()) {
    Block& b = blocks.front();
    const int bound = 16;
    int bestPredicted = std::numeric_limits<int>::max();
    double bestDiagonal = std::numeric_limits<double>::infinity();
    for (int nu = 1; nu <= bound; ++nu)
      for (int nv = 1; nv <= bound; ++nv) {
        if (nu * nv > bestPredicted) continue;  // cannot win
        const GridTrial t = tryGrid(b, nu, nv, lifter, peaks, options.peakSnapFraction);
        ++out.candidatesScreened;
        if (t.worstDiagonalM > options.maxPatchSizeM) continue;
        const int predicted = nu * nv + 3 * t.peaksLeftInside;
        if (predicted < bestPredicted || (predicted == bestPredicted && t.worstDiagonalM < bestDiagonal))
          bestPredicted = predicted, bestDiagonal = t.worstDiagonalM, b.nu = nu, b.nv = nv;
      }
    if (bestPredicted == std::numeric_limits<int>::max())
      throw InvalidInput(fmt::format("workflow 2: no grid of up to {} x {} patches has cells within patching.max_patch_size_m = {} m", bound, bound,
                                     options.maxPatchSizeM));
  } else {
    for (int guard = 0; guard < 200; ++guard) {
      bool changed = false;
      for (auto& b : blocks) {
        const GridTrial t = tryGrid(b, b.nu, b.nv, lifter, {}, 0.0);
        ++out.candidatesScreened;
        if (t.worstDiagonalM <= options.maxPatchSizeM) continue;
        if (t.worstAlongU) {
          ++b.nu;
        } else {
          const int nv = b.nv + 1;
          for (auto& other : blocks) other.nv = nv;
        }
        changed = true;
      }
      if (!changed) break;
    }
  }

  // Nodes, shared where blocks meet (same plan point to rounding).
  const double mergeTolerance = 1e-6 * std::max(half.x(), half.y());
  std::vector<Vec2> nodes;
  std::vector<char> onBoundary, fixedNode;  // fixed: on the boundary or on the box around the hole
  std::vector<std::optional<Eigen::Vector3d>> onSurface;  // boundary nodes: their point of the boundary in space
  std::vector<std::optional<Eigen::Vector3d>> startedOn;  // boundary nodes: where they were before being pulled in
  std::vector<std::array<int, 3>> interiorOf;             // interior nodes: (block, i, j) in the plain grids below
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
    interiorOf.push_back({-1, -1, -1});
    return static_cast<int>(nodes.size()) - 1;
  };
  std::vector<std::vector<std::vector<int>>> grid(blocks.size());
  std::vector<std::vector<std::vector<Vec2>>> plainGrids;
  std::vector<std::pair<int, int>> boundaryChords;  // consecutive boundary nodes
  std::vector<std::pair<int, int>> inwards;         // boundary node -> its neighbour one step inside
  for (size_t bi = 0; bi < blocks.size(); ++bi) {
    const Block& b = blocks[bi];
    plainGrids.push_back(tryGrid(b, b.nu, b.nv, lifter, {}, 0.0).plan);
    const auto& plain = plainGrids.back();
    grid[bi].assign(b.nu + 1, std::vector<int>(b.nv + 1));
    for (int i = 0; i <= b.nu; ++i)
      for (int j = 0; j <= b.nv; ++j) {
        const auto boundaryPoint = b.boundaryPoint(i, j, b.nu, b.nv);
        const int id = grid[bi][i][j] = nodeId(plain[i][j], boundaryPoint.has_value());
        if (boundaryPoint) onSurface[id] = startedOn[id] = boundaryPoint;
        const bool onHoleBox = !foot.holes.empty() && j == b.nv;
        if (boundaryPoint || onHoleBox) fixedNode[id] = 1;
        if (i > 0 && i < b.nu && j > 0 && j < b.nv && interiorOf[id][0] < 0) interiorOf[id] = {static_cast<int>(bi), i, j};
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
  // With the solver the traced test below decides instead: a plan test is wrong where the wall is
  // vertical (the Lilium's base: its outline is a geodesic there, concave in plan or not).
  for (int round = 0; round < (solver ? 0 : 10); ++round) {
    std::vector<char> bad(nodes.size(), 0);
    for (const auto& [a, b] : boundaryChords)
      if (!foot.containsSegment(nodes[a], nodes[b])) bad[a] = bad[b] = 1;
    if (!pullIn(bad)) break;
  }

  // High K first (Algorithm 2): an interior node near a K peak becomes a corner at p_max.
  std::vector<char> snapped(nodes.size(), 0);
  for (const auto& peak : peaks) {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (fixedNode[i] || snapped[i]) continue;
      const double d = (nodes[i] - peak.at).norm();
      if (d < bestDistance) bestDistance = d, best = static_cast<int>(i);
    }
    const auto [block, gi, gj] = best >= 0 ? interiorOf[best] : std::array<int, 3>{-1, -1, -1};
    if (block >= 0 && snapAllowed(plainGrids[block], gi, gj, peak.at, options.peakSnapFraction)) {
      nodes[best] = peak.at;
      snapped[best] = 1;
      ++out.peaksSnapped;
    }
  }

  // Lift the nodes onto the surface. A node on the boundary is its point of the boundary in space;
  // a node pulled in from it stays on the sheet it came from (not up an overhanging wall, as at the
  // Lilium's base); any other is the highest point over its plan point (the roof seen from above).
  int overhangs = 0;
  const auto lift = [&](size_t i) -> Eigen::Vector3d {
    if (onSurface[i]) return *onSurface[i];
    int sheets = 0;
    const Eigen::Vector3d x = lifter.lift(nodes[i], startedOn[i], &sheets);
    if (sheets > 1) ++overhangs;
    return x;
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
          if (surface.is_boundary(TriMesh::VertexHandle(v)) && vertexAngleSum(surface, TriMesh::VertexHandle(v)) > M_PI + turnTolerance &&
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
  if (overhangs) out.notes.push_back(fmt::format("{} corner(s) over a part of the surface that the plan sees twice", overhangs));
  for (size_t bi = 0; bi < blocks.size(); ++bi)
    for (int i = 0; i < blocks[bi].nu; ++i)
      for (int j = 0; j < blocks[bi].nv; ++j) {
        const auto& g = grid[bi];
        out.quads.push_back({g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]});
      }
  std::string counts;
  for (const auto& b : blocks) counts += fmt::format("{}{}x{}", counts.empty() ? "" : ", ", b.nu, b.nv);
  out.notes.push_back(fmt::format("patches per block: {} (cells up to {:.3g} m across in space; {} grids screened)", counts, options.maxPatchSizeM,
                                  out.candidatesScreened));
  if (out.peaksSnapped) out.notes.push_back(fmt::format("{} grid corner(s) moved onto K peaks", out.peaksSnapped));
  if (out.nodesPulledIn) out.notes.push_back(fmt::format("boundary corners pulled inwards {} time(s) off concave stretches", out.nodesPulledIn));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::patching
