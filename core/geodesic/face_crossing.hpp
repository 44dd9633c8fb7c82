#pragma once
// Internal: the two steps of the window propagation that every engine runs per window, inline so
// the wavefront engine's batch loop (wavefront_engine.cpp) compiles them into one function with its
// own window insertion: pruning a new window against its edge's endpoints, and crossing a face
// (the opposite vertex's distance, the targets in the face, the two child windows).
// window_propagation.cpp has the algorithm's description.
#include "core/geodesic/propagator.hpp"
#include "core/geodesic/window_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace egg::geodesic::detail {

// Trims the parts of `w` dominated by the paths through the endpoints of its edge. Returns false
// if nothing is left.
inline bool Propagator::prune(Window& w, double* endLengths) const {
  const int h = w.halfedge;
  const double L = t_.he[h].length;
  const double dA = s_.vertexDistance[t_.he[h].fromVertex];
  const double dB = s_.vertexDistance[t_.he[h].toVertex];
  // |s - b0| and |s - b1|, recomputed only when an end moves: every test below needs them and
  // the square roots were the bulk of this function.
  // The window was just written field by field (crossFace): its fields are read one by
  // one (loadAlone: a paired load would stall on the store buffer; docs/measurements.md).
  const double sx = loadAlone(w.sx), sy = loadAlone(w.sy);
  double r0, r1;
  planarLengths(loadAlone(w.b0) - sx, sy, loadAlone(w.b1) - sx, sy, r0, r1);
  // Endpoint A at (0,0): f(x) = sigma + |s - x| - dA - x is non-increasing in x.
  if (dA < kInfinity) {
    const double k = dA - w.sigma;
    const double f1 = r1 - k - w.b1;
    if (f1 > 0.0) return false;
    const double f0 = r0 - k - w.b0;
    if (f0 > 0.0) {
      const double denom = 2.0 * (k + sx);
      if (denom > 0.0) {
        const double root = (sx * sx + sy * sy - k * k) / denom;
        w.b0 = std::clamp(root, w.b0, w.b1);
        r0 = planarLength(w.b0 - sx, sy);
      }
    }
  }
  // Endpoint B at (L,0): g(x) = sigma + |s - x| - dB - (L - x) is non-decreasing in x.
  if (dB < kInfinity) {
    const double k = dB - w.sigma;
    const double g0 = r0 - k - (L - w.b0);
    if (g0 > 0.0) return false;
    const double g1 = r1 - k - (L - w.b1);
    if (g1 > 0.0) {
      const double mx = L - sx;
      const double denom = 2.0 * (k + mx);
      if (denom > 0.0) {
        const double root = L - (mx * mx + sy * sy - k * k) / denom;
        w.b1 = std::clamp(root, w.b0, w.b1);
        r1 = planarLength(w.b1 - sx, sy);
      }
    }
  }
  if (w.b1 - w.b0 <= o_.minWindowWidthRelative * L) return false;
  if (endLengths) {
    endLengths[0] = r0;
    endLengths[1] = r1;
  }
  // Xin-Wang's other two tests (the vertex ahead, the one behind the edge) are not made: they
  // killed almost no windows for a lookup and two square roots per window; one-split and trimming
  // do that work already. Nor would any vertex filter (VTP's per-triangle pruning included) help on
  // the sphere caps, whose windows are their exact field's: only cheaper windows make it faster
  // (test_window_propagation.cpp, WindowPruning; counts: docs/measurements.md).
  return true;
}

