#pragma once
// Exact geodesic distances on a triangle mesh (the polyhedral metric), from a vertex or from any
// surface point, to every vertex and to any list of surface points.
//
// Every later stage rests on these numbers: distance maps between opposite patch boundaries
// (Sections 2.4.2, 3.3.2), the eta check whose threshold is a 0.15 % length difference (2.3.3,
// 3.4.1), member intersections by summed distance fields (4.5.2) and non-convex boundaries (4.5.3).
// Approximate methods (edge Dijkstra, fast marching, heat method) are off by 1-17 % and cannot
// serve a 0.15 % test, so the engine is a window propagation, exact or within ~1e-5 (see
// window_propagation.cpp for the algorithm, distance_solver.cpp for why it was chosen).
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
  // shortest path may bend around it, so it becomes a pseudo-source. Reflex boundary vertices
  // (angle sum > pi) always are. 0, with imageMergeTolerance 0 (exact()), gives the exact
  // polyhedral distance. A near-flat saddle below the tolerance emits no windows; the points in
  // the shadow wedge behind it get their distance by bending at the saddle (pathBentAt,
  // window_geometry.hpp): exact for one bend, off by a second-order amount where other skipped
  // saddles lie in the same shadow. A saddle is never skipped where its shadow could grow wider
  // than a quarter of its shortest edge within twice the bounding-box diagonal (mesh_tables.cpp).
  // Why: near-flat saddles are most vertices of a remeshed negatively curved surface and most of
  // an exact field's time, and skipping them stays well inside the 1e-4 bar of the eta check
  // (Sections 2.3.3, 3.4.1). Error study and timings: docs/measurements.md.
  double saddleAngleTolerance = 7e-4;
  // Windows narrower than this fraction of their edge length are dropped (numerical slivers that
  // appear when a ray runs exactly through a vertex; the neighbouring windows cover them).
  double minWindowWidthRelative = 1e-11;
  // Full fields of the wavefront engine only (not directed queries, whose distance() must agree
  // with path(), nor the other engines): a new window and a queued one on the same edge whose
  // distance functions differ by at most this fraction of the edge length over the narrower one's
  // interval (distanceGapBound, a bound) and whose rays lie within sqrt(2 x tolerance) of each
  // other (absorbNearImage) become one window under the wider one's image. Relative error: of the
  // order of the tolerance, whatever the mesh size (an estimate, not a proof). 0: off.
  // Why: on a convex surface the windows per edge otherwise grow with the distance (every vertex
  // the front passes splits it into two images that never join). Error study:
  // docs/measurements.md.
  double imageMergeTolerance = 2e-6;
  // Worker threads of the batch call; 0 = TBB's default (all cores). Results do not depend on it.
  int threads = 0;
  // How distance fields are propagated (window_propagation.cpp). StoredWindows keeps every window
  // (memory O(windows)) and trims each new one against all earlier ones on its edge. FrontOnly
  // keeps only the queued windows (memory O(front), as VTP, Qin et al. 2016): a window's slot is
  // freed once it has crossed its face. Wavefront (wavefront_engine.cpp, after VTP; the default):
  // the front engine's windows queued per halfedge in first-in-first-out lists, one queue entry per
  // halfedge, a halfedge's windows propagated as one batch and trimmed against the first two of
  // their edge's list only; full fields also merge near images (imageMergeTolerance). Exact mode:
  // all three give the same distances to 1e-9; default mode: the wavefront engine's differ by up
  // to 3e-7, with the same error against the exact mode (test_window_propagation.cpp,
  // test_wavefront_engine.cpp). path() keeps the windows it traces back through whatever the
  // engine. Why Wavefront: the fastest of the three on every bench row, with O(front) memory
  // (docs/measurements.md, including the comparison with the authors' VTP).
  enum class Engine { StoredWindows, FrontOnly, Wavefront };
  Engine engine = Engine::Wavefront;

  void validate() const;  // throws InvalidInput naming the field
  // The exact polyhedral distance (to rounding): every saddle a pseudo-source, no near images
  // merged; the other fields at their defaults.
  static DistanceSolverOptions exact();
};

// A point on the surface given as a vertex (barycentric weight 1 at that vertex of one of its
// faces).
SurfacePoint vertexPoint(const TriMesh& mesh, int vertex);

// The surface point closest (Euclidean) to `point`: the source and target points of the CLI and of
// scene files are 3D points that need not lie exactly on the mesh. Throws InvalidInput on an
// empty mesh.
SurfacePoint snapToSurface(const TriMesh& mesh, const Eigen::Vector3d& point);

// One single-source field.
struct DistanceField {
  std::vector<double> vertexDistances;  // per vertex (OpenMesh index), metres; +inf if unreachable
  std::vector<double>
      targetDistances;      // per requested target point, same order; +inf if unreachable
  long windowsCreated = 0;  // diagnostics: windows pushed during the propagation
  long peakWindows = 0;     // diagnostics: most windows held at once (all of them when stored)
  double peakBytes = 0.0;   // diagnostics: the propagation's working memory at its peak, counted
  double seconds = 0.0;     // wall time of this field
};

// A shortest geodesic as a polyline on the surface. Interior points lie on edges (where the path
// crosses an edge) or at vertices (where it bends around a saddle or a boundary vertex).
struct GeodesicPath {
  std::vector<SurfacePoint> points;        // from `from` to `to`, both included
  std::vector<Eigen::Vector3d> positions;  // 3D positions of `points`
  double length = 0.0;                     // metres; +inf (and no points) if unreachable
  std::vector<int> bendVertices;  // vertices the path passes through (saddle/reflex boundary)
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
  DistanceField distances(const SurfacePoint& source,
                          const std::vector<SurfacePoint>& targets = {}) const;
  DistanceField distancesFromVertex(int vertex,
                                    const std::vector<SurfacePoint>& targets = {}) const;
  // The same distances to `targets` by one propagation directed at them (goal_bound.hpp): it stops
  // once every target is final, sweeping about the union of the ellipses d(source, p) + |p t| <=
  // d(source, t). targetDistances are the full field's in exact mode; with skipped near-flat
  // saddles (the default) they may be slightly longer, never shorter (goal_bound.hpp;
  // docs/measurements.md); vertexDistances are only upper bounds. For a
  // few targets close together: the farthest one sets how far the propagation runs.
  DistanceField directedDistances(const SurfacePoint& source,
                                  const std::vector<SurfacePoint>& targets) const;

  // Many sources at once, in parallel over sources (TBB). Each field is computed by one thread
  // from scratch, so the result is bit-identical for any thread count.
  std::vector<DistanceField> distances(const std::vector<SurfacePoint>& sources,
                                       const std::vector<SurfacePoint>& targets = {}) const;

  // Distance between two surface points: one propagation directed at `to` (A*, goal_bound.hpp),
  // which stops once `to` is final and sweeps only about the ellipse d(from, p) + |p to| <=
  // d(from, to); the value is the full field's (exact mode; see directedDistances otherwise).
  double distance(const SurfacePoint& from, const SurfacePoint& to) const;

  // The shortest geodesic from `from` to `to`, traced back through the windows of a propagation
  // directed at `to` (as distance()). Its
  // length equals distance(from, to) to rounding in exact mode; with skipped near-flat saddles
  // (the default) the path bends at the saddle as the distance does, and where that straight
  // segment would pass another vertex the traced path goes round it, a little longer (tested to
  // within 2e-5 relative; docs/measurements.md).
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
