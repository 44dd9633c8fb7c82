#pragma once
// Internal: the flat mesh tables and the exact window propagation behind DistanceSolver.
// Not part of the public API (include distance_solver.hpp instead).
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
  std::vector<int> fromVertex, toVertex, face, next, prev;
  std::vector<double> length, oppositeX, oppositeY;
  std::vector<int> oppositeVertex;
  // Per face: its vertices in OpenMesh circulator order (the SurfacePoint barycentric order) and
  // faceHalfedge[f][i] = the halfedge of f leaving faceVerts[f][i].
  std::vector<std::array<int, 3>> faceVerts;
  std::vector<std::array<int, 3>> faceHalfedge;
  // Outgoing halfedges of each vertex (CSR), boundary halfedges included.
  std::vector<int> outgoingStart, outgoing;
  std::vector<char> pseudoSource;  // saddle or reflex boundary vertex
  std::vector<char> boundaryVertex;
  std::vector<double> angleSum;
  double meanEdgeLength = 0.0;

  int twin(int h) const { return h ^ 1; }
};

MeshTables buildTables(const TriMesh& mesh, const DistanceSolverOptions& options);

// A window: an interval [b0, b1] of the edge of halfedge `halfedge` (measured from its from-vertex)
// through which straight rays from the unfolded source image (sx, sy) (sy < 0, i.e. behind the
// edge) enter face(halfedge). sigma is the geodesic distance from the source to the image (0 for
// the source itself, d(v) for a pseudo-source vertex v).
struct Window {
  int halfedge = -1;
  int parent = -1;        // window this one was propagated from; -1 if born at a (pseudo-)source
  int pseudoSource = -1;  // vertex the rays come from; -1 for the source point itself
  double b0 = 0.0, b1 = 0.0;
  double sx = 0.0, sy = 0.0;
  double sigma = 0.0;
};

// How the best value at a vertex or target was obtained (for backtracing paths).
struct Predecessor {
  enum Kind : char { None, Source, Vertex, ThroughWindow };
  Kind kind = None;
  int index = -1;  // vertex or window index
};

// Per-thread scratch space and the result of one propagation.
struct Propagation {
  std::vector<double> vertexDistance;
  std::vector<Predecessor> vertexPredecessor;
  std::vector<char> fired;
  // Per halfedge: the shortest distance to its face's opposite vertex offered by a window on this
  // halfedge so far, and where that ray crossed the edge (Chen-Han "one angle, one split").
  std::vector<double> splitDistance;
  std::vector<double> splitCrossing;
  // Windows on each halfedge as singly linked lists (for trimming a new window against them).
  std::vector<int> firstOnHalfedge;
  std::vector<int> nextOnHalfedge;
  std::vector<Window> windows;
  struct QueueEntry {
    double key;
    int item;  // >= 0: window index; < 0: vertex event for vertex -item-1
    bool operator>(const QueueEntry& o) const { return key > o.key || (key == o.key && item > o.item); }
  };
  std::vector<QueueEntry> queue;  // binary heap
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

// Runs the exact propagation from `source` with `targets`. Leaves the windows in `state` for
// backtracing.
void propagate(const MeshTables& tables, const DistanceSolverOptions& options, const SurfacePoint& source,
               const std::vector<SurfacePoint>& targets, Propagation& state);

// Traces the shortest path from the source of `state` to its target `targetIndex`, returned from
// source to target.
GeodesicPath tracePath(const MeshTables& tables, const Propagation& state, int targetIndex,
                       const SurfacePoint& source, const SurfacePoint& target);

}  // namespace egg::geodesic::detail
