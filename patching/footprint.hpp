#pragma once
// The plan view Workflow 2 lays its patches out in (Section 3.4.3): the surface seen along its
// least-variance direction, its boundary loops as polygons, arcs of the outer boundary, and the
// way back from a plan point to the surface. Only workflow2.cpp uses this.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <array>
#include <optional>
#include <utility>
#include <vector>

namespace egg::patching {

using Vec2 = Eigen::Vector2d;
using Polygon = std::vector<Vec2>;

// Projection onto the plane through `origin` spanned by e1, e2 (normal = e1 x e2).
struct Plan {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::UnitX(),
                  e2 = Eigen::Vector3d::UnitY(), normal = Eigen::Vector3d::UnitZ();
  Vec2 operator()(const Eigen::Vector3d& p) const {
    return {(p - origin).dot(e1), (p - origin).dot(e2)};
  }
  double height(const Eigen::Vector3d& p) const { return (p - origin).dot(normal); }
};

// The least-variance direction as the normal; a roof given z up keeps the model's x and y.
Plan planOf(const TriMesh& mesh);

double signedArea(const Polygon& polygon);  // counter-clockwise positive
bool insidePolygon(const Polygon& polygon, const Vec2& q);
double distanceToPolygon(const Polygon& polygon, const Vec2& q);  // to its closed outline
std::vector<char> convexHullMarks(const Polygon& polygon);  // 1 for the vertices on the convex hull

struct Footprint {
  Polygon outer;                         // the longest loop by area, counter-clockwise
  std::vector<Eigen::Vector3d> outer3d;  // the same boundary vertices in space
  std::vector<Polygon> holes;
  double tolerance = 0.0;  // "on the boundary": half a mean edge length
  bool contains(const Vec2& q) const;
  bool containsSegment(const Vec2& a, const Vec2& b) const;  // sampled, off the holes too
};

// Throws InvalidInput when the surface has no boundary.
Footprint footprintOf(const TriMesh& mesh, const Plan& plan);

// A piece of the outer boundary between two of its vertices, counter-clockwise, by arc length u in
// [0, 1].
struct Arc {
  std::vector<Vec2> points;
  std::vector<Eigen::Vector3d> points3d;
  std::vector<double> s;
  Vec2 at(double u) const;
  Eigen::Vector3d at3d(double u) const;  // on the mesh's own boundary

 private:
  std::pair<size_t, double> locate(double u) const;
};
Arc arcOf(const Footprint& foot, size_t from, size_t to);

inline Vec2 lerp(const Vec2& a, const Vec2& b, double t) { return (1.0 - t) * a + t * b; }

// From plan points back to the surface: the faces binned by their plan boxes.
class PlanLifter {
 public:
  PlanLifter(const TriMesh& surface, const Plan& plan);
  // The surface point over q: with `near`, the one closest to it (a corner pulled in from the
  // boundary stays on its sheet, not up an overhanging wall); otherwise the highest (the roof seen
  // from above). Off the surface: the nearest point of the nearest face in plan. `sheets` counts
  // the faces over q (more than one: the plan sees the surface twice there).
  Eigen::Vector3d lift(const Vec2& q, const std::optional<Eigen::Vector3d>& near = std::nullopt,
                       int* sheets = nullptr) const;

 private:
  Plan plan_;
  std::vector<std::array<Eigen::Vector3d, 3>> faces_;
  std::vector<std::array<Vec2, 3>> planFaces_;
  Vec2 lo_, cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> bins_;
  std::optional<Eigen::Vector3d> liftInBins(const Vec2& q,
                                            const std::optional<Eigen::Vector3d>& near,
                                            int* sheets) const;
};

}  // namespace egg::patching
