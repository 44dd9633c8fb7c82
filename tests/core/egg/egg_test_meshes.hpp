#pragma once
// Exactly developable test meshes: a cylinder strip triangulated along its rulings (every cell is
// a planar rectangle, so the polyhedral surface unrolls isometrically onto the plane).
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace egg::testing {

struct RuledCylinder {
  double radius = 3.0;
  double angle = 2.0;     // angular span (radians)
  double length = 6.0;    // along the axis x
  int segments = 40;      // around
  int rows = 30;          // along the axis
  double chord() const { return 2 * radius * std::sin(0.5 * angle / segments); }
  double unrolledWidth() const { return segments * chord(); }

  Eigen::Vector3d ring(int k, double x) const {
    const double phi = -0.5 * angle + angle * k / segments;
    return {x, radius * std::sin(phi), radius * std::cos(phi)};
  }
  TriMesh mesh() const {
    TriangleSoup soup;
    for (int j = 0; j <= rows; ++j)
      for (int k = 0; k <= segments; ++k) soup.vertices.push_back(ring(k, -0.5 * length + length * j / rows));
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

}  // namespace egg::testing
