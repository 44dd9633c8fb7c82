#pragma once
// Planarisation of a generalised geodesic grid (thesis Section 4.7): the straight lamellas of a
// grid whose members run between anchors on a free-form boundary, laid out in the plane so that
// each keeps its length on the surface exactly and the crossings come as close as they can to
// where they are on the surface; what is left at a crossing is a notch (sliding connection).
//
// Variables: the planar endpoints (start, end) of every member. At a crossing of members g and h
// with arc-length fractions lambda_g, lambda_h on the surface, q_g = (1 - lambda_g) s_g +
// lambda_g e_g and q_h likewise (the thesis prints lambda and 1 - lambda the other way round,
// which would put lambda = 0 at the end point it is measured from). Problem (4.15):
//   minimise E_notch = sum over crossings |q_g - q_h|^2                            (4.14)
//   subject to |e_i - s_i|^2 = l_i^2 for every member                              (G_len)
//   and, for consecutive lamellas of one family, e_1..e_4 <= 0                     (Fig. 4.18)
// The e_k are the determinants of Section 4.7.2: the edges of two neighbours facing each other
// (offset by w/2 from the centre lines) must not cross. The thesis adds them to the objective as
// a linear hinge, mu sum max(e, 0); SLSQP does not converge on that kink (a two-lamella case
// stopped with both a longer notch and an overlap than the constrained optimum for mu up to 10),
// so here they are inequality constraints, which SLSQP treats exactly; where they cannot all hold
// (lamellas too wide for their spacing) the result lists the overlapping pairs. With the normal of
// a member taken as its direction over its fixed length, every term is quadratic in the endpoints,
// as in the thesis. Solved by SLSQP with analytic gradients (NLopt), as Problem 3.3 is in
// propagation/; the first member's start is held at its initial position (the problem is
// invariant under rigid motions). After the solve each member is rescaled about its midpoint to
// its length, so lengths hold to rounding, whatever the solver's constraint tolerance.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace egg::generalised {

// A grid member: a straight lamella between two anchors.
struct PlanarMember {
  double lengthM = 0.0;  // d(p_x, p_y) on the surface, kept exactly in the plane
  int family = 0;        // 0 (g) or 1 (h)
};

// Member g (family 0) crosses member h (family 1) at these fractions of their lengths, measured on
// the surface from their starts: lambda = d(start, q) / length, in [0, 1].
struct MemberCrossing {
  int g = -1;
  int h = -1;
  double lambdaG = 0.0;
  double lambdaH = 0.0;
};

// Consecutive members of one family whose lamellas must not overlap: `second` lies to the left of
// `first`, looking along `first` from its start to its end.
struct NeighbourPair {
  int first = -1;
  int second = -1;
};

using Segment2 = std::array<Eigen::Vector2d, 2>;  // planar (start, end), metres

struct PlanarisationProblem {
  std::vector<PlanarMember> members;
  std::vector<MemberCrossing> crossings;
  std::vector<NeighbourPair> neighbours;  // empty: no fabrication term
  // An initial planar layout of the same combinatorics (e.g. the surface grid flattened); its
  // lengths need not be the members'.
  std::vector<Segment2> initial;
  double widthM = 0.0;  // lamella width w of the fabrication term

  void validate() const;  // throws InvalidInput naming the field and the element
};

struct PlanarisationOptions {
  int maxEvaluations = 5000;
  double relativeTolerance = 1e-14;  // on the objective (NLopt ftol_rel)

  void validate() const;  // throws InvalidInput naming the field
};

struct PlanarisationResult {
  std::vector<Segment2> endpoints;    // the planar layout, each member exactly its length
  std::vector<double> notchLengthsM;  // |q_g - q_h| per crossing, in the order of the problem
  double notchEnergyM2 = 0.0;         // E_notch of the layout
  double initialNotchEnergyM2 = 0.0;  // E_notch of the initial layout rescaled to the lengths
  double lengthResidualM = 0.0;       // largest | |e - s| - l | of the layout (rounding)
  // Before the rescaling: the solver's own largest length violation (metres).
  double solverLengthResidualM = 0.0;
  // Indices into problem.neighbours of pairs whose lamellas overlap by more than 1e-9 m:
  // fabrication cannot cut them as laid out.
  std::vector<int> overlappingPairs;
  std::string status;  // NLopt's result
  int evaluations = 0;
  double seconds = 0.0;
};

PlanarisationResult planarise(const PlanarisationProblem& problem,
                              const PlanarisationOptions& options = {});

// The pieces, over x = (s_0, e_0, s_1, e_1, ...) (4 numbers per member), for tests and callers
// that check a layout: E_notch with its gradient (may be null), the length constraints
// |e - s|^2 - l^2 with their Jacobian (row-major, members x 4 members; may be null), and the four
// overlap determinants of a neighbour pair divided by the length of the edge they are taken
// against (signed distances, metres; positive: overlapping) with their gradients over the pair's
// coordinates (s_first, e_first, s_second, e_second; may be null).
double notchEnergy(const PlanarisationProblem& problem, const std::vector<double>& x,
                   std::vector<double>* gradient);
void lengthConstraints(const PlanarisationProblem& problem, const std::vector<double>& x,
                       std::vector<double>& values, std::vector<double>* jacobian);
std::array<double, 4> overlapDistances(const PlanarisationProblem& problem,
                                       const NeighbourPair& pair, const std::vector<double>& x,
                                       std::array<Eigen::Matrix<double, 8, 1>, 4>* gradients);

}  // namespace egg::generalised
