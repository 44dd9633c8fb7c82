#pragma once
// Grid members (Section 2.4.4): where to place the members of one family along its cladding
// function. A member is a pair (x1, x2 = F(x1)); the two boundary members (0,0) and (1,1) are
// always present. Automatic placement follows the thesis' heuristic:
//   1. members at the extrema of C(s), the member length along the cladding curve (locally
//      longest/shortest geodesics capture the large features), then at the extrema of the
//      curvature of C (finer features), prioritised by |C''| when they crowd;
//   2. no two members closer than the minimum spacing d+/d- that lamellas of width w need where
//      they meet the boundaries at angles beta (start side) and gamma (end side);
//   3. gaps wider than the target spacing are filled, and the filled members are evened out
//      (least squares on neighbour distances, which spaces them equally inside each gap).
// C is read through a Gaussian over a physical length (smoothingFraction * target spacing) and
// every extremum is a root of the smoothed C' or kappa', solved between samples: member positions
// move continuously with C. What stays discrete (a small change of C can still add, drop or swap
// a member): a candidate at exactly half the target spacing from another, |C''| at the
// featureFraction threshold, a gap at a half-integer multiple of the target spacing (the count of
// filled members), and crowding candidates of different tiers, or near-tied beyond tieBand.
// A fixed count instead spaces the members equally along the cladding curve.
// Deviations from Section 2.4.4, which places members at the extrema of C and of its curvature:
//   - the extrema are those of C smoothed by a Gaussian (smoothingFraction), not of C itself;
//   - a near-tie (tieBand) places one member between two crowding extrema, weighted by priority,
//     i.e. at neither extremum.
#include "core/egg/cladding.hpp"
#include "core/egg/planar_quad.hpp"

#include <vector>

namespace egg {

struct MemberOptions {
  int count = 0;                // members per family including both boundary members; 0 = automatic
  double lamellaWidthM = 0.05;  // w, lamella width (metres)
  double spacingFactor = 8.0;   // automatic: target spacing between members = factor * w
  double featureFraction =
      0.1;  // curvature extrema with |C''| below this fraction of the largest are ignored
  // Automatic placement reads C through a Gaussian of standard deviation smoothingFraction * target
  // spacing: a physical length, so the features found do not depend on how finely C is sampled,
  // as long as C's samples are at most sigma / 1.5 apart along the curve. Coarser samples widen the
  // Gaussian to 1.5 x the longest step (members.cpp: narrower, every sample of the piecewise-linear
  // C is a curvature extremum of its own); the members are then those of C smoothed over that
  // width. Half the spacing: features of C closer than about one spacing merge (they could not all
  // get members), a narrow feature's curvature extrema land about one spacing from its centre, and
  // on `egg bench grid` sub-millimetre map changes move members by about a millimetre (a quarter of
  // the spacing left curvature extrema so flat that they moved by centimetres).
  double smoothingFraction = 0.5;
  // Extrema are bracketed on a scan with this many points per smoothing length and then solved
  // for (roots of the smoothed derivatives): the scan density does not move them.
  int scanSamplesPerSigma = 4;
  // Two feature candidates of one tier that crowd each other and whose priorities |C''| differ by
  // less than this fraction are a near-tie: one member is placed between them, weighted by
  // priority, instead of the winner flipping with the last digits of C.
  double tieBand = 0.05;
  void validate() const;  // throws InvalidInput naming the field
};

// Given: chosen by the caller (membersAt in patch_design.hpp, e.g. by propagation, Section 3.4.4).
enum class MemberOrigin { Boundary, LengthExtremum, CurvatureExtremum, Filled, Even, Given };

struct FamilyMembers {
  Family family = Family::U;
  std::vector<double> x1;            // start-side parameters, increasing, x1[0] = 0, x1.back() = 1
  std::vector<double> x2;            // end-side parameters F(x1)
  std::vector<double> lengths;       // member lengths from the cladding function (metres)
  std::vector<MemberOrigin> origin;  // why each member is there
};

// sideLengths: spatial lengths of the family's start and end sides (metres), which the boundary
// parameters run along at constant speed. Throws InfeasiblePatch when the cladding function is
// not bijective, InvalidInput when a fixed count is too dense for the lamella width.
FamilyMembers placeMembers(const CladdingFunction& cladding, const PlanarQuad& quad,
                           double startSideLength, double endSideLength,
                           const MemberOptions& options = {});

// Minimum distance (metres, along a side) a lamella of width w needs where it crosses that side
// at angle theta: w / sin(theta) (its footprint on the side), split half to each neighbour.
double lamellaFootprint(double width, double angle);

// The angles (beta, gamma) between a planar member and the start and end sides, in (0, pi/2].
std::array<double, 2> boundaryAngles(const PlanarQuad& quad, Family family, double x1, double x2);

}  // namespace egg
