#pragma once
// The shape-stability energy E_shape of a generalised grid (thesis Section 4.6.2, Figs. 4.13 and
// 4.14, Eq. 4.9). It estimates, without a physical simulation, how closely the deployed grid keeps
// its target shape.
//
// Each member is a geodesic, so its curvature is all normal curvature kappa_n(s). The member's
// shape-stability parameter eta follows from the number sigma of inflection points (sign changes of
// kappa_n): sigma < 2 is stable (eta = 1), sigma > 2 unstable (eta = 0), and sigma = 2 is decided
// by the criterion of Hafner and Bickel ("The design space of plane elastic curves", ACM TOG 40(4),
// 2021, doi 10.1145/3450626.3459800), torsion neglected: the member is taken as the plane curve
// whose signed curvature is kappa_n(s) (planarCurveFromCurvature).
//
// Hafner-Bickel's characterisation (the paper's abstract: "a geometric characterization of the
// design space of plane elastic rods with variable stiffness"; the form below is read off the
// authors' code, github.com/chrishafner/elastic-curves, whose LP for the stiffness K imposes
// K kappa = a + <b, x> with K >= 1 and a + <b, x> = 0 at every inflection point): a plane curve
// is the equilibrium of a rod with a positive, varying bending stiffness K(s) held at its ends iff
// its bending moment K(s) kappa(s) equals a + <b, x(s)>, the end force b times the signed distance
// of x(s) to the force's line of action. Since K > 0, kappa(s) must have the sign of that distance
// everywhere: every inflection point lies on the line, the kappa > 0 part on one side and the
// kappa < 0 part on the other. With two inflection points the line is the one
// through both, and nothing is left to choose, which is why the thesis calls sigma = 2 the limit
// case (Fig. 4.13 c). The paper also tests such equilibria for buckling (a second-variation
// analysis that needs the stiffness and the end conditions); the thesis gives neither for its
// members, so we read its "stability criterion" as the characterisation above (an assumption).
//
// Mutual stabilisation (Fig. 4.14): an unstable member is divided by its inflection points into
// (sigma - 1) segments R_j needing support; omega_j = 1 when at least one member that is stable on
// its own crosses it within R_j, and the member's eta becomes the mean of its omega_j. E_shape is
// the mean eta over all members (Eq. 4.9), in [0, 1].
#include <Eigen/Core>
#include <vector>

namespace egg::generalised {

// kappa_n sampled along one member: arc length strictly increasing (m; any start, conventionally
// 0) and kappa_n there (1/m), one value per arc length.
struct MemberCurvatureProfile {
  std::vector<double> arcLengthM;
  std::vector<double> kappaN;
};

// Two members crossing, given once per pair: `first` passes the crossing at `firstArcLengthM`
// along itself, `second` at `secondArcLengthM` (both in the arc-length frame of that member's
// profile). Each supports the other (Fig. 4.14).
struct StabilityCrossing {
  int first = -1;
  double firstArcLengthM = 0.0;
  int second = -1;
  double secondArcLengthM = 0.0;
};

struct ShapeStabilityOptions {
  // kappa_n with |kappa_n| at most this fraction of the member's max |kappa_n| counts as zero
  // (dimensionless): sign changes inside such a band (noise on a flat stretch) are no inflections,
  // and one sign change is counted across the band between two lobes of opposite sign.
  double relativeZeroTolerance = 0.05;
  // A member whose max |kappa_n| is at most this is straight, with no inflections (1/m).
  double absoluteZeroToleranceInvM = 1e-9;
  // The Hafner-Bickel test accepts a curve point on the wrong side of the inflection line by at
  // most this fraction of the member's length (dimensionless), for sampling and integration error.
  double lineSideTolerance = 0.005;

  // Throws InvalidInput naming the field at fault.
  void validate() const;
};

// The arc lengths (m) of the inflection points of a profile: sign changes of kappa_n between
// samples outside the zero band (ShapeStabilityOptions), each placed where the line between the
// last sample of one sign and the first of the other crosses zero. Throws InvalidInput for a
// malformed profile (see shapeStability).
std::vector<double> inflectionArcLengths(const MemberCurvatureProfile& profile,
                                         const ShapeStabilityOptions& options = {});

// The plane curve with signed curvature kappa_n(s), one point per sample: starting at the origin
// along +x, the turning angle integrated by the trapezoidal rule and each step taken along the
// mean of its end angles (m). Throws InvalidInput for a malformed profile.
std::vector<Eigen::Vector2d> planarCurveFromCurvature(const MemberCurvatureProfile& profile);

// Hafner-Bickel's test for a member with two inflection points (at arc lengths
// inflectionArcLengthsM): whether every sample outside the zero band lies on the side of the line
// through the two inflection points that its sign of kappa_n asks for (within
// lineSideTolerance). False when the two points coincide (no line to test).
bool hafnerBickelTwoInflections(const MemberCurvatureProfile& profile,
                                const std::vector<double>& inflectionArcLengthsM,
                                const ShapeStabilityOptions& options = {});

struct ShapeStabilityResult {
  std::vector<int> inflections;                            // sigma per member
  std::vector<std::vector<double>> inflectionArcLengthsM;  // where they are (m)
  std::vector<double> ownEta;  // eta of each member on its own: 0 or 1 (Fig. 4.13)
  std::vector<double> eta;     // after mutual stabilisation (Fig. 4.14), in [0, 1]
  double eShape = 0.0;         // Eq. 4.9, in [0, 1]
};

// E_shape of a grid whose members have the given profiles and cross as given. Throws InvalidInput
// for no members, a profile with fewer than two samples, sizes that differ, values that are not
// finite or arc lengths not strictly increasing (naming the member), and a crossing whose member is
// out of range, crosses itself or lies outside the member's arc length (naming the crossing).
ShapeStabilityResult shapeStability(const std::vector<MemberCurvatureProfile>& profiles,
                                    const std::vector<StabilityCrossing>& crossings,
                                    const ShapeStabilityOptions& options = {});

}  // namespace egg::generalised
