// Workflow 2's automatic initial layout (see workflow2.hpp).
#include "patching/workflow2.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "patching/footprint.hpp"
#include "patching/hole_box.hpp"
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
  if (!(holeMarginRelative >= 0.0 && holeMarginRelative < 1.0))
    throw InvalidInput("workflow 2: hole margin must lie in [0, 1)");
  if (!(peakSnapFraction >= 0.0 && peakSnapFraction <= 0.5))
    throw InvalidInput("workflow 2: peak snap fraction must lie in [0, 0.5]");
  const bool screened = blockGrid[0] == 0 && blockGrid[1] == 0;
  if (!screened && (blockGrid[0] < 1 || blockGrid[0] > 16 || blockGrid[1] < 1 || blockGrid[1] > 16))
    throw InvalidInput(
        fmt::format("patching.block_grid must be two patch counts in 1..16, got [{}, {}]",
                    blockGrid[0], blockGrid[1]));
}

namespace {

// One block: four plan curves (side 0 corner0 -> corner1, side 1 corner1 -> corner2, side 2
// corner3 -> corner2 and side 3 corner0 -> corner3, i.e. the Coons patch's u and v directions) and
// its grid of nu x nv patches.
struct Block {
  std::function<Vec2(double)> bottom, top, left, right;  // C0(u), C2(u), D3(v), D1(v)
  std::function<Eigen::Vector3d(double)> bottom3d, top3d, left3d,
      right3d;  // the same in space, for sides on the boundary
  int nu = 1, nv = 1;
  bool bottomOnBoundary = false, topOnBoundary = false, leftOnBoundary = false,
       rightOnBoundary = false;
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
// A hole's box in plan: its centre and half sizes (the tangent box, inflated a little).
struct HoleBox {
  Vec2 centre, half;
  Vec2 corner(int k, double scale = 1.0) const;
};

const std::array<Vec2, 4> kQuadrant{Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};

Vec2 HoleBox::corner(int k, double scale) const {
  return centre + scale * kQuadrant[k].cwiseProduct(half);
}

HoleBox holeBoxOf(const Polygon& hole, double margin) {
  Vec2 lo = hole.front(), hi = hole.front();
  for (const auto& p : hole) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {0.5 * (lo + hi), 0.5 * (hi - lo) * (1.0 + margin)};
}

struct GridTrial {
  std::vector<std::vector<Vec2>> plan;        // [i][j]
  std::vector<std::array<int, 2>> holeCells;  // per hole: the cell (i, j) holding its box
  bool holesFit = true;                       // every hole's box inside a cell of its own
  double worstDiagonalM = 0.0;
  bool worstAlongU = true;                // the worst cell is longer along u
  std::vector<std::vector<char>> onPeak;  // [i][j]: the node moved onto a peak
  std::vector<char> peakOnNode;           // per peak
  int snapped = 0;
  int peaksLeftInside = 0;  // peaks not on a node whose circle is smaller than the cells
};

// Whether interior node (i, j) of plan grid g may move to `to`: its move along each grid direction
// stays within `fraction` of the shorter grid line from it in that direction, so that the four
// cells round it stay convex and none shrinks to a sliver.
bool snapAllowed(const std::vector<std::vector<Vec2>>& g, int i, int j, const Vec2& to,
                 double fraction) {
  const Vec2 du = g[i + 1][j] - g[i - 1][j], dv = g[i][j + 1] - g[i][j - 1];
  const double su = std::min((g[i + 1][j] - g[i][j]).norm(), (g[i][j] - g[i - 1][j]).norm());
  const double sv = std::min((g[i][j + 1] - g[i][j]).norm(), (g[i][j] - g[i][j - 1]).norm());
  if (!(du.norm() > 0 && dv.norm() > 0)) return false;
  const Vec2 move = to - g[i][j];
  return std::abs(move.dot(du.normalized())) <= fraction * su &&
         std::abs(move.dot(dv.normalized())) <= fraction * sv;
}

GridTrial tryGrid(const Block& b, int nu, int nv, const PlanLifter& lifter,
                  const std::vector<PlanPeak>& peaks, double snapFraction,
                  const std::vector<HoleBox>& holes = {}) {
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
        if (!taken[i][j] && (t.plan[i][j] - peaks[k].at).norm() < best)
          best = (t.plan[i][j] - peaks[k].at).norm(), bi = i, bj = j;
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
          if (!taken[i][j])
            t.plan[i][j] =
                0.25 * (t.plan[i - 1][j] + t.plan[i + 1][j] + t.plan[i][j - 1] + t.plan[i][j + 1]);
  std::vector<std::vector<Eigen::Vector3d>> space(nu + 1, std::vector<Eigen::Vector3d>(nv + 1));
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const auto onBoundary = taken[i][j] ? std::nullopt : b.boundaryPoint(i, j, nu, nv);
      space[i][j] = onBoundary ? *onBoundary : lifter.lift(t.plan[i][j]);
    }
  // A cell's size: its diagonals measured on the surface over the plan diagonals (a chord through
  // the air would take a cell over the Lilium's dome for half its size).
  const auto overSurface = [&](int i0, int j0, int i1, int j1) {
    const int samples = 12;
    double length = 0.0;
    Eigen::Vector3d last = space[i0][j0];
    for (int k = 1; k <= samples; ++k) {
      const Eigen::Vector3d x =
          k == samples
              ? space[i1][j1]
              : lifter.lift(lerp(t.plan[i0][j0], t.plan[i1][j1], double(k) / samples), last);
      length += (x - last).norm();
      last = x;
    }
    return length;
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double diag =
          std::max(overSurface(i, j, i + 1, j + 1), overSurface(i + 1, j, i, j + 1));
      if (diag > t.worstDiagonalM)
        t.worstDiagonalM = diag,
        t.worstAlongU = overSurface(i, j, i + 1, j) + overSurface(i, j + 1, i + 1, j + 1) >=
                        overSurface(i, j, i, j + 1) + overSurface(i + 1, j, i + 1, j + 1);
    }
  // Holes: each box must lie inside one cell, which becomes a ring of four patches round it.
  for (const auto& hole : holes) {
    std::array<int, 2> cell{-1, -1};
    for (int i = 0; i < nu && cell[0] < 0; ++i)
      for (int j = 0; j < nv && cell[0] < 0; ++j) {
        const Polygon quad{t.plan[i][j], t.plan[i + 1][j], t.plan[i + 1][j + 1], t.plan[i][j + 1]};
        bool inside = true;
        for (int k = 0; k < 4; ++k)
          inside = inside && insidePolygon(quad, hole.corner(k, 1.25));  // room for the ring
        if (inside) cell = {i, j};
      }
    if (cell[0] < 0 || std::count(t.holeCells.begin(), t.holeCells.end(), cell)) t.holesFit = false;
    t.holeCells.push_back(cell);
  }
  // Expression 3.1 is "only useful as a quick check" (3.4.1): members cross a cell in about its
  // diagonal, and a 1.5 x 2 m cell of a bump whose circle is 2.51 m already fails η; hence the
  // margin.
  const double peakReach = 1.5;
  for (size_t k = 0; k < peaks.size(); ++k)
    if (!onNode[k] && peaks[k].radiusM < peakReach * t.worstDiagonalM) ++t.peaksLeftInside;
  return t;
}

// The four outer corners of the footprint and the boundary arcs between them.
struct OuterCorners {
  Vec2 centre, half;              // the footprint's box
  std::array<size_t, 4> index{};  // into foot.outer
  std::array<Arc, 4> arcs;        // arcs[k]: corner k -> corner k + 1
};

// Outer corners: the boundary points extreme in the four diagonal directions of its box. Only
// convex points of the boundary may be block corners (its convex hull's vertices): a corner in a
// concave neck, as between the Lilium's lobes, would make its patch reflex there.
OuterCorners outerCornersOf(const Footprint& foot) {
  OuterCorners out;
  Vec2 lo = foot.outer.front(), hi = foot.outer.front();
  for (const auto& p : foot.outer) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  out.centre = 0.5 * (lo + hi), out.half = 0.5 * (hi - lo);
  const Vec2 &centre = out.centre, &half = out.half;
  const auto& quadrant = kQuadrant;
  const std::vector<char> onHull = convexHullMarks(foot.outer);
  std::array<size_t, 4>& cornerIndex = out.index;
  for (int k = 0; k < 4; ++k) {
    double best = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < foot.outer.size(); ++i) {
      if (!onHull[i]) continue;
      const double score = quadrant[k].dot((foot.outer[i] - centre).cwiseQuotient(half));
      if (score > best) best = score, cornerIndex[k] = i;
    }
  }
  for (int k = 0; k < 4; ++k) out.arcs[k] = arcOf(foot, cornerIndex[k], cornerIndex[(k + 1) % 4]);
  return out;
}

