#pragma once
// A member family's map from one boundary of a patch to the next (Section 3.4.4): the cladding
// function x2 = F(x1, alpha_bar) of Section 2.4.3, read forwards (members entering at the
// family's start side) or backwards through F^-1 (entering at its end side), in the parameter
// direction the chain uses on each boundary. Problem 3.3 only needs value, slope and inverse, so
// the optimiser sees this small interface and can be tested without surfaces.
#include <Eigen/Core>

#include <vector>

namespace egg::propagation {

// A strictly increasing bijection of [0, 1] onto itself.
class SideMap {
 public:
  virtual ~SideMap() = default;
  virtual double value(double x) const = 0;  // x clamped to [0, 1]
  // dvalue/dx; at a kink of a piecewise-linear map, the slope of the segment starting there
  // (right-continuous, as claddingSlope in core/egg/patch_design.hpp; at x = 1 the last one).
  virtual double slope(double x) const = 0;
  virtual double inverse(double y) const = 0;  // y clamped to [0, 1]
};

// Piecewise linear through knots (x, y), both coordinates strictly increasing from (0, 0) to
// (1, 1): the form the cladding functions have (Section 2.4.3).
class PiecewiseLinearMap final : public SideMap {
 public:
  PiecewiseLinearMap();  // the identity
  // Throws InvalidInput unless the knots run from (0,0) to (1,1) strictly increasing in both.
  explicit PiecewiseLinearMap(std::vector<Eigen::Vector2d> knots);
  double value(double x) const override;
  double slope(double x) const override;
  double inverse(double y) const override;
  const std::vector<Eigen::Vector2d>& knots() const { return knots_; }

  // F^-1 as a map of its own (the knots swapped): back-propagation (Fig. 3.8).
  PiecewiseLinearMap inverted() const;
  // x -> 1 - F(1 - x): the same map with both boundaries' parameters running the other way.
  PiecewiseLinearMap mirrored() const;

 private:
  std::vector<Eigen::Vector2d> knots_;
};

}  // namespace egg::propagation
