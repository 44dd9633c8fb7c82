// Workflow 2's blocks and their grids (see workflow2_blocks.hpp).
#include "patching/workflow2_blocks.hpp"

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

namespace egg::patching::workflow2 {

const std::array<Vec2, 4> kQuadrant{Vec2(-1, -1), Vec2(1, -1), Vec2(1, 1), Vec2(-1, 1)};

Vec2 HoleBox::corner(int k, double scale) const {
  return centre + scale * kQuadrant[k].cwiseProduct(half);
}

HoleBox holeBoxOf(const Polygon& hole, double margin) {
  Vec2 lo = hole.front(), hi = hole.front();
  for (const auto& p : hole) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {0.5 * (lo + hi), 0.5 * (hi - lo) * (1.0 + margin)};
}

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
                  const std::vector<HoleBox>& holes) {
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

}  // namespace egg::patching::workflow2