// No hole, or several: one block between the four outer corners, all its sides on the boundary.
Block outerBlock(const std::array<Arc, 4>& arcs, size_t holes, Workflow2Layout& out) {
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
  out.notes.push_back(holes == 0
                          ? "one block between the four outer corners"
                          : fmt::format("one block between the four outer corners, each of its {} "
                                        "holes in a cell of its own "
                                        "cut into a ring of four patches round the hole's box",
                                        holes));
  return b;
}

// A single hole: a ring of four blocks between the outer corners and the box round the hole.
std::vector<Block> ringBlocks(const std::array<Arc, 4>& arcs, const Footprint& foot,
                              const Plan& plan, const PlanLifter& lifter, const TriMesh& surface,
                              const geodesic::DistanceSolver* solver,
                              const Workflow2Options& options, Workflow2Layout& out) {
  // The box tangent to the hole, inflated a little so that its sides clear the hole; with the
  // solver, its corners then move in until the traced sides just clear it.
  const HoleBox box = holeBoxOf(foot.holes[0], options.holeMarginRelative);
  std::array<double, 4> scale{1.0, 1.0, 1.0, 1.0};
  const auto cornerAt = [&](int k) { return box.corner(k, scale[k]); };
  if (solver) {
    const double clearance = tightenHoleBox(scale, cornerAt, foot.holes[0], plan, lifter, surface,
                                            *solver, foot.tolerance);
    if (clearance >= 0)
      out.notes.push_back(
          fmt::format("box round the hole tightened to sides {:.2f} m clear of it (corners at "
                      "{:.3f}, {:.3f}, {:.3f}, {:.3f} of the "
                      "tangent box)",
                      clearance, scale[0], scale[1], scale[2], scale[3]));
  }
  std::array<Vec2, 4> inner;
  for (int k = 0; k < 4; ++k) inner[k] = cornerAt(k);
  std::vector<Block> blocks;
  for (int k = 0; k < 4; ++k) {
    const Vec2 o0 = arcs[k].points.front(), o1 = arcs[k].points.back(), i0 = inner[k],
               i1 = inner[(k + 1) % 4];
    Block b;
    b.bottom = [a = arcs[k]](double u) { return a.at(u); };
    b.bottom3d = [a = arcs[k]](double u) { return a.at3d(u); };
    b.top = [i0, i1](double u) { return lerp(i0, i1, u); };
    b.left = [o0, i0](double v) { return lerp(o0, i0, v); };
    b.right = [o1, i1](double v) { return lerp(o1, i1, v); };
    b.bottomOnBoundary = true;
    blocks.push_back(b);
  }
  out.notes.push_back(
      "a ring of four blocks between the outer corners and the box tangent to the hole");
  return blocks;
}

