#include "core/egg/distance_map.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace egg {

DistanceMap::DistanceMap(int samples1, int samples2)
    : n1(samples1), n2(samples2), values(static_cast<size_t>(samples1) * samples2, 0.0) {}

double DistanceMap::interpolate(double x1, double x2) const {
  const double s = std::clamp(x1, 0.0, 1.0) * (n1 - 1);
  const double t = std::clamp(x2, 0.0, 1.0) * (n2 - 1);
  const int i = std::min(static_cast<int>(s), n1 - 2);
  const int j = std::min(static_cast<int>(t), n2 - 2);
  const double a = s - i, b = t - j;
  // Lower triangle (i,j),(i+1,j),(i,j+1) when a + b <= 1, else the upper one.
  if (a + b <= 1.0) return at(i, j) + a * (at(i + 1, j) - at(i, j)) + b * (at(i, j + 1) - at(i, j));
  return at(i + 1, j + 1) + (1.0 - a) * (at(i, j + 1) - at(i + 1, j + 1)) +
         (1.0 - b) * (at(i + 1, j) - at(i + 1, j + 1));
}

void PatchDistanceMaps::validate() const {
  for (Family family : {Family::U, Family::V}) {
    const DistanceMap& m = map(family);
    const std::string name = family == Family::U ? "D_u" : "D_v";
    if (m.n1 < 3 || m.n2 < 3)
      throw InvalidInput("distance map " + name + " needs at least 3x3 samples");
    if (m.values.size() != static_cast<size_t>(m.n1) * m.n2)
      throw InvalidInput("distance map " + name + " has " + std::to_string(m.values.size()) +
                         " values for " + std::to_string(m.n1) + "x" + std::to_string(m.n2) +
                         " samples");
    for (double d : m.values)
      if (!std::isfinite(d) || d < 0.0)
        throw InvalidInput("distance map " + name + " holds a non-finite or negative distance");
  }
  for (int k = 0; k < 4; ++k)
    if (!(sides[k] > 0.0))
      throw InvalidInput("patch side " + std::to_string(k) + " has no positive length");
  if (!(diagonalE > 0.0 && diagonalF > 0.0)) throw InvalidInput("patch diagonals must be positive");
  if (!(alphaSpatial > 0.0 && alphaSpatial < M_PI))
    throw InvalidInput("patch corner angle alpha must lie in (0, pi)");
}

DistanceMap planarDistanceMap(const PlanarQuad& quad, Family family, int n1, int n2) {
  DistanceMap map(n1, n2);
  const auto k = familyCorners(family);
  const auto& c = quad.corners;
  const Eigen::Vector2d start = c[k[0]], startDir = c[k[1]] - c[k[0]];
  const Eigen::Vector2d end = c[k[2]], endDir = c[k[3]] - c[k[2]];
  for (int i = 0; i < n1; ++i) {
    const Eigen::Vector2d p = start + (static_cast<double>(i) / (n1 - 1)) * startDir;
    for (int j = 0; j < n2; ++j)
      map.at(i, j) = (end + (static_cast<double>(j) / (n2 - 1)) * endDir - p).norm();
  }
  return map;
}

double planarDiagonalE(const PlanarQuad& quad) {
  return (quad.corners[2] - quad.corners[0]).norm();
}
double planarDiagonalF(const PlanarQuad& quad) {
  return (quad.corners[3] - quad.corners[1]).norm();
}

double diagonalProduct(const PatchDistanceMaps& maps, const PlanarQuad& quad) {
  return (maps.diagonalE - planarDiagonalE(quad)) * (maps.diagonalF - planarDiagonalF(quad));
}

}  // namespace egg
