#pragma once
// The design step of one patch, separate from its grid (Sections 2.4.1-2.4.3, 3.3):
// an already cut patch -> solver set-up -> eta check (smoothing only when asked) -> distance maps
// -> Problem 2.3 -> cladding functions F_u, F_v. The design keeps what tracing needs (the patch,
// its fine DistanceSolver, the maps, the alpha_bar result), so that the multi-patch flow can
//   - evaluate trial patches cheaply (no members, no tracing) and split infeasible ones by the
//     data of their failure (Workflow 1, Algorithm 1 in Section 3.4.3),
//   - read F(x1, alpha_bar) and dF/dx1 for propagation's SQP (Problem 3.3, Section 3.4.4),
//   - trace member coordinates chosen elsewhere (membersAt + traceDesignGrid,
//   Sections 2.4.4-2.4.6).
// solveEgg (solve_patch.hpp) is makePatch + designPatch + placeDesignMembers + traceDesignGrid.
#include "core/egg/alpha_bar.hpp"
#include "core/egg/grid.hpp"
#include "core/egg/members.hpp"
#include "core/egg/patch.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/egg/uniqueness.hpp"

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace egg {

struct EggOptions {
  PatchOptions patch;            // cutting the quad out of the surface
  UniquenessOptions uniqueness;  // eta check and smoothing (2.3.3, 3.4.1)
  DistanceMapOptions maps;       // distance map resolution
  AlphaBarOptions alphaBar;      // Problem 2.3 and the choice of alpha_bar
  MemberOptions members;         // member placement
  GridOptions grid;              // tracing, notches, anchors
  void validate() const;
};

// Wall times (seconds) of the parts of one solve. distanceMaps includes the eta check's K peaks
// and its peak and p1 fields, which run alongside the maps; uniqueness is the solver set-up, the
// check on the maps and any smoothing (with its own checks); sqp is Problem 2.3; tracing builds the
// grid. A design fills uniqueness, distanceMaps, sqp and total (its own time); solveEgg the rest.
struct EggTimings {
  double patch = 0.0, uniqueness = 0.0, distanceMaps = 0.0, sqp = 0.0, members = 0.0, tracing = 0.0,
         total = 0.0;
};

// Why a patch cannot carry a grid, as data Workflow 1 splits by (Section 3.4.3): eta fails for one
// family -> a new side through `peak`, both -> a corner at `peak`; the same for slopes.
enum class DesignFailureKind {
  Eta,     // shortest geodesics are not unique (eta > eta_max, Section 2.3.3) and smoothing is off
  Slopes,  // Problem 2.3 has no feasible alpha_bar (slopes of F outside (k_min, k_max), not
           // bijective, or (e - e_bar)(f - f_bar) >= 0), or the requested angle is infeasible
  Convexity  // criterion (iv): an inner angle reached pi after smoothing, or no convex planar quad
};
struct DesignFailure {
  DesignFailureKind kind = DesignFailureKind::Eta;
  // Which families fail. Eta: eta_u / eta_v > eta_max. Slopes: slopeViolation of F_u / F_v >= 0 at
  // the best sample of the convex range (both when only the diagonal inequality fails there).
  // Convexity after smoothing: those of the eta failure that called for smoothing; no convex
  // planar quad: both.
  bool familyU = false, familyV = false;
  // Eta (and Convexity after smoothing): p_max of the worst failing eta check. Slopes: the
  // strongest K peak of the patch. Otherwise, or with no peak: the patch vertex nearest to the
  // mean of its vertices.
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  std::string message;  // what solveEgg throws (InfeasiblePatch), unchanged from before the split
};

struct PatchDesign {
  Patch patch;  // the (possibly smoothed) patch
  // The fine patch's solver (it copies the mesh): tracing reuses its tables. Shared, so a design
  // copies cheaply; it is only read (const), safe from several threads.
  std::shared_ptr<const geodesic::DistanceSolver> solver;
  EggOptions options;  // as designed (claddingAt, placeDesignMembers read them)
  PatchPeaks peaks;    // interior K peaks, strongest first
  UniquenessReport uniqueness;
  PatchDistanceMaps maps;   // empty only when the design failed before the maps
  AlphaBarResult alphaBar;  // valid when feasible: the chosen angle, quad, F_u, F_v
  bool feasible = false;
  DesignFailure failure;  // valid when !feasible
  EggTimings seconds;     // uniqueness, distanceMaps, sqp, total
  int propagations = 0;   // distance propagations of the design (the patch's own not included)
};

// Designs an already cut patch. Infeasibility (eta, slopes, convexity) is returned in
// `feasible` / `failure`, not thrown: this is the cheap evaluation of a trial patch (maps and
// Problem 2.3, no members, no tracing). Throws InvalidInput on bad options and SolverFailure when
// a solve breaks down.
PatchDesign designPatch(Patch patch, const EggOptions& options = {});
// The throwing convenience: InfeasiblePatch(failure.message) when the design is infeasible.
void requireFeasible(const PatchDesign& design);

// F(x1) at the design's alpha_bar (x1 clamped to [0, 1]), its derivative and its inverse. F is
// piecewise linear (Section 2.4.3); the derivative is the slope of the segment containing x1,
// right-continuous at kinks (the segment starting there; at x1 = 1 the last one), the segment
// CladdingFunction::evaluate interpolates on. Throw InvalidInput on an infeasible design.
double claddingValue(const PatchDesign& design, Family family, double x1);
double claddingSlope(const PatchDesign& design, Family family, double x1);
double claddingInverse(const PatchDesign& design, Family family, double x2);
// The same derivative for any bijective cladding function (e.g. one from claddingAt).
double claddingSlope(const CladdingFunction& cladding, double x1);
// F at another angle alpha_bar (propagation varies it, Problem 3.3): the maps intersected with the
// planar quad at alpha_bar, as Problem 2.3 evaluates it (bit-identical to the design's own F at its
// alpha_bar, except for choice Unrolled on a near-developable patch, which loosens the tolerance).
// The caller checks bijective() / slopes; throws InvalidInput when no convex quad has that angle.
CladdingFunction claddingAt(const PatchDesign& design, Family family, double alphaBar);

// Automatic member placement on the design's F (Section 2.4.4), as solveEgg does.
FamilyMembers placeDesignMembers(const PatchDesign& design, Family family,
                                 const MemberOptions& options);
// Members at given start parameters x1 (strictly increasing, x1[0] = 0, x1.back() = 1): x2 = F(x1),
// lengths from F, origin Boundary at the ends and Given inside. No spacing check (the caller chose
// them, e.g. propagation). Throws InvalidInput on bad x1 or an infeasible design.
FamilyMembers membersAt(const PatchDesign& design, Family family, const std::vector<double>& x1);

// The grid step: buildGrid on the design's patch, solver and planar quad (Sections 2.4.5, 2.4.6).
EggGrid traceDesignGrid(const PatchDesign& design, const FamilyMembers& u, const FamilyMembers& v,
                        const GridOptions& options = {});

}  // namespace egg
