#pragma once
// Internal: the window propagation's state machine, shared by its two translation units:
// window_propagation.cpp (the hot loop: queue, pruning, trimming, crossing a face) and
// propagation_setup.cpp (per-query reset, the source, pseudo-source firing, the targets' vertex
// paths). Not part of the public API.
#include "core/geodesic/goal_bound.hpp"
#include "core/geodesic/window_geometry.hpp"
#include "core/geodesic/window_propagation.hpp"

#include <string>
#include <vector>

namespace egg::geodesic::detail {

class Propagator {
 public:
  Propagator(const MeshTables& t, const DistanceSolverOptions& o, Propagation& s)
      : t_(t), o_(o), s_(s) {}

  void run(const SurfacePoint& source, const std::vector<SurfacePoint>& targets, bool directed);

 private:
  const MeshTables& t_;
  const DistanceSolverOptions& o_;
  Propagation& s_;
  DirectedTargets directed_;  // empty (a full field) unless the query is directed at its targets
  const GoalBound& goal_ = directed_.goal;
  std::vector<int> fan_;

  double vertexKey(int v) const {
    return s_.vertexDistance[v] + (goal_.active() ? goal_.toPoint(t_.positions[v]) : 0.0);
  }
  double windowKey(const Window& w) const;
  // The same from |s - b0| and |s - b1| already known (bit-identical: sqrt is correctly rounded).
  double windowKey(const Window& w, const double* endLengths) const;
  double keyOfNearest(const Window& w,
                      double nearest) const;  // + the goal bound of a directed query

  // propagation_setup.cpp
  void reset(const std::vector<SurfacePoint>& targets);
  static Eigen::Vector3d normalisedWeights(const SurfacePoint& p, const std::string& what);
  void seed(const SurfacePoint& source);
  void seedTargetsInFaces();
  void fire(int v);
  double incomingAngle(int v) const;
  void finishTargets();

  void push(double key, int item) {
    if (item < 0 && s_.splitQueues)
      pushVertexEvent(key, item);
    else
      s_.queue.push(key, item);
  }
  void pushVertexEvent(double key, int item);
  BucketQueue::Entry popVertexEvent();

  // `via`: the window the path came through (none for vertex and source paths). Front mode keeps
  // a copy for a pseudo-source, whose cone is aimed from it when it fires (incomingAngle).
  void relaxVertex(int v, double d, Predecessor pred, const Window* via = nullptr) {
    if (!(d < s_.vertexDistance[v])) return;
    s_.vertexDistance[v] = d;
    s_.vertexPredecessor[v] = pred;
    if (t_.pseudoSource[v] && !s_.fired[v]) {
      if (via && !s_.storeWindows) s_.predecessorWindow[v] = *via;
      push(vertexKey(v), -v - 1);
    }
  }

  // Position of barycentric weights (in face circulator order) in the frame of halfedge h of face
  // f.
  void frameCoordinates(int f, int h, const Eigen::Vector3d& w, double& x, double& y) const {
    const auto& fv = t_.faceVerts[f];
    const int a = t_.he[h].fromVertex, b = t_.he[h].toVertex;
    double wb = 0, wc = 0;  // the from-vertex sits at the frame's origin
    for (int i = 0; i < 3; ++i) {
      if (fv[i] == b)
        wb = w[i];
      else if (fv[i] != a)
        wc = w[i];
    }
    x = wb * t_.he[h].length + wc * t_.he[h].oppositeX;
    y = wc * t_.he[h].oppositeY;
  }

  // window_propagation.cpp
  // endLengths (if given): |s - b0| and |s - b1| of the pruned window, which windowKey needs too.
  bool prune(Window& w, double* endLengths = nullptr) const;
  double bentDistance(const Window& w, int side, double px, double py, bool& atVertex) const;
  void addWindow(Window& w);
  void addStoredWindow(Window& w);
  void addFrontWindow(Window& w);
  bool takeFrontWindow(int slot);
  void clearSpan(int slot);
  // What every window crossing the face of halfedge h shares: the wavefront engine builds it once
  // per batch (propagateHalfedge), the other engines once per window.
  struct FaceCrossing {
    int h, f, c;            // the halfedge, its face, the face's vertex opposite it
    double length, cx, cy;  // the edge's length, the opposite vertex in its frame
    int leftChild,
        rightChild;  // halfedges A->C and C->B seen from the next faces; -1 at a boundary
    double leftLength, rightLength;
    FrameChange leftFrame, rightFrame;  // from h's frame into each child's
  };
  FaceCrossing faceCrossing(int h) const;
  // w: a copy of the window in slot `index` (its children may move the array it lies in).
  void propagateWindow(const Window& w, int index, const FaceCrossing& face);
  // propagateWindow's work, each child window handed to addChild(Window&) (face_crossing.hpp).
  template <class AddChild>
  void crossFace(const Window& w, int index, const FaceCrossing& face, AddChild&& addChild);

  // wavefront_engine.cpp
  void addWavefrontWindow(Window& w);
  void insertWavefrontWindow(Window& w);  // addWavefrontWindow's body, inline in the batch loop
  void unlinkWavefrontSlot(int h, int slot, int previous);
  void propagateHalfedge(int h, double key);
  void prefetchNextBatches() const;
  void runSplitQueues();
};

}  // namespace egg::geodesic::detail
