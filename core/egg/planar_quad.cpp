#include "core/egg/planar_quad.hpp"

#include <cmath>
#include <vector>

namespace egg {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

std::array<double, 4> innerAngles(const std::array<Eigen::Vector2d, 4>& c) {
  std::array<double, 4> angles{};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d toNext = c[(k + 1) % 4] - c[k];
    const Eigen::Vector2d toPrev = c[(k + 3) % 4] - c[k];
    // Signed angle from toNext to toPrev: in (0, pi) at every corner of a CCW convex quad.
    angles[k] = std::atan2(cross2(toNext, toPrev), toNext.dot(toPrev));
  }
  return angles;
}

std::optional<PlanarQuad> planarQuad(const QuadSides& sides, double alphaBar, double minAngle) {
  if (!(alphaBar > 0.0 && alphaBar < M_PI)) return std::nullopt;
  PlanarQuad quad;
  quad.alphaBar = alphaBar;
  quad.corners[0] = Eigen::Vector2d::Zero();
  quad.corners[1] = Eigen::Vector2d(sides[0], 0.0);
  quad.corners[3] = sides[3] * Eigen::Vector2d(std::cos(alphaBar), std::sin(alphaBar));
  // c2 closes the four-bar linkage: |c2 - c1| = sides[1], |c2 - c3| = sides[2].
  const Eigen::Vector2d c1 = quad.corners[1], c3 = quad.corners[3];
  const double span = (c3 - c1).norm();
  const double r1 = sides[1], r2 = sides[2];
  if (span <= 0.0 || span > r1 + r2 || span < std::abs(r1 - r2)) return std::nullopt;
  const Eigen::Vector2d along = (c3 - c1) / span;
  const double x = (span * span + r1 * r1 - r2 * r2) / (2.0 * span);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - x * x));
  Eigen::Vector2d normal(-along.y(), along.x());
  // c2 lies across the diagonal c1c3 from c0.
  if (cross2(along, quad.corners[0] - c1) > 0.0) normal = -normal;
  quad.corners[2] = c1 + x * along + h * normal;
  for (double angle : innerAngles(quad.corners))
    if (!(angle > minAngle && angle < M_PI - minAngle)) return std::nullopt;
  return quad;
}

std::optional<AngleInterval> convexAlphaRange(const QuadSides& sides, double margin,
                                              double minAngle) {
  // The closable convex configurations of a four-bar linkage form one interval of the input
  // angle; scan for it and sharpen both ends by bisection.
  constexpr int kSamples = 2048;
  int bestStart = -1, bestLength = 0, runStart = -1;
  std::vector<bool> valid(kSamples + 1);
  for (int i = 0; i <= kSamples; ++i) {
    valid[i] = planarQuad(sides, M_PI * i / kSamples, minAngle).has_value();
    if (valid[i] && runStart < 0) runStart = i;
    if ((!valid[i] || i == kSamples) && runStart >= 0) {
      const int end = valid[i] ? i + 1 : i;
      if (end - runStart > bestLength) bestLength = end - runStart, bestStart = runStart;
      runStart = -1;
    }
  }
  if (bestLength == 0) return std::nullopt;
  auto sharpen = [&](double inside, double outside) {
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (inside + outside);
      (planarQuad(sides, mid, minAngle) ? inside : outside) = mid;
    }
    return inside;
  };
  const double step = M_PI / kSamples;
  const double firstValid = bestStart * step, lastValid = (bestStart + bestLength - 1) * step;
  AngleInterval range;
  range.lo = sharpen(firstValid, std::max(0.0, firstValid - step)) + margin;
  range.hi = sharpen(lastValid, std::min(M_PI, lastValid + step)) - margin;
  if (range.hi < range.lo) return std::nullopt;
  return range;
}

std::array<int, 4> familyCorners(Family family) {
  return family == Family::U ? std::array<int, 4>{0, 3, 1, 2} : std::array<int, 4>{0, 1, 3, 2};
}

std::array<Eigen::Vector2d, 2> planarMember(const PlanarQuad& quad, Family family, double x1,
                                            double x2) {
  const auto k = familyCorners(family);
  const auto& c = quad.corners;
  return {c[k[0]] + x1 * (c[k[1]] - c[k[0]]), c[k[2]] + x2 * (c[k[3]] - c[k[2]])};
}

double planarDistance(const PlanarQuad& quad, Family family, double x1, double x2) {
  const auto ends = planarMember(quad, family, x1, x2);
  return (ends[1] - ends[0]).norm();
}

}  // namespace egg
