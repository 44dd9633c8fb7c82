#include "propagation/side_map.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <string>

namespace egg::propagation {

PiecewiseLinearMap::PiecewiseLinearMap() : knots_{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)} {}

PiecewiseLinearMap::PiecewiseLinearMap(std::vector<Eigen::Vector2d> knots)
    : knots_(std::move(knots)) {
  if (knots_.size() < 2 || knots_.front() != Eigen::Vector2d(0, 0) ||
      knots_.back() != Eigen::Vector2d(1, 1))
    throw InvalidInput("PiecewiseLinearMap: the knots must run from (0, 0) to (1, 1)");
  for (size_t k = 1; k < knots_.size(); ++k)
    if (!(knots_[k].x() > knots_[k - 1].x()) || !(knots_[k].y() > knots_[k - 1].y()))
      throw InvalidInput("PiecewiseLinearMap: knot " + std::to_string(k) +
                         " does not increase strictly in both coordinates");
}

namespace {
// Index of the segment [k, k+1] containing `key` in coordinate `axis`: the last knot at or below
// it starts the segment (right-continuous), the last segment at 1.
size_t segmentOf(const std::vector<Eigen::Vector2d>& knots, double key, int axis) {
  size_t lo = 0, hi = knots.size() - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (knots[mid][axis] <= key ? lo : hi) = mid;
  }
  return lo;
}
}  // namespace

double PiecewiseLinearMap::value(double x) const {
  x = std::clamp(x, 0.0, 1.0);
  const size_t k = segmentOf(knots_, x, 0);
  const Eigen::Vector2d &a = knots_[k], &b = knots_[k + 1];
  return a.y() + (x - a.x()) * (b.y() - a.y()) / (b.x() - a.x());
}

double PiecewiseLinearMap::slope(double x) const {
  const size_t k = segmentOf(knots_, std::clamp(x, 0.0, 1.0), 0);
  const Eigen::Vector2d step = knots_[k + 1] - knots_[k];
  return step.y() / step.x();
}

double PiecewiseLinearMap::inverse(double y) const {
  y = std::clamp(y, 0.0, 1.0);
  const size_t k = segmentOf(knots_, y, 1);
  const Eigen::Vector2d &a = knots_[k], &b = knots_[k + 1];
  return a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
}

PiecewiseLinearMap PiecewiseLinearMap::inverted() const {
  std::vector<Eigen::Vector2d> swapped;
  for (const auto& k : knots_) swapped.emplace_back(k.y(), k.x());
  return PiecewiseLinearMap(std::move(swapped));
}

PiecewiseLinearMap PiecewiseLinearMap::mirrored() const {
  std::vector<Eigen::Vector2d> out;
  for (auto it = knots_.rbegin(); it != knots_.rend(); ++it)
    out.emplace_back(1.0 - it->x(), 1.0 - it->y());
  out.front() = Eigen::Vector2d(0, 0);  // exact ends despite rounding of 1 - x
  out.back() = Eigen::Vector2d(1, 1);
  return PiecewiseLinearMap(std::move(out));
}

}  // namespace egg::propagation
