#pragma once
// Internal description of a sample surface: an exact analytic map from a planar parameter domain to
// R^3. Height fields use the footprint itself as the domain (x, y) -> (x, y, z(x, y)); developable
// and revolved surfaces use an unrolled or polar domain. Meshing happens in the domain, measured in
// 3D, so every vertex is an exact evaluation of the map (the analytic oracles of
// docs/architecture.md "Validation references" hold to rounding).
#include <Eigen/Dense>

#include <functional>
#include <string>
#include <vector>

namespace egg::samples::detail {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// A piece of domain boundary, s in [0, 1]. Its ends become mesh vertices, so corners of the
// footprint are kept exactly.
struct DomainCurve {
  std::function<Vec2(double)> at;
};

// A closed boundary loop: curves joined end to start, the last one ending where the first starts.
// A single closed curve (at(0) == at(1)) is a loop on its own.
using BoundaryLoop = std::vector<DomainCurve>;

struct SurfaceSpec {
  std::string name;
  // Exact map from the parameter domain to R^3.
  std::function<Vec3(const Vec2&)> position;
  // Outer boundary and holes (nesting decides which side is inside; orientation is free). Loops
  // may be non-convex (a bay in the outer loop, as for Chapter 4's Moon): meshing works on the
  // polygon of boundary samples, and every interior vertex, edge midpoint and move stays inside
  // that polygon (the remesher keeps triangles counter-clockwise). Where the boundary is convex the
  // polygon lies inside the true domain; where it is reflex (any hole, a bay) the polygon's chords
  // overhang the true domain by their sagitta (~h^2 / 8R), so such a spec sets inDomain. There a
  // refinement point snapped back onto the curve moves into its own triangles; the mesher undoes
  // a snap that would invert one (surface_mesher.cpp).
  std::vector<BoundaryLoop> boundary;
  // Optional exact domain test (the polygonal boundary cuts chords across reflex stretches: curved
  // holes, bays): midpoints and moves that would leave the true domain are refused. Empty = the
  // polygon is the domain.
  std::function<bool(const Vec2&)> inDomain;
  // Interior domain points that must become (fixed) mesh vertices: spot heights, a tip.
  std::vector<Vec2> requiredPoints;
  // True when a counter-clockwise domain triangle maps to a downward / inward normal.
  bool reverseOrientation = false;
};

}  // namespace egg::samples::detail