// Peaks for corners: not on the boundary, nor next to a hole (twice its box): the ring round the
// hole has its sides there already, and a corner moved there would cut through the hole's cell.
std::vector<PlanPeak> cornerPeaks(const TriMesh& surface, const Plan& plan,
                                  const std::vector<HoleBox>& holeBoxes) {
  const auto surfacePeaks = findSurfacePeaks(surface);
  std::vector<PlanPeak> peaks;
  for (const auto& peak : surfacePeaks) {
    const Vec2 at = plan(peak.position);
    const bool byHole = std::any_of(holeBoxes.begin(), holeBoxes.end(), [&](const HoleBox& h) {
      return std::abs(at.x() - h.centre.x()) <= 2 * h.half.x() &&
             std::abs(at.y() - h.centre.y()) <= 2 * h.half.y();
    });
    if (!peak.onBoundary && !byHole) peaks.push_back({at, peak.radiusM});
  }
  return peaks;
}

// One block: every grid up to 16 x 16 (or the architect's) screened, the one predicting the fewest
// patches kept (its peaks on nodes, each hole in a cell of its own); sets the block's nu x nv.
GridTrial screenGrids(Block& b, const PlanLifter& lifter, const std::vector<PlanPeak>& peaks,
                      const std::vector<HoleBox>& holeBoxes, const Workflow2Options& options,
                      Workflow2Layout& out) {
  GridTrial chosen;
  const int bound = 16;
  int bestPredicted = std::numeric_limits<int>::max();
  double bestDiagonal = std::numeric_limits<double>::infinity();
  const bool given = options.blockGrid[0] > 0;
  for (int nu = given ? options.blockGrid[0] : 1; nu <= (given ? options.blockGrid[0] : bound);
       ++nu)
    for (int nv = given ? options.blockGrid[1] : 1; nv <= (given ? options.blockGrid[1] : bound);
         ++nv) {
      if (nu * nv > bestPredicted) continue;  // cannot win
      GridTrial t = tryGrid(b, nu, nv, lifter, peaks, options.peakSnapFraction, holeBoxes);
      ++out.candidatesScreened;
      if (t.worstDiagonalM > options.maxPatchSizeM * (1 + 1e-9) || !t.holesFit)
        continue;  // a cell of exactly the size fits
      const int predicted =
          nu * nv + 3 * t.peaksLeftInside + 3 * static_cast<int>(holeBoxes.size());
      if (predicted < bestPredicted ||
          (predicted == bestPredicted && t.worstDiagonalM < bestDiagonal))
        bestPredicted = predicted, bestDiagonal = t.worstDiagonalM, b.nu = nu, b.nv = nv,
        chosen = std::move(t);
    }
  if (bestPredicted == std::numeric_limits<int>::max() && given)
    throw InvalidInput(
        fmt::format("patching.block_grid [{}, {}]: a cell is larger than patching.max_patch_size_m "
                    "= {} m across{}",
                    options.blockGrid[0], options.blockGrid[1], options.maxPatchSizeM,
                    holeBoxes.empty() ? "" : ", or a hole does not sit in a cell of its own"));
  if (bestPredicted == std::numeric_limits<int>::max())
    throw InvalidInput(fmt::format(
        "workflow 2: no grid of up to {} x {} patches has cells within patching.max_patch_size_m = "
        "{} m{}",
        bound, bound, options.maxPatchSizeM,
        holeBoxes.empty()
            ? ""
            : " and each hole in a cell of its own (holes too close together or too large)"));
  return chosen;
}

