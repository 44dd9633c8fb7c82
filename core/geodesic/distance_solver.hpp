#pragma once
// Exact geodesic distances on a triangle mesh (the polyhedral metric), from a vertex or from any
// surface point, to every vertex and to any list of surface points.
//
// Every later stage rests on these numbers: distance maps between opposite patch boundaries
// (Sections 2.4.2, 3.3.2), the eta check whose threshold is a 0.15 % length difference (2.3.3,
// 3.4.1), member intersections by summed distance fields (4.5.2) and non-convex boundaries (4.5.3).
// Approximate methods (edge Dijkstra, fast marching, heat method) are off by 1-17 % and cannot
// serve a 0.15 % test, so the engine is an exact window propagation (see distance_solver.cpp for
// the algorithm and why it was chosen).
//
// Usage:
//   egg::geodesic::DistanceSolver solver(mesh);                 // precomputes per-mesh tables
//   auto field = solver.distances(source, targets);             // one source
//   field.vertexDistances[v], field.targetDistances[i]          // metres, +inf if unreachable
//   auto fields = solver.distances(sources, targets);           // many sources, parallel (TBB)
//   auto path = solver.path(from, to);                          // polyline of surface points
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <memory>
#include <vector>

namespace egg::geodesic {

namespace detail {
struct MeshTables;  // flat connectivity + unfolded triangle frames (distance_solver.cpp)
}

struct DistanceSolverOptions {
  // An interior vertex whose angle sum exceeds 2*pi by more than this (radians) is a saddle: a
  // shortest path may bend around it, so it becomes a pseudo-source; likewise a boundary vertex
  // whose angle sum exceeds pi (a reflex corner of the boundary).
  // Below it the vertex's shadow is closed by paths bent over the neighbouring windows' ends
  // instead. One skipped bend of angle e costs little, but along a path through a negatively
  // curved region every vertex is a near-flat saddle, the skipped bends add up, and the error grows
  // with the number of vertices the path passes (finer meshes skip more). Error study (2026-12,
  // max relative error against tolerance 0, the exact polyhedral distance):
  //   tolerance   patch side-to-side maps, steep bump       samples, interior sources
  //               3.9k vertices     14.9k vertices          (bump/hypar/waves 1k-18k)
  //   7e-4        1.7e-4 - 2.2e-4   -                       2.4e-6
  //   5e-4        3.4e-5 - 1.5e-4   -                       1.8e-6
  //   2e-4        8.9e-6 - 1.7e-5   9.9e-5                  -
  //   1e-4        8.9e-6            3.0e-5                  -
  // (maps: bump height 2 m, sigma 1.5 m, 8 x 8 m, 6 x 6 m patch over the top, every row exact;
  // the test PatchMapsAccuracy.* in tests/core/egg repeats the 3.9k case.) The default keeps the
  // 1e-4 bar of Sections 2.3.3/3.4.1 with a margin of 3 at 15k vertices; meshes much finer than
  // that should lower it or use 0. Reflex boundary vertices are always pseudo-sources.
  double saddleAngleTolerance = 1e-4;
  // Windows narrower than this fraction of their edge length are dropped (numerical slivers that
  // appear when a ray runs exactly through a vertex; the neighbouring windows cover them).
  double minWindowWidthRelative = 1e-11;
  // Worker threads of the batch call; 0 = TBB's default (all cores). Results do not depend on it.
  int threads = 0;

  void validate() const;  // throws InvalidInput naming the field
};

// A point on the surface given as a vertex (barycentric weight 1 at that vertex of one of its faces).
SurfacePoint vertexPoint(const TriMesh& mesh, int vertex);

// The surface point closest (Euclidean) to `point`: the source and target points of the CLI and of
// scene files are 3D points that need not lie exactly on the mesh. Throws InvalidInput on an
// empty mesh.
SurfacePoint snapToSurface(const TriMesh& mesh, const Eigen::Vector3d& point);

// One single-source field.
struct DistanceField {
  std::vector<double> vertexDistances;  // per vertex (OpenMesh index), metres; +inf if unreachable
  std::vector<double> targetDistances;  // per requested target point, same order; +inf if unreachable
  long windowsCreated = 0;              // diagnostics: windows pushed during the propagation
  double seconds = 0.0;                 // wall time of this field
};

// A shortest geodesic as a polyline on the surface. Interior points lie on edges (where the path
// crosses an edge) or at vertices (where it bends around a saddle or a boundary vertex).
struct GeodesicPath {
  std::vector<SurfacePoint> points;          // from `from` to `to`, both included
  std::vector<Eigen::Vector3d> positions;    // 3D positions of `points`
  double length = 0.0;                       // metres; +inf (and no points) if unreachable
  std::vector<int> bendVertices;             // vertices the path passes through (saddle/reflex boundary)
};

class DistanceSolver {
 public:
  // Builds the per-mesh tables (halfedge arrays, edge lengths, unfolded triangle frames, vertex
  // angle sums, pseudo-source flags). The mesh is copied into the tables; it need not outlive the
  // solver. Throws InvalidInput for an empty mesh, a degenerate (zero-area) face or bad options.
  explicit DistanceSolver(const TriMesh& mesh, const DistanceSolverOptions& options = {});
  ~DistanceSolver();
  DistanceSolver(DistanceSolver&&) noexcept;
  DistanceSolver& operator=(DistanceSolver&&) noexcept;

  // Exact distances from `source` (a vertex, a point on an edge or inside a face) to all vertices
  // and to `targets` (any surface points: on the boundary, inside faces, at vertices).
  DistanceField distances(const SurfacePoint& source, const std::vector<SurfacePoint>& targets = {}) const;
  DistanceField distancesFromVertex(int vertex, const std::vector<SurfacePoint>& targets = {}) const;

  // Many sources at once, in parallel over sources (TBB). Each field is computed by one thread
  // from scratch, so the result is bit-identical for any thread count.
  std::vector<DistanceField> distances(const std::vector<SurfacePoint>& sources,
                                       const std::vector<SurfacePoint>& targets = {}) const;

  // Distance between two surface points (one propagation).
  double distance(const SurfacePoint& from, const SurfacePoint& to) const;

  // The shortest geodesic from `from` to `to`, traced back through the propagation's windows
  // (exact up to rounding; length equals distance(from, to)).
  GeodesicPath path(const SurfacePoint& from, const SurfacePoint& to) const;

  int vertexCount() const;
  int faceCount() const;
  double meanEdgeLength() const;
  // True if `vertex` is a saddle or a reflex boundary vertex (a shortest path may pass through it).
  bool isPseudoSource(int vertex) const;
  double precomputeSeconds() const;
  const DistanceSolverOptions& options() const;

 private:
  std::unique_ptr<detail::MeshTables> tables_;
  DistanceSolverOptions options_;
  double precomputeSeconds_ = 0.0;
};

// One-off convenience: builds a solver and computes one field.
DistanceField geodesicDistances(const TriMesh& mesh, const SurfacePoint& source,
                                const std::vector<SurfacePoint>& targets = {},
                                const DistanceSolverOptions& options = {});

}  // namespace egg::geodesic
