#pragma once
// The blocks of Workflow 2's initial layout (Section 3.4.3, Algorithm 2) and the grids screened on
// them: the outer block or the ring of four round a hole, their corner peaks, and each block's
// nu x nv grid of patches. Only workflow2.cpp uses this.
#include "core/mesh/mesh.hpp"
#include "patching/footprint.hpp"
#include "patching/workflow2.hpp"

#include <Eigen/Core>

#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace egg::patching::workflow2 {

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

// A hole's box in plan: its centre and half sizes (the tangent box, inflated a little).
struct HoleBox {
  Vec2 centre, half;
  Vec2 corner(int k, double scale = 1.0) const;
};

// An nu x nv grid of one block tried before it is built: Algorithm 2's high-K regions first (the
// interior node nearest a peak moves onto it when within `snapFraction` of its cells), and the
// largest cell diagonal in space (chords between the nodes lifted onto the surface: a steep cell
// is measured as it is, not through a mean stretch of the plan).
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

// The four outer corners of the footprint and the boundary arcs between them.
struct OuterCorners {
  Vec2 centre, half;              // the footprint's box
  std::array<size_t, 4> index{};  // into foot.outer
  std::array<Arc, 4> arcs;        // arcs[k]: corner k -> corner k + 1
};

HoleBox holeBoxOf(const Polygon& hole, double margin);

// Whether interior node (i, j) of plan grid g may move to `to`: its move along each grid direction
// stays within `fraction` of the shorter grid line from it in that direction, so that the four
// cells round it stay convex and none shrinks to a sliver.
bool snapAllowed(const std::vector<std::vector<Vec2>>& g, int i, int j, const Vec2& to,
                 double fraction);

GridTrial tryGrid(const Block& b, int nu, int nv, const PlanLifter& lifter,
                  const std::vector<PlanPeak>& peaks, double snapFraction,
                  const std::vector<HoleBox>& holes = {});

// Outer corners: the boundary points extreme in the four diagonal directions of its box. Only
// convex points of the boundary may be block corners (its convex hull's vertices): a corner in a
// concave neck, as between the Lilium's lobes, would make its patch reflex there.
OuterCorners outerCornersOf(const Footprint& foot);

// No hole, or several: one block between the four outer corners, all its sides on the boundary.
Block outerBlock(const std::array<Arc, 4>& arcs, size_t holes, Workflow2Layout& out);

// A single hole: a ring of four blocks between the outer corners and the box round the hole.
std::vector<Block> ringBlocks(const std::array<Arc, 4>& arcs, const Footprint& foot,
                              const Plan& plan, const PlanLifter& lifter, const TriMesh& surface,
                              const geodesic::DistanceSolver* solver,
                              const Workflow2Options& options, Workflow2Layout& out);

// Peaks for corners: not on the boundary, nor next to a hole (twice its box): the ring round the
// hole has its sides there already, and a corner moved there would cut through the hole's cell.
std::vector<PlanPeak> cornerPeaks(const TriMesh& surface, const Plan& plan,
                                  const std::vector<HoleBox>& holeBoxes);

// One block: every grid up to 16 x 16 (or the architect's) screened, the one predicting the fewest
// patches kept (its peaks on nodes, each hole in a cell of its own); sets the block's nu x nv.
GridTrial screenGrids(Block& b, const PlanLifter& lifter, const std::vector<PlanPeak>& peaks,
                      const std::vector<HoleBox>& holeBoxes, const Workflow2Options& options,
                      Workflow2Layout& out);

// The ring of four blocks: a block whose worst cell is too large gets one more patch across its
// longer direction (along v for all four at once, so that their grids meet), until all fit.
void growRingGrids(std::vector<Block>& blocks, const PlanLifter& lifter,
                   const Workflow2Options& options, Workflow2Layout& out);

}  // namespace egg::patching::workflow2
