#pragma once
// The elastic grid energy and its minimisation (thesis Sections 4.6.3-4.6.4):
//   E_grid = E_effort / ((n + m) kappa_s^4) - lambda E_shape                          (4.12)
// E_effort (Eq. 4.11) is in 1/m^4; divided by the member count and by the square of the surface's
// mean squared curvature kappa_s^2 (GridDomain::kappaScale2) it becomes minus the variance of the
// members' efforts in units of the surface's own, so that one lambda suits every surface and size
// (the thesis gives no value for its lambda).
//
// Optimisation. E_grid is piecewise constant in the anchors (they sit on boundary samples), jumps
// where the combinatorics change, and has many local minima (Fig. 4.19): gradients are useless and
// a local method stops at the first plateau. The thesis runs a genetic algorithm over all anchor
// parameters, seeded with rotations of the grid. We split that search in two:
//  1. global: DIRECT-L (NLopt; Gablonsky and Kelley's locally biased DIRECT) over the layout's
//     rotation, skew and line offsets (4 numbers). DIRECT divides the box and samples every part
//     of it, ever finer where the energy is low: it needs no gradient, is deterministic (the same
//     grid on every run, which a random GA is not), and its samples spread over the whole box
//     before they gather (dense in it in the limit), so a basin of the kind Fig. 4.19 shows is
//     found by the division, not by a lucky seed; with a finite budget it is no guarantee;
//  2. local, in the discrete dual space: each anchor of each member moved by one and two samples
//     either way (Section 4.5.4's discrete domain), a move kept when the layout stays buildable
//     (layoutProblem) and E_grid falls, until a sweep keeps nothing. This is the per-anchor
//     freedom of the thesis's t-vector that a rotation of parallel lines cannot reach.
#include "core/generalised/generalised_grid.hpp"
#include "core/generalised/shape_stability.hpp"

#include <vector>

namespace egg::generalised {

struct GridEnergyOptions {
  double shapeWeight = 1.0;  // lambda of Eq. 4.12 (dimensionless with the scaling above)
  ShapeStabilityOptions shape;
  void validate() const;  // throws InvalidInput naming the field
};

struct GridEnergy {
  std::vector<double> efforts;  // E_c per member (Eq. 4.10, 1/m^2)
  double eEffort = 0.0;         // Eq. 4.11 (1/m^4)
  double eEffortScaled = 0.0;   // E_effort / ((n + m) kappa_s^4), dimensionless
  ShapeStabilityResult shape;   // eta per member and E_shape (Eq. 4.9)
  double eShape = 0.0;
  double eGrid = 0.0;  // Eq. 4.12 as above
};

// The energy of a buildable layout with its crossings (gridCrossings). Traces the members it has
// not seen yet (GridDomain::member).
GridEnergy gridEnergy(const GridDomain& domain, const GeneralisedLayout& layout,
                      const std::vector<GridCrossing>& crossings,
                      const GridEnergyOptions& options = {});

struct GridOptimisationOptions {
  std::array<int, 2> lines = {6, 6};  // lines per family
  double maxSkewRad = 0.35;           // |skew| of the families' angle from 90 degrees
  int globalEvaluations = 400;        // DIRECT-L evaluations
  int maxRefinementSweeps = 4;        // sweeps of the anchor moves (0: none)
  // A layout with two members crossing at less than this is unbuildable (radians): a bolt through
  // lamellas a few degrees apart holds nothing, and the notch would run along the lamella. The
  // angle is the traced members' at the field crossing.
  double minCrossingAngleRad = 0.2618;  // 15 degrees
  LayoutOptions layout;
  GridEnergyOptions energy;
  void validate() const;  // throws InvalidInput naming the field
};

struct GridOptimisationResult {
  LayoutParameters parameters;  // the best rotation, skew and offsets
  GeneralisedLayout layout;     // after the anchor moves
  std::vector<GridCrossing> crossings;
  GridEnergy energy;
  double initialEGrid = 0.0;     // the layout at rotation 0, no skew, offsets 1/2
  double globalEGrid = 0.0;      // after stage 1
  int evaluations = 0;           // energy evaluations, both stages
  int buildableEvaluations = 0;  // of which on buildable layouts
  int anchorMoves = 0;           // moves kept in stage 2
  int tracedMembers = 0;         // distinct members traced (the cache's size)
  double seconds = 0.0;          // t_opt of Table 4.1
};

// Throws InvalidInput when no buildable layout was found (e.g. too many lines for the boundary's
// samples).
GridOptimisationResult optimiseGrid(const GridDomain& domain,
                                    const GridOptimisationOptions& options = {});

}  // namespace egg::generalised
