#pragma once
// Exactly developable test meshes: a cylinder strip triangulated along its rulings (every cell is
// a planar rectangle, so the polyhedral surface unrolls isometrically onto the plane).
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace egg::testing {

struct RuledCylinder {
  double radius = 3.0;
  double angle = 2.0;   // angular span (radians)
  double length = 6.0;  // along the axis x
  int segments = 40;    // around
  int rows = 30;        // along the axis
  double chord() const { return 2 * radius * std::sin(0.5 * angle / segments); }
  double unrolledWidth() const { return segments * chord(); }

  Eigen::Vector3d ring(int k, double x) const {
    const double phi = -0.5 * angle + angle * k / segments;
    return {x, radius * std::sin(phi), radius * std::cos(phi)};
  }
  TriMesh mesh() const {
    TriangleSoup soup;
    for (int j = 0; j <= rows; ++j)
      for (int k = 0; k <= segments; ++k)
        soup.vertices.push_back(ring(k, -0.5 * length + length * j / rows));
    const auto id = [&](int k, int j) { return j * (segments + 1) + k; };
    for (int j = 0; j < rows; ++j)
      for (int k = 0; k < segments; ++k) {
        soup.triangles.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
        soup.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
      }
    return meshFromSoup(soup);
  }
  // Unrolled coordinates (w along the chords from the first ruling, x along the axis) -> 3D point.
  Eigen::Vector3d fromUnrolled(const Eigen::Vector2d& p) const {
    const double w = std::clamp(p.x(), 0.0, unrolledWidth());
    const int k = std::min(static_cast<int>(w / chord()), segments - 1);
    const double t = w / chord() - k;
    return ring(k, p.y()) + t * (ring(k + 1, p.y()) - ring(k, p.y()));
  }
  // 3D point on the strip -> unrolled coordinates.
  Eigen::Vector2d toUnrolled(const Eigen::Vector3d& q) const {
    double phi = std::atan2(q.y(), q.z()) + 0.5 * angle;
    const int k = std::clamp(static_cast<int>(phi / (angle / segments)), 0, segments - 1);
    const Eigen::Vector3d a = ring(k, q.x()), b = ring(k + 1, q.x());
    const double t = (q - a).dot(b - a) / (b - a).squaredNorm();
    return {(k + t) * chord(), q.x()};
  }
};

// A cone frustum triangulated along its rulings: every cell lies in the plane of two rulings
// through the apex, so the polyhedral surface unrolls exactly onto a planar annular sector.
struct RuledCone {
  double halfAngle = 0.5;             // angle between axis (z) and rulings
  double angle = 2.5;                 // angular span around the axis (radians)
  double rInner = 3.0, rOuter = 9.0;  // distances from the apex along the rulings
  int segments = 40, rows = 30;
  Eigen::Vector3d ruling(int k) const {
    const double phi = -0.5 * angle + angle * k / segments;
    return {std::sin(halfAngle) * std::cos(phi), std::sin(halfAngle) * std::sin(phi),
            -std::cos(halfAngle)};
  }
  double cellAngle() const { return std::acos(std::clamp(ruling(0).dot(ruling(1)), -1.0, 1.0)); }
  TriMesh mesh() const {
    TriangleSoup soup;
    for (int j = 0; j <= rows; ++j)
      for (int k = 0; k <= segments; ++k)
        soup.vertices.push_back((rInner + (rOuter - rInner) * j / rows) * ruling(k));
    const auto id = [&](int k, int j) { return j * (segments + 1) + k; };
    for (int j = 0; j < rows; ++j)
      for (int k = 0; k < segments; ++k) {
        soup.triangles.push_back({id(k, j), id(k, j + 1), id(k + 1, j + 1)});
        soup.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k + 1, j)});
      }
    return meshFromSoup(soup);
  }
  // Unrolled polar coordinates (rho from the apex, psi from the first ruling) -> 3D and back.
  Eigen::Vector3d fromUnrolled(double rho, double psi) const {
    const int k = std::clamp(static_cast<int>(psi / cellAngle()), 0, segments - 1);
    const double t = psi - k * cellAngle();
    const Eigen::Vector3d d = ruling(k),
                          n = (ruling(k + 1) - ruling(k).dot(ruling(k + 1)) * ruling(k))
                                  .normalized();
    return rho * (std::cos(t) * d + std::sin(t) * n);
  }
  Eigen::Vector2d toUnrolled(const Eigen::Vector3d& q) const {
    const double rho = q.norm();
    const double phi = std::atan2(q.y(), q.x()) + 0.5 * angle;
    const int k = std::clamp(static_cast<int>(phi / (angle / segments)), 0, segments - 1);
    const Eigen::Vector3d d = ruling(k),
                          n = (ruling(k + 1) - ruling(k).dot(ruling(k + 1)) * ruling(k))
                                  .normalized();
    const double psi = k * cellAngle() + std::atan2(q.dot(n), q.dot(d));
    return rho * Eigen::Vector2d(std::cos(psi), std::sin(psi));
  }
};

}  // namespace egg::testing
