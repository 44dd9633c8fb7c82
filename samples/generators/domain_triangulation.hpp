#pragma once
// Delaunay refinement of a planar parameter domain (CGAL's 2D constrained Delaunay mesher), with
// triangle size measured in 3D through the surface map. CGAL stays inside the .cpp.
#include "samples/generators/surface_spec.hpp"

#include <array>
#include <functional>
#include <vector>

namespace egg::samples::detail {

struct DomainTriangulation {
  std::vector<Vec2> points;
  // Index of the input point each output point came from (polygon points in order, then the
  // required points), or -1 for a point the refinement inserted.
  std::vector<int> inputIndex;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in the domain
};

// Triangulates the region bounded by `polygons` (closed, no repeated first point; the region is
// decided by nesting parity, so holes need no orientation), keeps every polygon edge, inserts
// `requiredPoints`, and refines until each triangle's longest 3D edge (through `lift`) is at most
// `maxEdge3d` and its smallest domain angle is at least about 20.7 degrees (CGAL's B = 0.125).
DomainTriangulation triangulateDomain(const std::vector<std::vector<Vec2>>& polygons,
                                      const std::vector<Vec2>& requiredPoints,
                                      const std::function<Vec3(const Vec2&)>& lift, double maxEdge3d);

}  // namespace egg::samples::detail
