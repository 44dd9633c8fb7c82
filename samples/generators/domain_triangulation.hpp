#pragma once
// Delaunay refinement of a planar parameter domain (CGAL's 2D constrained Delaunay mesher), with
// triangle size measured in 3D through the surface map. CGAL stays inside the .cpp.
#include "samples/generators/surface_spec.hpp"

#include <array>
#include <cstddef>
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
// `maxEdge3d` and the squared sine of its smallest domain angle is at least `aspectBound` (CGAL's
// B; 0.125 is about 20.7 degrees, 0 refines by size only). Throws InvalidInput when the refinement
// needs more than `maxVertices` vertices (a domain far thinner than the edge length).
DomainTriangulation triangulateDomain(const std::vector<std::vector<Vec2>>& polygons,
                                      const std::vector<Vec2>& requiredPoints,
                                      const std::function<Vec3(const Vec2&)>& lift,
                                      double maxEdge3d, double aspectBound = 0.125,
                                      std::size_t maxVertices = 20'000'000);

}  // namespace egg::samples::detail
