#pragma once
// Distance maps written in closed form, for testing the planar side of the EGG solver without the
// geodesic engine: planar (and hence developable: cylinder/cone unrolled) patches and geodesic
// quads on a sphere (great-circle distances).
#include "core/egg/distance_map.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>

namespace egg::testing {

inline double angleBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
}

// A planar patch with corners c0..c3 (counter-clockwise): its maps are planar distances and its
// corner angle is the planar angle at c0. A cylinder or cone patch has exactly these maps, with
// the corners taken in the unrolled plane.
inline PatchDistanceMaps planarPatchMaps(const std::array<Eigen::Vector2d, 4>& c, int n) {
  PatchDistanceMaps maps;
  for (int k = 0; k < 4; ++k) maps.sides[k] = (c[(k + 1) % 4] - c[k]).norm();
  maps.diagonalE = (c[2] - c[0]).norm();
  maps.diagonalF = (c[3] - c[1]).norm();
  maps.alphaSpatial = angleBetween(c[1] - c[0], c[3] - c[0]);
  for (Family family : {Family::U, Family::V}) {
    const auto k = familyCorners(family);
    DistanceMap m(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x1 = double(i) / (n - 1), x2 = double(j) / (n - 1);
        m.at(i, j) =
            ((c[k[2]] + x2 * (c[k[3]] - c[k[2]])) - (c[k[0]] + x1 * (c[k[1]] - c[k[0]]))).norm();
      }
    (family == Family::U ? maps.u : maps.v) = m;
  }
  return maps;
}

// Point at fraction t of the great-circle arc from unit vector a to unit vector b.
inline Eigen::Vector3d slerp(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t) {
  const double omega = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  if (omega < 1e-15) return a;
  return (std::sin((1 - t) * omega) * a + std::sin(t * omega) * b) / std::sin(omega);
}

inline double greatCircle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius) {
  return radius * std::atan2(a.cross(b).norm(), a.dot(b));
}

// A geodesic quad on a sphere of radius R with corner directions c0..c3 (normalised inside).
inline PatchDistanceMaps spherePatchMaps(std::array<Eigen::Vector3d, 4> c, double radius, int n) {
  for (auto& p : c) p.normalize();
  PatchDistanceMaps maps;
  for (int k = 0; k < 4; ++k) maps.sides[k] = greatCircle(c[k], c[(k + 1) % 4], radius);
  maps.diagonalE = greatCircle(c[0], c[2], radius);
  maps.diagonalF = greatCircle(c[1], c[3], radius);
  const Eigen::Vector3d t1 = (c[1] - c[1].dot(c[0]) * c[0]).normalized();
  const Eigen::Vector3d t3 = (c[3] - c[3].dot(c[0]) * c[0]).normalized();
  maps.alphaSpatial = std::acos(std::clamp(t1.dot(t3), -1.0, 1.0));
  for (Family family : {Family::U, Family::V}) {
    const auto k = familyCorners(family);
    DistanceMap m(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        m.at(i, j) = greatCircle(slerp(c[k[0]], c[k[1]], double(i) / (n - 1)),
                                 slerp(c[k[2]], c[k[3]], double(j) / (n - 1)), radius);
    (family == Family::U ? maps.u : maps.v) = m;
  }
  return maps;
}

// A sphere quad around the north pole: corners at polar angle theta, azimuths given (radians).
inline std::array<Eigen::Vector3d, 4> capCorners(double theta, std::array<double, 4> azimuths) {
  std::array<Eigen::Vector3d, 4> c;
  for (int k = 0; k < 4; ++k)
    c[k] = Eigen::Vector3d(std::sin(theta) * std::cos(azimuths[k]),
                           std::sin(theta) * std::sin(azimuths[k]), std::cos(theta));
  return c;
}

}  // namespace egg::testing
