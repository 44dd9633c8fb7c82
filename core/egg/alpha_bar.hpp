#pragma once
// Problem 2.3 (Section 2.4.3): the feasible range [alpha_bar_min, alpha_bar_max] of the planar
// angle for which both cladding functions exist, are bijective and have slopes inside
// (k_min, k_max), and the inequality (e - e_bar)(f - f_bar) < 0 holds.
//
// The problem has one unknown, so the feasible set is found directly rather than by SLSQP from a
// seed (which only sees the interval its seed lies in): a scan of the convex range (criterion iv),
// refined where a feasible stretch could hide between samples (a Lipschitz bound with the rates
// the scan itself shows), then the sign changes of each constraint located on their own to
// `tolerance`; the feasible set is the intersection of the constraints' negative sets. A feasible
// interval made by two constraints that overlap only slightly is therefore found whatever its
// width; one made by a single constraint dipping below zero between two samples is found by the
// refinement.
#include "core/egg/cladding.hpp"
#include "core/egg/distance_map.hpp"
#include "core/egg/planar_quad.hpp"

#include <string>
#include <vector>

namespace egg {

enum class AlphaBarChoice {
  Min,       // alpha_bar_min: the compact planar layout the thesis uses by default
  Max,       // alpha_bar_max
  Unrolled,  // alpha_bar = alpha, the surface angle at c0 (the unrolled grid of a developable
             // patch)
  Given      // a value in radians
};

struct AlphaBarOptions {
  double slopeMin = 0.1;   // k_min, lower slope bound of the cladding functions
  double slopeMax = 10.0;  // k_max, upper slope bound
  AlphaBarChoice choice = AlphaBarChoice::Min;  // which alpha_bar the grid is built at
  double givenAlphaBar = 0.0;                   // radians, used when choice == Given
  // Smallest inner angle of the planar quad (radians). Convexity alone (criterion iv) would let
  // the quad fold flat, where the lamellas of the planar grid lie on top of each other; this
  // keeps the flat grid buildable. 0 = convexity only.
  double minPlanarAngle = 0.15;
  // choice == Unrolled on a surface that is developable only up to its triangulation (a meshed
  // cylinder is not exactly flat): when the intersection at alpha is not bijective but the maps
  // agree within this fraction of the mean side length everywhere, the identity pairing is used.
  double unrolledTolerance = 2e-3;
  int scanSamples = 48;      // uniform samples of the convex range before refinement
  int maxEvaluations = 200;  // budget of refinement samples (each one cladding evaluation)
  double tolerance = 1e-8;   // radians, accuracy of alpha_bar_min / alpha_bar_max
  CladdingOptions cladding;  // intersection tolerances
  void validate() const;
};

// Parses the scene's grid.alpha_bar: "min" | "max" | "unrolled" | a number (radians).
// Throws InvalidInput naming the value otherwise.
void parseAlphaBarChoice(const std::string& text, AlphaBarOptions& options);

// Everything about one candidate alpha_bar.
struct AlphaBarEvaluation {
  double alphaBar = 0.0;
  bool closable = false;         // the planar quad exists and is convex
  double diagonalProduct = 0.0;  // (e - e_bar)(f - f_bar) / scale^2, must be < 0
  double violationU = 0.0;       // slopeViolation of F_u, must be < 0
  double violationV = 0.0;       // slopeViolation of F_v, must be < 0
  bool bijective = false;        // both cladding functions bijective (criterion iii)
  bool feasible = false;         // all constraints of Problem 2.3 strictly met
};
AlphaBarEvaluation evaluateAlphaBar(const PatchDistanceMaps& maps, double alphaBar,
                                    const AlphaBarOptions& options);

struct AlphaBarResult {
  double alphaBar = 0.0;    // the chosen angle, radians
  bool rangeFound = false;  // a feasible alpha_bar exists
  double alphaMin = 0.0;    // alpha_bar_min (valid if rangeFound)
  double alphaMax = 0.0;    // alpha_bar_max (valid if rangeFound)
  // The feasible set itself: it need not be one interval. A patch of positive curvature is
  // typically feasible only away from its own angle alpha (the maps barely meet there), so the
  // set is [alpha_min, a] U [b, alpha_max]. Every end is located to options.tolerance.
  std::vector<AngleInterval> feasibleIntervals;
  AngleInterval convexRange;  // angles giving a closable convex planar quad
  PlanarQuad quad;            // planar patch at alphaBar
  CladdingFunction claddingU, claddingV;
  double slopeMin = 0.0,
         slopeMax = 0.0;    // extreme segment slopes of F_u, F_v at alphaBar (thesis form)
  bool degenerate = false;  // the maps coincide at alphaBar (developable at its unrolled angle)
  int evaluations = 0;      // cladding evaluations spent
  int scanSamples = 0;      // samples of the scan after refinement
  std::string status;       // how the bounds were settled
  double seconds = 0.0;
};

// Solves Problem 2.3 and builds the planar quad and cladding functions at the chosen angle.
// Throws InfeasiblePatch when no feasible alpha_bar exists (choice min/max) or when the requested
// angle gives no bijective cladding function (choice unrolled/given); InvalidInput on bad input.
AlphaBarResult solveAlphaBar(const PatchDistanceMaps& maps, const AlphaBarOptions& options = {});

}  // namespace egg