template <class AddChild>
void Propagator::crossFace(const Window& w, int index, const FaceCrossing& face,
                           AddChild&& addChild) {
  // No second pruning here (pruned when added): re-pruning at the pop would kill almost no windows
  // for ~10 % of the time (docs/measurements.md). An unpruned window is still a real path, so
  // what it offers and the pruning it feeds stay valid: it only costs its own propagation.
  const int h = face.h;
  const int f = face.f;
  const double L = face.length;
  const double cx = face.cx, cy = face.cy;
  const int c = face.c;
  const double slack = 1e-9 * L;
  // Where the ray through the opposite vertex crosses the edge.
  const double xc = rayCrossing(w.sx, w.sy, cx, cy);
  bool leftChild = xc > w.b0, rightChild = xc < w.b1;
  if (xc >= w.b0 - slack && xc <= w.b1 + slack) {
    const double dc = w.sigma + planarLength(cx - w.sx, cy - w.sy);
    auto& split = s_.split[h];
    if (dc > split.distance * (1.0 + 1e-10)) {
      // One angle, one split (Chen & Han 1990): a shorter path to C already enters this face
      // through this edge at split.crossing. It and this window's ray to C bound a region; this
      // window's rays on that path's side must cross it and are beaten there, so only the
      // child on the far side can carry shortest paths.
      if (split.crossing < xc)
        leftChild = false;
      else
        rightChild = false;
    } else {
      if (dc < split.distance) split = {dc, xc};
      relaxVertex(c, dc, {Predecessor::ThroughWindow, index}, &w);
    }
  } else {
    // C lies just outside the window: a path bent round the window's end (a valid upper bound),
    // or at the vertex its boundary ray runs through - the only way into the shadow of a
    // near-flat saddle that is not a pseudo-source (see pathBentAt).
    const int side = xc < w.b0 ? 0 : 1;
    const int x = w.endVertex[side];
    // Whether x has a cone is read whatever x (vertex 0's when there is none), and the two tests
    // joined without a branch: x >= 0 is a coin toss along the wavefront, and its branch was a
    // large share of the propagation's mispredictions (docs/measurements.md).
    const char bendsAtX = t_.hasShadowCone[x >= 0 ? x : 0];
    if ((x >= 0) & (bendsAtX != 0)) {
      bool atVertex;
      const double d = bentDistance(w, side, cx, cy, atVertex);
      relaxVertex(c, d, Predecessor::throughWindow(index, side, atVertex), &w);
    } else {
      // Round the end (bentDistance's value here): sigma + |s - end| + |end - C|, where
      // |end - C| >= cy. Most of these paths improve nothing, so the second square root waits for
      // the bound; its margin, far above rounding, means a spared relaxation would have been
      // refused: the distances are bit-identical (savings: docs/measurements.md).
      const double toEnd = w.sigma + distanceToEnd(w, side);
      if ((toEnd + cy) * (1.0 - 1e-12) < s_.vertexDistance[c]) {
        const double d = toEnd + planarLength(cx - (side ? w.b1 : w.b0), cy);
        relaxVertex(c, d, Predecessor::throughWindow(index, side, false), &w);
      }
    }
  }
  // Targets inside the face the window enters.
  for (int i = s_.faceFirstTarget[f]; i >= 0; i = s_.nextTarget[i]) {
    double qx, qy;
    frameCoordinates(f, h, s_.targetWeights[i], qx, qy);
    const double xq = rayCrossing(w.sx, w.sy, qx, qy);
    double d;
    Predecessor pred{Predecessor::ThroughWindow, index};
    if (xq >= w.b0 - slack && xq <= w.b1 + slack) {
      d = w.sigma + planarLength(qx - w.sx, qy - w.sy);
    } else {
      const int side = xq < w.b0 ? 0 : 1;
      bool atVertex;
      d = bentDistance(w, side, qx, qy, atVertex);
      pred = Predecessor::throughWindow(index, side, atVertex);
    }
    if (d < s_.targetDistance[i]) {
      s_.targetDistance[i] = d;
      s_.targetPredecessor[i] = pred;
    }
  }
  // A child on the edge `halfedge` of the next face, whose frame is `frame` from h's: its ends
  // are the crossings of w's boundary rays, or the edge's start (0) or end (`length`) where w's
  // rays reach that vertex.
  auto child = [&](int halfedge, double length, const FrameChange& frame, bool fromStart,
                   bool toEnd) {
    Window cw;
    cw.halfedge = halfedge;
    cw.parent = index;
    cw.sigma = w.sigma;
    std::copy_n(w.endVertex, 2, cw.endVertex);
    frame.apply(w.sx, w.sy, cw.sx, cw.sy);
    if (!(cw.sy < 0.0)) return;
    double px, py;
    if (fromStart) {
      cw.b0 = 0.0;
    } else {
      frame.apply(w.b0, 0.0, px, py);
      cw.b0 = rayCrossing(cw.sx, cw.sy, px, py);
    }
    if (toEnd) {
      cw.b1 = length;
    } else {
      frame.apply(w.b1, 0.0, px, py);
      cw.b1 = rayCrossing(cw.sx, cw.sy, px, py);
    }
    cw.b0 = std::clamp(cw.b0, 0.0, length);
    cw.b1 = std::clamp(cw.b1, 0.0, length);
    if (cw.b1 > cw.b0) addChild(cw);
  };
  // On edge A-C (rays left of the opposite vertex), the halfedge A->C of the next face; on edge
  // C-B (rays right of it), C->B. The rays through C end the left child at C and start the right.
  if (leftChild && face.leftChild >= 0)
    child(face.leftChild, face.leftLength, face.leftFrame, w.b0 == 0.0, xc < w.b1);
  if (rightChild && face.rightChild >= 0)
    child(face.rightChild, face.rightLength, face.rightFrame, xc > w.b0, w.b1 == L);
}

}  // namespace egg::geodesic::detail
