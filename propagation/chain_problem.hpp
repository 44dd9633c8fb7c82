#pragma once
// Problem 3.3 (Section 3.4.4) on one chain of patches: the members of one family run through
// patches 0 .. n-1, crossing boundaries 0 .. n (boundary i is where they enter patch i, boundary
// n where they leave the last). A member is fixed by its parameter t on boundary 0; on boundary
// i+1 it lies at G_i(t_i) (the cladding function of patch i, forwards or backwards: side_map.hpp),
// which is what keeps neighbouring patches' members C0 at their shared sides. The free members'
// t minimise
//     sum_i omega_i <du_i, du_i>,   du_i = differences of consecutive member parameters on boundary
//     i,
// where a parameter is the arc length along the boundary over its length l_i (the 1/l_i of the
// thesis: every side counts by its spacing relative to its length), subject to ordering and the
// minimum spacing of the lamella footprint (d+-, Section 2.4.4) on every boundary. The member
// count is fixed; originals (members a T-junction or a smaller patch puts on some boundary, Fig.
// 3.8) are members fixed at a given parameter on a given boundary. Solved with NLopt SLSQP on
// analytic gradients (chain rule through the piecewise-linear maps). A ring is passed cut open:
// boundary n is boundary 0 again, and its members need not close (3.7.1).
#include "propagation/side_map.hpp"

#include <string>
#include <vector>

namespace egg::propagation {

struct ChainBoundary {
  double lengthM = 1.0;  // l_i (only for reports: parameters are already normalised by it)
  double weight = 1.0;   // omega_i
  double minGap = 0.0;   // smallest member spacing on this boundary, as a parameter (metres / l_i)
};

struct ChainOriginal {
  int boundary = 0;    // where the member is fixed
  double value = 0.5;  // its parameter there, in (0, 1)
};

// A range of a boundary where a neighbour across a T-junction has already placed its members
// (Fig. 3.8): they are all originals, and no free member may lie strictly inside it.
struct ChainClosedRange {
  int boundary = 0;
  double from = 0.0, to = 1.0;  // parameters on that boundary, from < to
};

struct ChainProblem {
  std::vector<const SideMap*> maps;       // n: boundary i -> boundary i+1, increasing bijections
  std::vector<ChainBoundary> boundaries;  // n + 1
  int members = 2;                        // per boundary, both boundary members (0 and 1) included
  std::vector<ChainOriginal> originals;
  std::vector<ChainClosedRange> closed;
  void validate() const;  // throws InvalidInput naming the field
};

struct ChainOptions {
  double relativeTolerance = 1e-12;  // SLSQP stop on the objective's relative change
  int maxIterations = 500;           // objective evaluations
  // Ordering is enforced as a spacing of at least this (parameter units) where a boundary asks for
  // less, so members never coincide.
  double minOrderGap = 1e-6;
  void validate() const;
};

struct ChainSolution {
  std::vector<double> start;                   // member parameters on boundary 0, increasing
  std::vector<bool> fixed;                     // per member: boundary member or original
  std::vector<std::vector<double>> positions;  // per boundary, per member
  std::vector<double> startBefore;             // plain propagation (Fig. 3.9 left)
  double evennessBefore = 0.0;                 // objective of the plain propagation
  double evennessAfter = 0.0;                  // objective of `start` (<= before)
  int iterations = 0;                          // objective evaluations of SLSQP
  bool optimised = false;                      // SLSQP's point was accepted
  std::string status;  // NLopt's result, or why the plain propagation was kept
};

// The positions of members given by their parameters on boundary 0 on every boundary.
std::vector<std::vector<double>> propagateMembers(const ChainProblem& problem,
                                                  const std::vector<double>& start);
// Problem 3.3's objective for the members at `start`; with `gradient`, d/d start[k] for every k.
double chainObjective(const ChainProblem& problem, const std::vector<double>& start,
                      std::vector<double>* gradient = nullptr);
// The plain propagation: fixed members (0, 1, the originals pulled back to boundary 0 through
// G^-1) and the free members spaced equally on boundary 0 between them, the free count shared
// out by gap length. Throws InvalidInput when the originals leave fewer members than they need.
// A gap between two consecutive fixed members that lies inside a closed range gets none.
std::vector<double> plainStart(const ChainProblem& problem, std::vector<bool>* fixed = nullptr);
// The fixed members on boundary 0 (0, 1 and the originals pulled back, increasing) and, per gap
// between consecutive ones, whether it is closed (lies inside a closed range).
std::vector<double> fixedStarts(const ChainProblem& problem,
                                std::vector<bool>* closedGaps = nullptr);
ChainSolution solveChain(const ChainProblem& problem, const ChainOptions& options = {});

}  // namespace egg::propagation
