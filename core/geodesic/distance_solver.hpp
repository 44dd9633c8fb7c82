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
  // polyhedral distance.
  // A saddle below the tolerance (a near-flat one: on a remeshed negatively curved surface almost
  // every vertex is) emits no windows. Behind it lies a shadow wedge as wide as its excess that no
  // window enters; the points in it get their distance by bending at the saddle from the windows
  // that border the wedge (pathBentAt in window_geometry.hpp): exact for one bend, while other
  // skipped saddles inside the same shadow make it slightly long or, where the straight segment
  // passes one on its far side, slightly short (second order in the excess; measured from -1.1e-6
  // to +8e-6, the latter on a hypar where an under-estimated pseudo-source shut out a window).
  // Near-flat saddles are ~40 % of the windows and ~60 % of the time of an exact field on the bench
  // bump (4.5k vertices).
  // Error study (2026-12, max relative error against tolerance 0; patch = side-to-side distances
  // of a 6 x 6 m patch over an 8 x 8 m bump with sigma 1.5 m and height h, 9 sources x 100 targets
  // per family, as the distance maps of Section 2.4.2 use them; bench = `egg bench geodesic` bump,
  // side sources to all vertices):
  //   tolerance   patch h = 2 m              patch h = 3 m      bench bump
  //               1k      3.9k    15k        1.1k     4.5k      1k      4.5k    17.7k
  //   7e-4        6.2e-7  1.1e-6  3.3e-7     2.9e-8   4.5e-6    4.1e-7  5.8e-7  2.9e-7
  //   1e-3        1.3e-6  9.3e-6  6.4e-5     1.0e-6   3.8e-5    1.5e-6  8.2e-7  4.8e-7
  //   2e-3        5.2e-6  9.3e-6  6.4e-5     1.2e-4   9.6e-5    4.1e-6  1.9e-6  1.1e-6
  // (The 1e-3 and 2e-3 rows were measured before the review fixes of the bend: aiming pseudo-source
  // cones from the bend, and the edge check.)
  // Time per field at 7e-4 against tolerance 0: 0.40 (bench, 4.5k), 0.47 (patch 3.9k), 0.34 (15k).
  // Bending at the window's end instead of at the saddle, as before, gave 1.7e-4 (patch h = 2 m,
  // 3.9k) at 7e-4, and 3e-5 at 15k even at 1e-4; the bar (Sections 2.3.3, 3.4.1) is 1e-4. The
  // default keeps a margin of 20 on every case above; past it the speed barely grows (most
  // near-flat saddles are already skipped) and the error does.
  // A saddle is also never skipped where its shadow could grow wider than a quarter of its
  // shortest edge within twice the mesh's bounding-box diagonal (mesh_tables.cpp).
  double saddleAngleTolerance = 7e-4;
  // Windows narrower than this fraction of their edge length are dropped (numerical slivers that
  // appear when a ray runs exactly through a vertex; the neighbouring windows cover them).
  double minWindowWidthRelative = 1e-11;
  // Full fields of the wavefront engine (not directed queries, whose distance() must agree with
  // path(), nor the other engines): a new window and a queued one on the same edge whose distance
  // functions differ by at most this fraction of the edge length over the narrower one's interval
  // become one window under the wider one's image (distanceGapBound, window_geometry.hpp: a bound,
  // not an estimate). On a convex surface every vertex the front passes splits it into two images
  // a vertex's angle defect apart, and their pieces never join again (as on a plane before exact
  // merging, but here the images differ): the windows per edge grow with the distance. A merge
  // moves the distance over the narrower piece by at most tolerance x edge length; a path
  // crosses about distance / edge length edges, so even with a change at every one the error
  // would stay of the order of the tolerance relative to the distance, whatever the mesh size (an
  // estimate, not a proof; measured: a tenth of the tolerance, on 4.6k to 418k triangles).
  // A merged pair must also have rays within sqrt(2 x tolerance) of each other (absorbNearImage:
  // why; without it a pseudo-source's wide fan went to a far image's sliver).
  // Error study (2026-12; max relative error against exact() at the vertices; windows per field;
  // issue 19's meshes and vertex sources, `egg geodesic --merge-tolerance T` against `--exact`;
  // the rows at 0 are the saddle skipping's alone):
  //   tolerance   cap 4.6k          cap 18k           bump 4.4k         bump 418k triangles
  //   0           0       132.5k    0       1062k     5.9e-8  121.7k    1.2e-10 39.0M
  //   1e-6        2.3e-8  125.3k    4.4e-8  752k      5.9e-8  117.7k    5.1e-8  26.8M
  //   2e-6        5.8e-8  119.6k    1.2e-7  609k      6.6e-8  115.6k    2.1e-7  26.6M
  //   5e-6        2.9e-7  104.8k    6.7e-7  407k      2.6e-7  110.0k    4.9e-7  26.6M
  //   1e-5        4.9e-7  88.5k     1.2e-6  293k      5.0e-7  105.1k
  // Time at the default against 0 (interleaved pinned runs; instructions by callgrind): 18k cap
  // 0.81 (instructions 0.64), 418k-triangle bump 0.58-0.77, 4.6k cap and 4.4k bump within the
  // noise (instructions 0.98). The default keeps the error within 1e-6 of the exact distance with
  // a margin of 5 on these, well below the saddle skipping's own (up to 8e-6, above). 0: off.
  double imageMergeTolerance = 2e-6;
  // Worker threads of the batch call; 0 = TBB's default (all cores). Results do not depend on it.
  int threads = 0;
  // How distance fields are propagated (window_propagation.cpp). StoredWindows keeps every window
  // (memory O(windows)) and trims each new one against all earlier ones on its edge. FrontOnly
  // keeps only the queued windows (memory O(front), as VTP, Qin et al. 2016): a window's slot is
  // freed once it has crossed its face, and a new window is trimmed against the queued windows of
  // its edge, and they against it. Same distances to rounding (tests/core/geodesic/
  // test_window_propagation.cpp). Time per field, front / stored (2026-12, `egg bench geodesic
  // --engine-rows large`, thread CPU; and `egg geodesic --engine`): 1.05-1.10 on the 4.5k bump and
  // cap, 0.84-1.02 on the 18k cap, 0.88-0.97 on the 17k plane, 0.55-1.02 on the 418k-triangle bump,
  // whose process peak RSS drops from 5.0 GB to 0.27 GB (working memory 3.6 GB -> 53 MB).
  // Wavefront (wavefront_engine.cpp, after VTP): the front engine's windows queued per halfedge
  // (first-in-first-out lists, one queue entry per halfedge, a halfedge's windows propagated as one
  // batch) and trimmed against the first two of their edge's list only: a few % more windows, each
  // cheaper. Exact mode: the stored engine's distances to 1e-9; default mode: differences up to
  // 3e-7 where bends at skipped saddles see other window ends, with the same error against the
  // exact mode (tests: test_window_propagation.cpp, test_wavefront_engine.cpp). Time per field
  // against stored / front, one interleaved run, 5 vertex sources (2026-12, thread CPU, `egg bench
  // geodesic --engine-rows large`): 4.4k bump 0.69 / 0.64, 4.6k cap 0.57 / 0.55, 18k cap 0.46 /
  // 0.46, 17k plane 0.06 / 0.93, 418k-triangle bump (1 source) 0.29 / 0.31 (14.9 s; 0.22 / 0.31 in
  // a second run; peak RSS of a wavefront-only process 0.39 GB). Prefetching each halfedge's first
  // queued window a bucket ahead of its pop, and the next window of a list while one crosses
  // (wavefront_engine.cpp), cut the 418k-triangle field to 0.65-0.75 of that (`egg geodesic` on the
  // exported mesh, interleaved, 8.4-9.6 s against 12.5-12.9 s; `egg bench geodesic --engine-rows
  // large`: 8.7 s, 0.13 of the stored engine's 65 s in the same run; peak RSS of a wavefront-only
  // process 0.28 GB); up to 18k vertices, whose fronts stay in cache, the change is within the
  // noise (+-20 %, three interleaved bench runs). Full fields pop a bucket's halfedges in any
  // order, in buckets one edge wide, with vertex events held back until their bucket is clear
  // (wavefront_engine.cpp, runSplitQueues): 418k-triangle bump 3.3 s against 8.0 s, 18k cap
  // 0.88, 4.4k bump 0.78 of the time before (interleaved `egg geodesic` runs; numbers of this and
  // the authors' VTP on the same meshes: issue 19's note). Full fields also merge near images
  // (imageMergeTolerance). A batch's crossing, pruning and insertion compile into one function
  // (face_crossing.hpp), and the records of the next two batches are prefetched while one runs
  // (wavefront_engine.cpp, prefetchNextBatches): warm fields, interleaved with the authors' VTP
  // (medians of 5 x 11, bit-identical distances), 18k cap 0.52 -> 0.49 of VTP's time, 4.6k cap
  // 0.73 -> 0.70, 4.4k bump 0.35 -> 0.32, 17k plane 0.06 -> 0.05 (issue 19's note). The default:
  // faster than both on every row. path() keeps the windows it traces back through whatever the
  // engine.
  enum class Engine { StoredWindows, FrontOnly, Wavefront };
  Engine engine = Engine::Wavefront;

  void validate() const;  // throws InvalidInput naming the field
  // The exact polyhedral distance (to rounding): every saddle a pseudo-source, no near images
  // merged; the other fields at their defaults.
  static DistanceSolverOptions exact();
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
  long peakWindows = 0;                 // diagnostics: most windows held at once (all of them when stored)
  double peakBytes = 0.0;               // diagnostics: the propagation's working memory at its peak, counted
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
  // The same distances to `targets` by one propagation directed at them (goal_bound.hpp): it stops
  // once every target is final, sweeping about the union of the ellipses d(source, p) + |p t| <=
  // d(source, t). targetDistances are the full field's in exact mode; with skipped near-flat
  // saddles (the default) they may be slightly longer (measured up to 8e-7 relative at 7e-4, never
  // shorter, goal_bound.hpp); vertexDistances are only upper bounds. For a
  // few targets close together: the farthest one sets how far the propagation runs.
  DistanceField directedDistances(const SurfacePoint& source, const std::vector<SurfacePoint>& targets) const;

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
  // segment would pass another vertex the traced path goes round it, a little longer (reviewed on
  // bump, hypar and waves samples with vertex, edge and face targets: up to 7e-6; tested: 2e-5).
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
