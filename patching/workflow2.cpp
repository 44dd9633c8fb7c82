// Workflow 2's automatic initial layout (see workflow2.hpp).
#include "patching/workflow2.hpp"

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

using namespace workflow2;

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
