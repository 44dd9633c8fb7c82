#pragma once
// Internal: the flat mesh tables and the exact window propagation behind DistanceSolver.
// Not part of the public API (include distance_solver.hpp instead).
#include "core/geodesic/bucket_queue.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <array>
#include <limits>
#include <vector>

namespace egg::geodesic::detail {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Halfedge arrays copied out of OpenMesh (twin(h) = h ^ 1 as in OpenMesh), plus for every halfedge
// with a face the "unfolded frame" of that face: from-vertex at (0,0), to-vertex at (length,0), the
// opposite vertex at (oppositeX, oppositeY) with oppositeY > 0. All propagation runs in these 2D
// frames, so no 3D arithmetic happens in the inner loop.
struct MeshTables {
  int vertexCount = 0;
  int faceCount = 0;
  int halfedgeCount = 0;
  std::vector<Eigen::Vector3d> positions;
  // Per halfedge, one 48-byte record: the propagation reads most of these fields for every
  // window, and one record is one or two cache lines where separate arrays cost a line each.
  // oppositeVertex/oppositeX/oppositeY are -1/0/0 for a boundary halfedge (no face).
  struct Halfedge {
    double length, oppositeX, oppositeY;
    int fromVertex, toVertex, face, next, prev, oppositeVertex;
  };
  std::vector<Halfedge> he;
  // Per face: its vertices in OpenMesh circulator order (the SurfacePoint barycentric order) and
  // faceHalfedge[f][i] = the halfedge of f leaving faceVerts[f][i].
  std::vector<std::array<int, 3>> faceVerts;
  std::vector<std::array<int, 3>> faceHalfedge;
  // Outgoing halfedges of each vertex (CSR), boundary halfedges included.
  std::vector<int> outgoingStart, outgoing;
  std::vector<char> pseudoSource;  // saddle or reflex boundary vertex
  std::vector<char> boundaryVertex;
  std::vector<double> angleSum;
  // Per vertex: the widest bend (tan of the angle from the incoming ray) a path may take there to
  // reach the shadow behind it (window_geometry.hpp, pathBentAt). A skipped saddle's shadow is its
  // excess wide, plus at most one more skipped excess (the tolerance) for a skipped saddle inside
  // it. 0 for pseudo-sources (their windows cover their shadows) and convex vertices (none): wider
  // cones let the bent segment cross other vertices and underestimate (measured: up to 3e-5 on a
  // 1k-vertex patch with excess + tolerance at every vertex, 6e-7 with this rule).
  std::vector<double> shadowCone;
  // shadowCone > 0, a byte per vertex: every window that misses its face's opposite vertex asks
  // this of the vertex on its end's ray, and a byte array stays in the first-level cache where the
  // doubles did not.
  std::vector<char> hasShadowCone;
  double meanEdgeLength = 0.0;

  int twin(int h) const { return h ^ 1; }
  // The 3D point with barycentric weights w (faceVerts order) in face f.
  Eigen::Vector3d pointIn(int f, const Eigen::Vector3d& w) const {
    const auto& fv = faceVerts[f];
    return w[0] * positions[fv[0]] + w[1] * positions[fv[1]] + w[2] * positions[fv[2]];
  }
};

MeshTables buildTables(const TriMesh& mesh, const DistanceSolverOptions& options);

// A window: an interval [b0, b1] of the edge of halfedge `halfedge` (measured from its from-vertex)
// through which straight rays from the unfolded source image (sx, sy) (sy < 0, i.e. behind the
// edge) enter face(halfedge). sigma is the geodesic distance from the source to the image (0 for
// the source itself, d(v) for a pseudo-source vertex v).
//
// 56 bytes: ~180k windows of a 4k-vertex field are written once and read back at least once, so
// their size is memory traffic. The origin is therefore packed into one int.
struct Window {
  int halfedge = -1;
  // >= 0: the window this one was propagated from. Otherwise the window was born at the source
  // point (kFromSource) or at pseudo-source vertex v (fromVertex(v)).
  int parent = kFromSource;
  double b0 = 0.0, b1 = 0.0;
  double sx = 0.0, sy = 0.0;
  double sigma = 0.0;
  // Per end (0: b0, 1: b1): the vertex its boundary ray passes through, -1 if the end was cut
  // anywhere else (trimming, pruning, a pseudo-source cone). A point just outside the window on
  // that side is reached by bending at the vertex, not at the end (see Propagator::bentDistance).
  int endVertex[2] = {-1, -1};