// The ring of four blocks: a block whose worst cell is too large gets one more patch across its
// longer direction (along v for all four at once, so that their grids meet), until all fit.
void growRingGrids(std::vector<Block>& blocks, const PlanLifter& lifter,
                   const Workflow2Options& options, Workflow2Layout& out) {
  if (options.blockGrid[0] > 0)
    throw InvalidInput(
        "patching.block_grid applies to a surface with no hole or several; around a single hole "
        "Workflow 2 "
        "lays a ring of four blocks whose grids follow from max_patch_size_m");
  for (int guard = 0; guard < 200; ++guard) {
    bool changed = false;
    for (auto& b : blocks) {
      const GridTrial t = tryGrid(b, b.nu, b.nv, lifter, {}, 0.0);
      ++out.candidatesScreened;
      if (t.worstDiagonalM <= options.maxPatchSizeM * (1 + 1e-9)) continue;
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

// The layout's corner nodes as they are placed, pulled in, snapped and lifted.
struct LayoutNodes {
  double mergeTolerance = 0.0;
  std::vector<Vec2> nodes;
  std::vector<char> onBoundary, fixedNode;  // fixed: on the boundary or on the box around the hole
  std::vector<std::optional<Eigen::Vector3d>>
      onSurface;  // boundary nodes: their point of the boundary in space
  std::vector<std::optional<Eigen::Vector3d>>
      startedOn;  // boundary nodes: where they were before being pulled in
  std::vector<std::array<int, 3>>
      interiorOf;  // interior nodes: (block, i, j) in the plain grids below
  std::vector<std::vector<std::vector<int>>> grid;  // per block: node ids [i][j]
  std::vector<std::vector<std::vector<Vec2>>> plainGrids;
  std::vector<std::pair<int, int>> boundaryChords;  // consecutive boundary nodes
  std::vector<std::pair<int, int>> inwards;  // boundary node -> its neighbour one step inside
  std::map<std::array<int, 2>, std::array<int, 4>> ringOfCell;  // cell -> its box's corner nodes
  Vec2 blockCentre = Vec2::Zero();
  std::vector<char> moved;
  std::vector<Eigen::Vector3d> lifted;

  // The node at plan point p (an existing one within mergeTolerance, else a new one).
  int nodeId(const Vec2& p, bool boundary) {
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
  }

  // Moves the marked boundary nodes 8 % of the way to their inward targets (they leave the
  // boundary); false when none is marked.
  bool pullIn(const std::vector<char>& bad, int& nodesPulledIn) {
    if (std::none_of(bad.begin(), bad.end(), [](char c) { return c; })) return false;
    for (const auto& [node, towards] : inwards) {
      if (!bad[node]) continue;
      const Vec2 target = towards >= 0 && towards != node ? nodes[towards] : blockCentre;
      nodes[node] = lerp(nodes[node], target, 0.08);
      onSurface[node].reset();
      moved[node] = 1;
      ++nodesPulledIn;
    }
    return true;
  }

  // Lift the nodes onto the surface. A node on the boundary is its point of the boundary in space;
  // a node pulled in from it stays on the sheet it came from (not up an overhanging wall, as at the
  // Lilium's base); any other is the highest point over its plan point (the roof seen from above).
  Eigen::Vector3d lift(size_t i, const PlanLifter& lifter, int& overhangs) const {
    if (onSurface[i]) return *onSurface[i];
    int sheets = 0;
    const Eigen::Vector3d x = lifter.lift(nodes[i], startedOn[i], &sheets);
    if (sheets > 1) ++overhangs;
    return x;
  }
};

// One block's boundary chords, and where each of its boundary nodes moves when pulled in.
void addBoundaryChords(const Block& b, const std::vector<std::vector<int>>& g, LayoutNodes& net) {
  for (int i = 0; i < b.nu; ++i) {
    if (b.bottomOnBoundary) net.boundaryChords.emplace_back(g[i][0], g[i + 1][0]);
    if (b.topOnBoundary) net.boundaryChords.emplace_back(g[i][b.nv], g[i + 1][b.nv]);
  }
  for (int j = 0; j < b.nv; ++j) {
    if (b.leftOnBoundary) net.boundaryChords.emplace_back(g[0][j], g[0][j + 1]);
    if (b.rightOnBoundary) net.boundaryChords.emplace_back(g[b.nu][j], g[b.nu][j + 1]);
  }
  // Where a boundary node moves when pulled in: towards the block's centre.
  for (int i = 0; i <= b.nu; ++i)
    for (int j = 0; j <= b.nv; ++j)
      if (net.onBoundary[g[i][j]]) {
        const int ii = std::clamp(i, 1, std::max(1, b.nu - 1)),
                  jj = std::clamp(j, 1, std::max(1, b.nv - 1));
        const int to = (b.nu >= 2 || b.nv >= 2) ? g[std::min(ii, b.nu)][std::min(jj, b.nv)] : -1;
        net.inwards.emplace_back(g[i][j], to);
      }
}

// Nodes, shared where blocks meet (same plan point to rounding).
LayoutNodes gridNodes(const std::vector<Block>& blocks, const GridTrial& chosen, bool singleBlock,
                      const PlanLifter& lifter, double mergeTolerance, Workflow2Layout& out) {
  LayoutNodes net;
  net.mergeTolerance = mergeTolerance;
  net.grid.resize(blocks.size());
  for (size_t bi = 0; bi < blocks.size(); ++bi) {
    const Block& b = blocks[bi];
    net.plainGrids.push_back(tryGrid(b, b.nu, b.nv, lifter, {}, 0.0).plan);
    // One block: the screened grid as it was chosen (its peaks on nodes, the others evened out).
    const auto& plain = singleBlock ? chosen.plan : net.plainGrids.back();
    net.grid[bi].assign(b.nu + 1, std::vector<int>(b.nv + 1));
    for (int i = 0; i <= b.nu; ++i)
      for (int j = 0; j <= b.nv; ++j) {
        const auto boundaryPoint = b.boundaryPoint(i, j, b.nu, b.nv);
        const int id = net.grid[bi][i][j] = net.nodeId(plain[i][j], boundaryPoint.has_value());
        if (boundaryPoint) net.onSurface[id] = net.startedOn[id] = boundaryPoint;
        const bool onHoleBox = !singleBlock && j == b.nv;
        if (boundaryPoint || onHoleBox || (singleBlock && chosen.onPeak[i][j]))
          net.fixedNode[id] = 1;
        if (singleBlock && chosen.onPeak[i][j]) ++out.peaksSnapped;
        if (i > 0 && i < b.nu && j > 0 && j < b.nv && net.interiorOf[id][0] < 0)
          net.interiorOf[id] = {static_cast<int>(bi), i, j};
      }
    addBoundaryChords(b, net.grid[bi], net);
  }
  return net;
}

// Each hole's cell becomes a ring of four patches round the hole's box (its corners moved in
// until the traced sides just clear the hole, with the solver).
void addHoleRings(const std::vector<HoleBox>& holeBoxes, const GridTrial& chosen,
                  const Footprint& foot, const Plan& plan, const PlanLifter& lifter,
                  const TriMesh& surface, const geodesic::DistanceSolver* solver, LayoutNodes& net,
                  Workflow2Layout& out) {
  for (size_t h = 0; h < holeBoxes.size(); ++h) {
    std::array<double, 4> scale{1.0, 1.0, 1.0, 1.0};
    const auto cornerAt = [&](int k) { return holeBoxes[h].corner(k, scale[k]); };
    if (solver && tightenHoleBox(scale, cornerAt, foot.holes[h], plan, lifter, surface, *solver,
                                 foot.tolerance) >= 0)
      ++out.holeBoxesTightened;
    std::array<int, 4> ring{};
    for (int k = 0; k < 4; ++k) {
      ring[k] = net.nodeId(cornerAt(k), false);
      net.fixedNode[ring[k]] = 1;
    }
    net.ringOfCell[chosen.holeCells[h]] = ring;
  }
}

// A chord along a concave stretch leaves the footprint: pull its ends inwards until it does not.
// With the solver the traced test below decides instead: a plan test is wrong where the wall is
// vertical (the Lilium's base: its outline is a geodesic there, concave in plan or not).
void pullInOffConcaveStretches(const Footprint& foot, LayoutNodes& net, Workflow2Layout& out) {
  for (int round = 0; round < 10; ++round) {
    std::vector<char> bad(net.nodes.size(), 0);
    for (const auto& [a, b] : net.boundaryChords)
      if (!foot.containsSegment(net.nodes[a], net.nodes[b])) bad[a] = bad[b] = 1;
    if (!net.pullIn(bad, out.nodesPulledIn)) break;
  }
}

// High K first (Algorithm 2): an interior node near a K peak becomes a corner at p_max (one
// block: done while screening).
void snapNodesToPeaks(const std::vector<PlanPeak>& peaks, const Workflow2Options& options,
                      LayoutNodes& net, Workflow2Layout& out) {
  std::vector<char> snapped(net.nodes.size(), 0);
  for (const auto& peak : peaks) {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < net.nodes.size(); ++i) {
      if (net.fixedNode[i] || snapped[i]) continue;
      const double d = (net.nodes[i] - peak.at).norm();
      if (d < bestDistance) bestDistance = d, best = static_cast<int>(i);
    }
    const auto [block, gi, gj] = best >= 0 ? net.interiorOf[best] : std::array<int, 3>{-1, -1, -1};
    if (block >= 0 &&
        snapAllowed(net.plainGrids[block], gi, gj, peak.at, options.peakSnapFraction)) {
      net.nodes[best] = peak.at;
      snapped[best] = 1;
      ++out.peaksSnapped;
    }
  }
}

// The boundary vertex of `surface` nearest to x.
TriMesh::VertexHandle boundaryVertexAt(const TriMesh& surface, const Eigen::Vector3d& x) {
  int vertex = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (auto vh : surface.vertices())
    if (surface.is_boundary(vh) && (toEigen(surface.point(vh)) - x).norm() < nearest)
      nearest = (toEigen(surface.point(vh)) - x).norm(), vertex = vh.idx();
  return TriMesh::VertexHandle(vertex);
}

// The node a boundary node moves towards when pulled in, or -1.
int inwardOf(const LayoutNodes& net, int node) {
  for (const auto& [n, towards] : net.inwards)
    if (n == node && towards >= 0 && towards != node) return towards;
  return -1;
}

// The point `step` along a polyline from its start (its end when shorter; `from` when it has one
// point).
Eigen::Vector3d pointAlong(const std::vector<Eigen::Vector3d>& positions, double step,
                           const Eigen::Vector3d& from) {
  double walked = 0.0;
  Eigen::Vector3d moved = from;
  for (size_t i = 1; i < positions.size(); ++i) {
    const double piece = (positions[i] - positions[i - 1]).norm();
    if (walked + piece >= step) {
      moved = positions[i - 1] +
              (step - walked) / std::max(piece, 1e-300) * (positions[i] - positions[i - 1]);
      break;
    }
    walked += piece;
    moved = positions[i];
  }
  return moved;
}

// An outer corner where the boundary runs on nearly straight (in the surface: the Lilium's
// base is a geodesic all round, so Gauss-Bonnet leaves its corners no turning) gives its patch
// an inner angle of about pi, and criterion (iv) fails. Moving the corner in would make that
// angle reflex; its two neighbours along the boundary move in instead, along the surface (in
// plan a step near a vertical wall would climb it) by a tenth of their side, which leaves the
// corner an angle of about pi - 0.2 and two thin cut-offs.
void moveNeighboursOfStraightCorners(const TriMesh& surface, const Footprint& foot,
                                     const std::array<size_t, 4>& cornerIndex, const Plan& plan,
                                     const geodesic::DistanceSolver& solver, LayoutNodes& net,
                                     Workflow2Layout& out) {
  const double cornerAngleMargin = 0.1, neighbourStep = 0.1;
  std::vector<int> outerCorners;
  for (size_t k = 0; k < 4; ++k)
    for (size_t i = 0; i < net.nodes.size(); ++i)
      if (net.onSurface[i] &&
          (net.nodes[i] - foot.outer[cornerIndex[k]]).norm() <= net.mergeTolerance)
        outerCorners.push_back(static_cast<int>(i));
  auto& lifted = net.lifted;
  for (int node : outerCorners) {
    std::vector<int> along;
    for (const auto& [a, b] : net.boundaryChords)
      if (a == node || b == node) along.push_back(a == node ? b : a);
    if (along.size() != 2) continue;
    const auto from = geodesic::snapToSurface(surface, lifted[node]);
    const auto toA = solver.path(from, geodesic::snapToSurface(surface, lifted[along[0]]));
    const auto toB = solver.path(from, geodesic::snapToSurface(surface, lifted[along[1]]));
    if (toA.positions.size() < 2 || toB.positions.size() < 2) continue;
    const double angle =
        M_PI + geodesicTurningAtBoundary(surface, boundaryVertexAt(surface, lifted[node]),
                                         toA.positions[1], toB.positions[1]);
    if (angle <= M_PI - cornerAngleMargin) continue;
    for (size_t side = 0; side < 2; ++side) {
      const int neighbour = along[side], towards = inwardOf(net, neighbour);
      if (towards < 0 || !net.onSurface[neighbour] ||
          std::count(outerCorners.begin(), outerCorners.end(), neighbour))
        continue;
      const auto inward = solver.path(geodesic::snapToSurface(surface, lifted[neighbour]),
                                      geodesic::snapToSurface(surface, lifted[towards]));
      const double step = neighbourStep * (side == 0 ? toA.length : toB.length);
      const Eigen::Vector3d moved = pointAlong(inward.positions, step, lifted[neighbour]);
      lifted[neighbour] = moved;
      net.onSurface[neighbour] = moved;
      net.nodes[neighbour] = plan(moved);
    }
    ++out.cornersMovedOffStraightBoundary;
  }
}

// Each boundary chord traced on the surface; where it bends round a boundary vertex its ends are
// pulled further in (and lifted again).
void pullInWrappingChords(const TriMesh& surface, const PlanLifter& lifter,
                          const geodesic::DistanceSolver& solver, const Workflow2Options& options,
                          LayoutNodes& net, int& overhangs, Workflow2Layout& out) {
  for (int round = 0; round < 12; ++round) {
    std::vector<char> bad(net.nodes.size(), 0);
    for (const auto& [a, b] : net.boundaryChords) {
      const auto path = solver.path(geodesic::snapToSurface(surface, net.lifted[a]),
                                    geodesic::snapToSurface(surface, net.lifted[b]));
      const double wrap = boundaryWrapTurning(surface, path.positions, path.bendVertices);
      if (wrap > options.boundaryWrapToleranceRad) bad[a] = bad[b] = 1;
    }
    std::fill(net.moved.begin(), net.moved.end(), 0);
    if (!net.pullIn(bad, out.nodesPulledIn)) break;
    for (size_t i = 0; i < net.nodes.size(); ++i)
      if (net.moved[i]) net.lifted[i] = net.lift(i, lifter, overhangs);
  }
}

// The patches: a grid cell each, or a ring of four round the box in a hole's cell.
void addQuads(const std::vector<Block>& blocks, const LayoutNodes& net, bool singleBlock,
              Workflow2Layout& out) {
  for (size_t bi = 0; bi < blocks.size(); ++bi)
    for (int i = 0; i < blocks[bi].nu; ++i)
      for (int j = 0; j < blocks[bi].nv; ++j) {
        const auto& g = net.grid[bi];
        const std::array<int, 4> cell{g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]};
        const auto ring = singleBlock ? net.ringOfCell.find({i, j}) : net.ringOfCell.end();
        if (ring == net.ringOfCell.end()) {
          out.quads.push_back(cell);
          continue;
        }
        for (int k = 0; k < 4; ++k)  // the patch between cell side k and box side k
          out.quads.push_back(
              {cell[k], cell[(k + 1) % 4], ring->second[(k + 1) % 4], ring->second[k]});
      }
}

// How the layout was made, for the report.
void addSummaryNotes(const std::vector<Block>& blocks, const Workflow2Options& options,
                     Workflow2Layout& out) {
  std::string counts;
  for (const auto& b : blocks)
    counts += fmt::format("{}{}x{}", counts.empty() ? "" : ", ", b.nu, b.nv);
  out.notes.push_back(
      fmt::format("patches per block: {} (cells up to {:.3g} m across in space; {} grids screened)",
                  counts, options.maxPatchSizeM, out.candidatesScreened));
  if (out.peaksSnapped)
    out.notes.push_back(fmt::format("{} grid corner(s) moved onto K peaks", out.peaksSnapped));
  if (out.cornersMovedOffStraightBoundary)
    out.notes.push_back(
        fmt::format("{} outer corner(s) on a boundary running on straight there (an inner angle "
                    "near pi): their neighbours moved in",
                    out.cornersMovedOffStraightBoundary));
  if (out.nodesPulledIn)
    out.notes.push_back(fmt::format(
        "boundary corners pulled inwards {} time(s) off concave stretches", out.nodesPulledIn));
}

}  // namespace

