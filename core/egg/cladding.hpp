#pragma once
// Cladding functions (Section 2.4.3): x2 = F(x1, alpha_bar) is the projection of the intersection
// of the surface distance map D and the planar distance map D_bar(alpha_bar) onto the (x1, x2)
// plane. Points on it are pairs of boundary points whose geodesic on the surface and straight
// line in the plane have the same length (criterion i); it is a valid parametrisation of a member
// family when it runs from (0,0) to (1,1) and is strictly increasing (criterion iii).
//
// Following the thesis, F is kept as a piecewise-linear parametric curve over the whole domain:
// the zero set of D - D_bar on the triangulated map grid, completed along the domain boundary when
// the intersection does not reach a corner, so that slope constraints see every defect.
#include "core/egg/distance_map.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg {

struct CladdingOptions {
  // Maps that differ by less than this (relative to the mean side length) everywhere coincide:
  // a developable patch at its unrolled angle. F is then the identity (any pairing is exact).
  double degenerateTolerance = 1e-6;
  // c in the thesis' replacement F' = c * dx2 for vertical segments (c >> k_max), Section 2.4.3.
  double infiniteSlopeFactor = 1e4;
  void validate() const;
};

struct CladdingFunction {
  Family family = Family::U;
  std::vector<Eigen::Vector2d> points;  // (x1, x2) from (0,0) to (1,1)
  std::vector<double> lengths;          // member length at each point (D = D_bar there), metres
  bool degenerate = false;              // the maps coincide: identity chosen
  bool connectsCorners = false;         // the intersection itself runs from (0,0) to (1,1)

  // Criterion (iii): connects the corners and strictly increases in both coordinates.
  bool bijective() const;
  // x2 = F(x1) and x1 = F^-1(x2) by linear interpolation; require bijective().
  double evaluate(double x1) const;
  double inverse(double x2) const;
  // Member length at x1 (interpolated along the curve); requires bijective().
  double lengthAt(double x1) const;
};

// Intersects the surface map with the planar map (same grid). `scale` is the patch's length scale
// (mean side length) for the tolerances.
CladdingFunction claddingFunction(const DistanceMap& surface, const DistanceMap& planar,
                                  Family family, double scale, const CladdingOptions& options = {});
// The same against the planar map of `quad` in closed form (planarDistanceMap), evaluated only at
// the grid nodes the intersection passes: what Problem 2.3 calls for every candidate alpha_bar.
CladdingFunction claddingFunction(const DistanceMap& surface, const PlanarQuad& quad, Family family,
                                  double scale, const CladdingOptions& options = {});

// Slopes of the segments by finite differences dx2/dx1 (Section 2.4.3); a vertical segment
// (dx1 = 0) gets c * dx2 as in the thesis. Zero-length segments are skipped.
std::vector<double> segmentSlopes(const CladdingFunction& cladding, double infiniteSlopeFactor);

// Largest violation of k_min < F' < k_max over all segments, measured on the segment direction
// (max(k_min dx1 - dx2, dx2 - k_max dx1) / |segment|) so it stays finite and continuous in
// alpha_bar through vertical segments. Negative iff every slope is strictly inside the bounds.
double slopeViolation(const CladdingFunction& cladding, double slopeMin, double slopeMax);

}  // namespace egg