  static constexpr int kFromSource = -1;
  static int fromVertex(int v) { return -2 - v; }
  bool isRoot() const { return parent < 0; }
  // For a root window: the pseudo-source vertex its rays come from, or -1 for the source point.
  int rootVertex() const { return parent <= -2 ? -2 - parent : -1; }
};
static_assert(sizeof(Window) == 56);

// How the best value at a vertex or target was obtained (for backtracing paths).
// BentAtVertex: through window `index`, whose end `side` the path passed to bend at the vertex on
// that end's boundary ray (pathBentAt in window_geometry.hpp).
struct Predecessor {
  enum Kind : char { None, Source, Vertex, ThroughWindow, BentAtVertex };
  Kind kind = None;
  int index = -1;  // vertex or window index
  char side = 0;   // BentAtVertex: which end of the window

  static Predecessor throughWindow(int window, int side, bool bentAtVertex) {
    return bentAtVertex ? Predecessor{BentAtVertex, window, static_cast<char>(side)}
                        : Predecessor{ThroughWindow, window};
  }
};

// Per-thread scratch space and the result of one propagation.
struct Propagation {
  std::vector<double> vertexDistance;
  std::vector<Predecessor> vertexPredecessor;
  std::vector<char> fired;
  // Per halfedge: the shortest distance to its face's opposite vertex offered by a window on this
  // halfedge so far, and where that ray crossed the edge (Chen-Han "one angle, one split").
  // One record per halfedge: both are read together, a cache line instead of two.
  struct OneSplit {
    double distance, crossing;
  };
  std::vector<OneSplit> split;
  // The windows of each halfedge, for trimming a new window against them: their [b0, b1] kept in
  // blocks of five (144 bytes) chained per halfedge, so the walk over a halfedge's windows - most
  // of which do not overlap the new one - reads a few contiguous lines. A linked list through the
  // window array cost a cache miss per window and was a third of all misses.
  struct SpanBlock {
    static constexpr int kCapacity = 5;
    struct Span {
      double b0, b1;
      int window;
    } spans[kCapacity];
    double lo, hi;  // the union of the spans: a new window outside it skips the whole block
    int count;
    int next;  // the halfedge's previous (older) block, -1 at the end
  };
  std::vector<int> firstBlock;  // per halfedge, its newest block; -1 if none
  std::vector<SpanBlock> blocks;
  // Stored mode: every window, in creation order. Front mode: slots, reused once a window has
  // crossed its face (freeSlots); only the queued windows are held. Wavefront mode: empty (slots).
  std::vector<Window> windows;
  // Front mode (DistanceSolverOptions::Engine::FrontOnly). Per slot, where its span is (block * 8
  // + index): -1 once the window has been trimmed away while queued (its queue entry is then
  // skipped) or taken from the queue. The blocks hold only the queued windows' spans: a block whose
  // spans are all gone is unlinked (blockPrev) and reused (freeBlocks).
  bool storeWindows = true;
  std::vector<int> freeSlots;  // a queue: [freeHead, end) are free
  std::size_t freeHead = 0;
  std::vector<int> slotSpan;
  std::vector<int> blockLive, blockPrev, freeBlocks;
  // Wavefront mode (DistanceSolverOptions::Engine::Wavefront, wavefront_engine.cpp): the queued
  // windows of each halfedge form one first-in-first-out list through the slots (slotNext), and
  // the queue holds halfedges, not windows: EdgeList::key is the key of a halfedge's live queue
  // entry (the smallest key of its windows when it was pushed; +inf if none). Head, tail and key
  // are read together for every window added: one 16-byte record per halfedge, one cache line
  // where three arrays cost three. Slots are reused as a stack (freeSlots from the back): the slot
  // just freed is the one still in cache.
  bool wavefront = false;
  struct EdgeList {
    double key;
    int head, tail;  // slots, -1 if the list is empty
  };
  std::vector<EdgeList> lists;
  // A slot: the window and the link to the next slot of its halfedge's list (-1 at the tail), one
  // cache line. A popped list is walked slot by slot, and the 56-byte windows with their links in
  // an array of their own were two or three lines per window (misses: docs/measurements.md).
  struct alignas(64) Slot {
    Window window;
    int next;
  };
  std::vector<Slot> slots;
  long halfedgePops = 0;      // diagnostics: batches propagated (live queue entries popped)
  long nearImagesMerged = 0;  // diagnostics: windows merged into a near image (imageMergeTolerance)
  // Per pseudo-source vertex, a copy of the window its best path so far came through: the cone it
  // fires into is aimed from that path (incomingAngle), and the window's slot may be reused.
  std::vector<Window> predecessorWindow;
  long windowsCreated =
      0;  // windows queued by the last propagation (the slots are fewer in front mode)
  // Items >= 0: window index (the wavefront engine: halfedge); < 0: vertex event for vertex
  // -item-1.
  BucketQueue queue;
  // A full field of the wavefront engine (wavefront_engine.cpp, runSplitQueues): the queue holds
  // halfedges only, popped in any order within a bucket, and the vertex events wait in this heap by
  // (key, item).
  bool splitQueues = false;
  std::vector<BucketQueue::Entry> vertexEvents;
  std::size_t vertexEventsPeak = 0;
  // Targets of this query, bucketed by face.
  std::vector<int> faceFirstTarget;  // -1 if none (reset after each query)
  std::vector<int> nextTarget;
  std::vector<Eigen::Vector3d> targetWeights;  // normalised barycentric of each target
  std::vector<int> targetFace;
  std::vector<double> targetDistance;
  std::vector<Predecessor> targetPredecessor;
  // The source point (resolved).
  int sourceVertex = -1;  // >= 0 if the source is a vertex
  std::vector<int> sourceFaces;
  Eigen::Vector3d sourcePosition = Eigen::Vector3d::Zero();
};

// The working memory of the last propagation at its peak (the arrays it used, windows and queue
// entries at their most), in bytes.
double peakBytes(const MeshTables& tables, const Propagation& state);

// Runs the exact propagation from `source` with `targets`. `wavefront` (without storeWindows)
// selects Engine::Wavefront, otherwise storeWindows false is Engine::FrontOnly. With storeWindows
// (path() needs it, or Engine::StoredWindows) it leaves the windows in `state` for backtracing;
// otherwise only the distances and targets' values are meaningful. directedAtTargets (with
// targets): queued by distance plus the chord to the nearest target and stopped once every target
// is final (goal_bound.hpp); the target distances and paths are the full field's (exact mode; see
// goal_bound.hpp), the vertex distances only upper bounds.
void propagate(const MeshTables& tables, const DistanceSolverOptions& options,
               const SurfacePoint& source, const std::vector<SurfacePoint>& targets,
               Propagation& state, bool directedAtTargets = false, bool storeWindows = true,
               bool wavefront = false);

// Traces the shortest path from the source of `state` to its target `targetIndex`, returned from
// source to target.
GeodesicPath tracePath(const MeshTables& tables, const Propagation& state, int targetIndex,
                       const SurfacePoint& source, const SurfacePoint& target);

}  // namespace egg::geodesic::detail
