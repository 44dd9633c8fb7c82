// Meshing pipeline shared by every sample (docs/architecture.md "Samples": generated at a requested
// edge length). Delaunay refinement gives a valid domain triangulation with 3D edges below a bound;
// remeshing then makes the triangles near-equilateral on the surface.
#include "samples/generators/surface_mesher.hpp"

#include "samples/generators/boundary_sampling.hpp"
#include "samples/generators/domain_triangulation.hpp"
#include "samples/generators/remeshing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace egg::samples::detail {
namespace {

std::vector<std::vector<Vec2>> polygonsOf(const std::vector<SampledLoop>& loops) {
  std::vector<std::vector<Vec2>> polygons;
  for (const SampledLoop& loop : loops) {
    std::vector<Vec2> polygon;
    for (const BoundarySample& sample : loop.points) polygon.push_back(sample.domain);
    polygons.push_back(std::move(polygon));
  }
  return polygons;
}

double domainDiameter(const std::vector<SampledLoop>& loops) {
  Eigen::AlignedBox2d box;
  for (const SampledLoop& loop : loops) {
    for (const BoundarySample& sample : loop.points) box.extend(sample.domain);
  }
  return box.diagonal().norm();
}

// Vertices on the triangulation's boundary (edges used by one triangle only).
std::vector<bool> boundaryVertices(const DomainTriangulation& domain) {
  std::unordered_map<std::uint64_t, int> edgeUse;
  for (const auto& t : domain.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      ++edgeUse[(a << 32) | b];
    }
  }
  std::vector<bool> onBoundary(domain.points.size(), false);
  for (const auto& [key, uses] : edgeUse) {
    if (uses != 1) continue;
    onBoundary[key >> 32] = true;
    onBoundary[key & 0xffffffffu] = true;
  }
  return onBoundary;
}

// Where the boundary is reflex (a hole, or a bay of a non-convex outer loop), the exact curve
// lies on the domain side of its chords, so a snap moves the point into its own triangles: by a
// sagitta far below their height at any sensible edge length, but nothing guarantees it when the
// curve's radius nears the edge length. A triangle the snaps would invert gets its snapped
// points back on the chord (a vertex a sagitta off the curve, still on the surface), so the
// remesher always starts from a valid counter-clockwise triangulation.
void undoInvertingSnaps(const DomainTriangulation& domain, std::vector<bool>& snapped,
                        DomainMesh& input) {
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& t : domain.triangles) {
      const Vec2 a = input.domain[t[1]] - input.domain[t[0]],
                 b = input.domain[t[2]] - input.domain[t[0]];
      if (a.x() * b.y() - a.y() * b.x() > 0) continue;
      for (int k : t) {
        if (!snapped[k]) continue;
        input.domain[k] = domain.points[k];
        snapped[k] = false;
        changed = true;
      }
    }
  }
}

}  // namespace

double boundaryLength(const SurfaceSpec& spec) {
  double perimeter = 0.0;
  for (const BoundaryLoop& loop : spec.boundary) {
    for (const DomainCurve& curve : loop) perimeter += curveLength3d(spec, curve, 256);
  }
  return perimeter;
}

double estimateArea(const SurfaceSpec& spec) {
  // Midpoint rule on a grid over the domain's bounding box, inside by polygon parity: no
  // triangulation, so even a sliver of a domain costs the same few milliseconds.
  const auto loops = sampleBoundary(spec, boundaryLength(spec) / 512.0);
  const auto polygons = polygonsOf(loops);
  Eigen::AlignedBox2d box;
  for (const auto& polygon : polygons) {
    for (const Vec2& p : polygon) box.extend(p);
  }
  constexpr int kCells = 256;
  const Vec2 cell = box.sizes() / kCells;
  const double step = 1e-4 * cell.minCoeff();
  double area = 0.0;
  std::vector<double> crossings;
  for (int j = 0; j < kCells; ++j) {
    // Scanline: the row's crossings with every polygon edge, paired, are the inside intervals.
    const double y = box.min().y() + (j + 0.5) * cell.y();
    crossings.clear();
    for (const auto& polygon : polygons) {
      for (size_t a = 0, b = polygon.size() - 1; a < polygon.size(); b = a++) {
        const Vec2& p = polygon[a];
        const Vec2& q = polygon[b];
        if ((p.y() > y) != (q.y() > y))
          crossings.push_back(p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      const int first =
          std::max(0, int(std::ceil((crossings[k] - box.min().x()) / cell.x() - 0.5)));
      const int last = std::min(
          kCells - 1, int(std::floor((crossings[k + 1] - box.min().x()) / cell.x() - 0.5)));
      for (int i = first; i <= last; ++i) {
        const Vec2 u(box.min().x() + (i + 0.5) * cell.x(), y);
        const Vec3 du =
            (spec.position(u + Vec2(step, 0)) - spec.position(u - Vec2(step, 0))) / (2 * step);
        const Vec3 dv =
            (spec.position(u + Vec2(0, step)) - spec.position(u - Vec2(0, step))) / (2 * step);
        area += du.cross(dv).norm() * cell.x() * cell.y();
      }
    }
  }
  return area;
}

TriangleSoup meshSurface(const SurfaceSpec& spec, double edgeLength, double expectedTriangles) {
  const auto loops = sampleBoundary(spec, edgeLength);  // boundary edges = request
  std::size_t boundaryPoints = 0;
  for (const auto& loop : loops) boundaryPoints += loop.points.size();
  // Refinement at 1.2 h makes fewer vertices than the final mesh (about half the triangles);
  // ten times that means the angle bound is fighting a domain thinner than the edge length.
  const auto maxVertices = std::size_t(10.0 * expectedTriangles) + 10 * boundaryPoints + 10'000;
  // Refinement bound a little above the target: the remesher splits what is longer than 4/3 of
  // it anyway, and a looser bound leaves fewer tiny edges to collapse.
  const DomainTriangulation domain = triangulateDomain(
      polygonsOf(loops), spec.requiredPoints, spec.position, 1.2 * edgeLength, 0.125, maxVertices);

  DomainMesh input;
  input.domain = domain.points;
  input.triangles = domain.triangles;
  input.locked.resize(domain.points.size());
  // Refinement splits encroached boundary chords at their domain midpoints; put those points back
  // on the exact boundary curve (a sagitta of ~h^2/8R, far below any triangle's size).
  const double tolerance = 1e-9 * domainDiameter(loops);
  const std::vector<bool> onTriangulationBoundary = boundaryVertices(domain);
  std::vector<bool> snapped(domain.points.size(), false);
  for (size_t i = 0; i < domain.points.size(); ++i) {
    input.locked[i] = domain.inputIndex[i] >= 0;
    if (input.locked[i] || !onTriangulationBoundary[i]) continue;
    bool onBoundary = false;
    const Vec2 point = snapToBoundary(spec, loops, domain.points[i], tolerance, onBoundary);
    if (onBoundary) input.domain[i] = point;
    snapped[i] = onBoundary;
  }
  undoInvertingSnaps(domain, snapped, input);
  RemeshOptions options;
  // Remeshing with the 4/5 .. 4/3 band settles at a mean edge of about 0.93 of its target (measured
  // on every sample); aim a little long so the mean edge matches the request.
  options.targetEdge = 1.07 * edgeLength;
  return remeshInDomain(spec, input, options);
}

}  // namespace egg::samples::detail
