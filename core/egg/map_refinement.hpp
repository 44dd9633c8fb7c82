#pragma once
// Adaptive rows of a distance map (Section 2.4.2). For a fixed end-side sample x2, D(x1, x2) is
// smooth in x1 wherever the shortest geodesic does not touch the patch boundary: on a patch the
// sides are geodesics and the two sides of a family are disjoint, so between kinks the distance
// is the length of a straight segment in an unfolding and varies smoothly with its start point.
// One exact source field gives a whole row (every x2), so only some x1 samples need a field; the
// others are read off a local cubic interpolant in x1.
//
// Refinement: exact rows at `initialNodes` samples spread evenly, then rounds of checks. Each
// round computes the exact row at the middle sample of every interval still under test (one
// batch) and compares it with the cubic through the neighbouring exact rows; an interval whose
// check misses by more than the tolerance anywhere along x2 is split and both halves are tested
// in the next round. A passing check is not trusted alone (a kink at a fixed x1 near an end of
// the interval hardly moves the middle): the cubics that will fill the interval, the checked
// one and those through the node stencils shifted by one node to either side must agree to the
// tolerance at every sample, else the interval is split too; this is repeated with the final
// nodes. Near a kink (a geodesic bending around a non-convex boundary) the intervals shrink to
// adjacent samples, which is the exact map there: the fallback is local and needs no separate
// switch. When 3/4 of the first-round checks miss by far (> 32x the tolerance: kinks everywhere),
// the remaining rows are computed in one batch instead of several rounds. On a triangle mesh D
// also carries tiny kinks wherever a geodesic sweeps over a mesh vertex (~1e-4 m on the bench
// bumps); a tolerance below that level refines far more (every row on the 0.6k bench bump at
// 3e-4 m).
#include <functional>
#include <vector>

namespace egg {

struct MapRefinementStats {
  int exactRows = 0;  // rows computed by an exact source field (initial nodes + checks)
  int rounds = 0;     // batches after the initial one (check rounds, or the one batch of the rest)
  int refinedIntervals = 0;   // checks or stencil comparisons that failed and split their interval
  double largestMissM = 0.0;  // largest miss of a check that passed (metres)
};

// exactRows(indices) returns one row (all n2 values, metres) per requested x1 sample index, in
// order; it is called once with the initial nodes and once per round. `rows` receives all n1
// rows. tolerance <= 0 or initialNodes >= n1 computes every row exactly in one call. Rows that
// were not computed lie within the tolerance of the exact ones wherever the map is smooth in x1
// between the nodes around them (checked, not guaranteed: a feature narrower than the node
// spacing that no check or stencil comparison sees is missed).
// Throws InvalidInput on n1 < 2, initialNodes < 2 or rows of the wrong length.
MapRefinementStats refineMapRows(
    int n1, int n2, double tolerance, int initialNodes,
    const std::function<std::vector<std::vector<double>>(const std::vector<int>&)>& exactRows,
    std::vector<std::vector<double>>& rows);

}  // namespace egg