Workflow2Layout proposeLayout(const TriMesh& surface, const Workflow2Options& options,
                              const geodesic::DistanceSolver* solver) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (surface.n_faces() == 0) throw InvalidInput("workflow 2: the surface has no faces");
  Workflow2Layout out;
  const Plan plan = planOf(surface);
  const Footprint foot = footprintOf(surface, plan);
  const PlanLifter lifter(surface, plan);
  out.holes = static_cast<int>(foot.holes.size());

  // Blocks: one between the outer corners (no hole, or several), or a ring of four round a single
  // hole.
  const OuterCorners corners = outerCornersOf(foot);
  const bool singleBlock = foot.holes.size() != 1;
  std::vector<Block> blocks =
      singleBlock ? std::vector<Block>{outerBlock(corners.arcs, foot.holes.size(), out)}
                  : ringBlocks(corners.arcs, foot, plan, lifter, surface, solver, options, out);
  out.blocks = static_cast<int>(blocks.size());

  std::vector<HoleBox> holeBoxes;
  if (foot.holes.size() > 1)
    for (const auto& hole : foot.holes)
      holeBoxes.push_back(holeBoxOf(hole, options.holeMarginRelative));
  const std::vector<PlanPeak> peaks = cornerPeaks(surface, plan, holeBoxes);

  // Each block's grid of patches.
  GridTrial chosen;
  if (singleBlock)
    chosen = screenGrids(blocks.front(), lifter, peaks, holeBoxes, options, out);
  else
    growRingGrids(blocks, lifter, options, out);

  // The corner nodes: placed, pulled in off concave stretches, snapped to peaks, lifted.
  LayoutNodes net = gridNodes(blocks, chosen, singleBlock, lifter,
                              1e-6 * std::max(corners.half.x(), corners.half.y()), out);
  addHoleRings(holeBoxes, chosen, foot, plan, lifter, surface, solver, net, out);
  net.blockCentre = [&] {
    Vec2 c = Vec2::Zero();
    for (const auto& p : net.nodes) c += p;
    return Vec2(c / static_cast<double>(net.nodes.size()));
  }();
  net.moved.assign(net.nodes.size(), 0);
  if (!solver) pullInOffConcaveStretches(foot, net, out);
  if (!singleBlock) snapNodesToPeaks(peaks, options, net, out);
  int overhangs = 0;
  net.lifted.resize(net.nodes.size());
  for (size_t i = 0; i < net.nodes.size(); ++i) net.lifted[i] = net.lift(i, lifter, overhangs);

  // The plan test above cannot see a chord that hugs a wall (the Lilium's base is vertical): trace
  // each boundary chord on the surface, and where it bends round a boundary vertex, pull its ends
  // further in.
  if (solver) {
    moveNeighboursOfStraightCorners(surface, foot, corners.index, plan, *solver, net, out);
    pullInWrappingChords(surface, lifter, *solver, options, net, overhangs, out);
  }
  out.corners = net.lifted;
  if (overhangs)
    out.notes.push_back(
        fmt::format("{} corner(s) over a part of the surface that the plan sees twice", overhangs));
  addQuads(blocks, net, singleBlock, out);
  addSummaryNotes(blocks, options, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::patching
