// The cold parts of the window propagation (window_propagation.cpp has the algorithm and the hot
// loop): per-query reset, the source's first windows, pseudo-source firing into its cone, the
// targets' vertex paths, and the working-memory count of a field.
#include "core/geodesic/propagator.hpp"
#include "core/geodesic/window_geometry.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace egg::geodesic::detail {

void Propagator::reset(const std::vector<SurfacePoint>& targets) {
  s_.vertexDistance.assign(t_.vertexCount, kInfinity);
  s_.vertexPredecessor.assign(t_.vertexCount, Predecessor{});
  s_.fired.assign(t_.vertexCount, 0);
  s_.split.assign(t_.halfedgeCount, {kInfinity, 0.0});
  s_.windows.clear();
  s_.blocks.clear();
  s_.firstBlock.assign(t_.halfedgeCount, -1);
  s_.freeSlots.clear();
  s_.freeHead = 0;
  s_.slotSpan.clear();
  s_.blockLive.clear();
  s_.blockPrev.clear();
  s_.freeBlocks.clear();
  s_.halfedgePops = 0;
  s_.nearImagesMerged = 0;
  s_.slots.clear();
  if (s_.wavefront) {
    s_.lists.assign(t_.halfedgeCount, {kInfinity, -1, -1});
  }
  if (!s_.storeWindows && static_cast<int>(s_.predecessorWindow.size()) != t_.vertexCount) {
    s_.predecessorWindow.resize(t_.vertexCount);
  }
  s_.windowsCreated = 0;
  // Exact (key, item) order (the stored and front engines, directed queries): buckets of 1/1024
  // edge, a handful of queued windows each (see bucket_queue.hpp); measured on the 3.6k bump,
  // 1/256 left crowded buckets (8 % more instructions).
  // A full field of the wavefront engine pops a bucket's halfedges in any order (Propagator::
  // runSplitQueues), so its buckets can be wide: one mean edge. A halfedge whose key drops within
  // its bucket is not queued again, and the newest halfedge of a bucket, popped first, is the one
  // still in cache. Against 1/1024 edge (18k-vertex cap of issue 19, one field): 74k queue entries
  // instead of 256k for 54-59k batches, simulated first-level misses 2.35M -> 1.05M, branch misses
  // 2.76M -> 1.95M; the windows within 0.1 % and the distances equal. 1/16, 1/4, 1/2 and 4 edges
  // were all costlier in that count, on the cap and on the 4.4k bump.
  const double bucketWidth = s_.splitQueues ? t_.meanEdgeLength : t_.meanEdgeLength / 1024.0;
  s_.queue.reset(bucketWidth, /*unordered=*/s_.splitQueues);
  s_.vertexEvents.clear();
  s_.vertexEventsPeak = 0;
  if (static_cast<int>(s_.faceFirstTarget.size()) != t_.faceCount)
    s_.faceFirstTarget.assign(t_.faceCount, -1);
  const int nt = static_cast<int>(targets.size());
  s_.nextTarget.assign(nt, -1);
  s_.targetWeights.resize(nt);
  s_.targetFace.resize(nt);
  s_.targetDistance.assign(nt, kInfinity);
  s_.targetPredecessor.assign(nt, Predecessor{});
  for (int i = 0; i < nt; ++i) {
    const int f = targets[i].face;
    if (f < 0 || f >= t_.faceCount) {
      for (int j = 0; j < i; ++j) s_.faceFirstTarget[s_.targetFace[j]] = -1;
      throw InvalidInput("geodesic: target " + std::to_string(i) + " refers to face " +
                         std::to_string(f) + ", but the mesh has " + std::to_string(t_.faceCount) +
                         " faces");
    }
    s_.targetWeights[i] = normalisedWeights(targets[i], "target " + std::to_string(i));
    s_.targetFace[i] = f;
    s_.nextTarget[i] = s_.faceFirstTarget[f];
    s_.faceFirstTarget[f] = i;
  }
}

Eigen::Vector3d Propagator::normalisedWeights(const SurfacePoint& p, const std::string& what) {
  Eigen::Vector3d w = p.barycentric.cwiseMax(0.0);
  const double sum = w.sum();
  if (!(sum > 0.0) || !p.barycentric.allFinite() || (p.barycentric.array() < -1e-9).any()) {
    throw InvalidInput("geodesic: " + what + " has invalid barycentric weights");
  }
  w /= sum;
  for (int i = 0; i < 3; ++i) {
    if (w[i] < 1e-14) w[i] = 0.0;
  }
  return w / w.sum();
}

void Propagator::seed(const SurfacePoint& source) {
  s_.sourceVertex = -1;
  s_.sourceFaces.clear();
  if (source.face < 0 || source.face >= t_.faceCount) {
    throw InvalidInput("geodesic: the source refers to face " + std::to_string(source.face) +
                       ", but the mesh has " + std::to_string(t_.faceCount) + " faces");
  }
  const Eigen::Vector3d w = normalisedWeights(source, "the source");
  const auto& fv = t_.faceVerts[source.face];
  s_.sourcePosition = t_.pointIn(source.face, w);
  int nonZero = 0, lastNonZero = -1;
  for (int i = 0; i < 3; ++i) {
    if (w[i] > 0.0) {
      ++nonZero;
      lastNonZero = i;
    }
  }
  if (nonZero == 1) {
    // A vertex source is a pseudo-source at distance 0, whatever its angle sum.
    const int v = fv[lastNonZero];
    s_.sourceVertex = v;
    s_.sourcePosition = t_.positions[v];
    s_.vertexDistance[v] = 0.0;
    s_.vertexPredecessor[v] = {Predecessor::Source, -1};
    push(vertexKey(v), -v - 1);
    seedTargetsInFaces();
    return;
  }
  s_.sourceFaces.push_back(source.face);
  if (nonZero == 2) {
    // On an edge: the point belongs to both faces of that edge.
    for (int i = 0; i < 3; ++i) {
      if (w[i] != 0.0) continue;
      const int h = t_.faceHalfedge[source.face][(i + 1) % 3];  // the edge opposite fv[i]
      const int other = t_.he[t_.twin(h)].face;
      if (other >= 0) s_.sourceFaces.push_back(other);
    }
  }
  const Eigen::Vector3d& p = s_.sourcePosition;
  for (int f : s_.sourceFaces) {
    for (int k = 0; k < 3; ++k) {
      const int v = t_.faceVerts[f][k];
      relaxVertex(v, (t_.positions[v] - p).norm(), {Predecessor::Source, -1});
    }
    // Barycentric weights of the point in face f (f may be the neighbour across the edge).
    Eigen::Vector3d wf = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 3; ++i) {
        if (t_.faceVerts[f][k] == fv[i]) wf[k] = w[i];
      }
    }
    for (int k = 0; k < 3; ++k) {
      const int h = t_.faceHalfedge[f][k];
      const int opposite = t_.he[h].oppositeVertex;
      double oppositeWeight = 0.0;
      for (int i = 0; i < 3; ++i) {
        if (t_.faceVerts[f][i] == opposite) oppositeWeight = wf[i];
      }
      if (oppositeWeight <= 0.0) continue;  // the point lies on this edge
      const int tw = t_.twin(h);
      if (t_.he[tw].face < 0) continue;
      double x, y;
      frameCoordinates(f, h, wf, x, y);
      Window win;
      win.halfedge = tw;
      win.b0 = 0.0;
      win.b1 = t_.he[h].length;
      win.sx = t_.he[h].length - x;
      win.sy = -y;
      win.sigma = 0.0;
      addWindow(win);
    }
  }
  seedTargetsInFaces();
}

// Targets in a face that contains the source see it in a straight line.
void Propagator::seedTargetsInFaces() {
  std::vector<int> faces = s_.sourceFaces;
  if (s_.sourceVertex >= 0) {
    const int v = s_.sourceVertex;
    for (int k = t_.outgoingStart[v]; k < t_.outgoingStart[v + 1]; ++k) {
      if (t_.he[t_.outgoing[k]].face >= 0) faces.push_back(t_.he[t_.outgoing[k]].face);
    }
  }
  for (int f : faces) {
    for (int i = s_.faceFirstTarget[f]; i >= 0; i = s_.nextTarget[i]) {
      const double d = (t_.pointIn(f, s_.targetWeights[i]) - s_.sourcePosition).norm();
      if (d < s_.targetDistance[i]) {
        s_.targetDistance[i] = d;
        s_.targetPredecessor[i] = {Predecessor::Source, -1};
      }
    }
  }
}

// A pseudo-source with its final distance emits windows onto the edges opposite it, but only
// into the directions where a shortest path can continue: a path through v is locally shortest
// only if it leaves at least pi of surface angle on each side (Mitchell-Mount-Papadimitriou,
// Lemma 3.4; Xin-Wang's pseudo-source cone). On a saddle with angle sum 2 pi + e that is a
// wedge of width e opposite the incoming direction; on a boundary vertex, the directions at
// least pi away from the incoming one on the surface side.
void Propagator::fire(int v) {
  s_.fired[v] = 1;
  const double dv = s_.vertexDistance[v];
  for (int k = t_.outgoingStart[v]; k < t_.outgoingStart[v + 1]; ++k) {
    const int hout = t_.outgoing[k];
    relaxVertex(t_.he[hout].toVertex, dv + t_.he[hout].length, {Predecessor::Vertex, v});
  }
  // The faces around v in counter-clockwise order (h -> twin(prev(h))), starting after the
  // boundary for a boundary vertex.
  fan_.clear();
  int start = -1;
  for (int k = t_.outgoingStart[v]; k < t_.outgoingStart[v + 1]; ++k) {
    const int h = t_.outgoing[k];
    if (t_.he[h].face < 0) continue;
    if (start < 0) start = h;
    if (t_.he[t_.twin(h)].face < 0) {
      start = h;
      break;
    }
  }
  if (start < 0) return;
  for (int h = start;;) {
    fan_.push_back(h);
    const int nextOut = t_.twin(t_.he[h].prev);
    if (t_.he[nextOut].face < 0 || nextOut == start) break;
    h = nextOut;
    if (static_cast<int>(fan_.size()) > t_.outgoingStart[v + 1] - t_.outgoingStart[v])
      break;  // non-manifold guard
  }
  const bool boundary = t_.boundaryVertex[v] != 0;
  double backAngle = -1.0;
  if (v != s_.sourceVertex) backAngle = incomingAngle(v);
  double cumulative = 0.0;
  const double total = t_.angleSum[v];
  const double tol = 1e-7;
  for (int h : fan_) {
    const double corner = std::atan2(t_.he[h].oppositeY, t_.he[h].oppositeX);
    const double a0 = cumulative, a1 = cumulative + corner;
    cumulative = a1;
    double lo = a0, hi = a1;
    if (backAngle >= 0.0 && !allowedFanInterval(a0, a1, backAngle, total, boundary, tol, lo, hi))
      continue;
    const int ho = t_.he[h].next;  // edge opposite v in this face; v is its opposite vertex
    const int tw = t_.twin(ho);
    if (t_.he[tw].face < 0) continue;
    // The window covers only where the allowed rays cross the opposite edge. On a near-flat
    // saddle the cone is a sliver of the face: a full-edge window there is dominated almost
    // everywhere, yet it is trimmed against and propagated across the whole front - measured on
    // the 4.5k bump, clipping saves 16 % of the propagation's instructions (half the trimming).
    const double length = t_.he[ho].length;
    const double ox = t_.he[ho].oppositeX, oy = t_.he[ho].oppositeY;  // v in the frame of ho
    Window win;
    win.halfedge = tw;
    win.parent = Window::fromVertex(v);
    // Coordinates on the twin run from the other end of the edge.
    const auto [from, to] = coneCrossings(ox, oy, length, corner, lo - a0, hi - a0);
    win.b0 = length - to;
    win.b1 = length - from;
    win.sx = length - ox;
    win.sy = -oy;
    win.sigma = dv;
    if (win.b1 > win.b0) addWindow(win);
  }
}

// The angle (measured counter-clockwise around v from the start of fan_) of the direction back
// along the shortest path that reached v; -1 if unknown (then every direction is allowed).
double Propagator::incomingAngle(int v) const {
  const Predecessor pred = s_.vertexPredecessor[v];
  Eigen::Vector3d back;
  if (pred.kind == Predecessor::ThroughWindow || pred.kind == Predecessor::BentAtVertex) {
    // Where the path entered v's face: on the window's ray, or on the segment from the bend.
    const Window& w = s_.storeWindows ? s_.windows[pred.index] : s_.predecessorWindow[v];
    const int h = w.halfedge;
    const double L = t_.he[h].length;
    const double cx = t_.he[h].oppositeX, cy = t_.he[h].oppositeY;
    double xc;
    if (pred.kind == Predecessor::ThroughWindow) {
      xc = std::clamp(rayCrossing(w.sx, w.sy, cx, cy), w.b0, w.b1);
    } else {
      double bx, by;
      bendPoint(w, pred.side, s_.vertexDistance[w.endVertex[static_cast<int>(pred.side)]], bx, by);
      xc = std::clamp(rayCrossing(bx, by, cx, cy), 0.0, L);
    }
    back = t_.positions[t_.he[h].fromVertex] +
           (xc / L) * (t_.positions[t_.he[h].toVertex] - t_.positions[t_.he[h].fromVertex]);
  } else if (pred.kind == Predecessor::Vertex) {
    back = t_.positions[pred.index];
  } else if (pred.kind == Predecessor::Source) {
    back = s_.sourcePosition;
  } else {
    return -1.0;
  }
  const Eigen::Vector3d p = t_.positions[v];
  const Eigen::Vector3d dir = back - p;
  if (dir.squaredNorm() == 0.0) return -1.0;
  return fanAngleOf(t_, fan_, p, dir);
}

// Vertex paths into the targets' faces: d(v) + |v q| for the three vertices.
void Propagator::finishTargets() {
  const int nt = static_cast<int>(s_.targetFace.size());
  for (int i = 0; i < nt; ++i) {
    const int f = s_.targetFace[i];
    const auto& fv = t_.faceVerts[f];
    const Eigen::Vector3d q = t_.pointIn(f, s_.targetWeights[i]);
    for (int k = 0; k < 3; ++k) {
      const double d = s_.vertexDistance[fv[k]] + (q - t_.positions[fv[k]]).norm();
      if (d < s_.targetDistance[i]) {
        s_.targetDistance[i] = d;
        s_.targetPredecessor[i] = {Predecessor::Vertex, fv[k]};
      }
    }
  }
}

double peakBytes(const MeshTables& t, const Propagation& s) {
  const double v = t.vertexCount, h = t.halfedgeCount,
               windows = static_cast<double>(s.windows.size());
  // Per vertex: distance, predecessor, fired; per halfedge: the one-split pair and a list head.
  double bytes =
      v * (sizeof(double) + sizeof(Predecessor) + 1) + h * (2 * sizeof(double) + sizeof(int));
  if (s.storeWindows) {
    bytes += windows * sizeof(Window) +
             static_cast<double>(s.blocks.size()) * sizeof(Propagation::SpanBlock);
  } else if (s.wavefront) {
    // Slots (window and list link, a free-list entry), per halfedge a list's head, tail and key,
    // and the pseudo-sources' window copies.
    bytes += static_cast<double>(s.slots.size()) * (sizeof(Propagation::Slot) + sizeof(int)) +
             h * sizeof(Propagation::EdgeList) + v * sizeof(Window);
  } else {
    // Slots (window, span, a free-list entry), blocks (with live count, back link and a
    // free-list entry) and the pseudo-sources' window copies.
    bytes +=
        windows * (sizeof(Window) + 2 * sizeof(int)) + v * sizeof(Window) +
        static_cast<double>(s.blocks.size()) * (sizeof(Propagation::SpanBlock) + 3 * sizeof(int));
  }
  const double nt = static_cast<double>(s.targetFace.size());
  bytes += nt * (2 * sizeof(int) + sizeof(Eigen::Vector3d) + sizeof(double) + sizeof(Predecessor));
  return bytes +
         static_cast<double>(s.queue.peakSize() + s.vertexEventsPeak) * sizeof(BucketQueue::Entry);
}

}  // namespace egg::geodesic::detail
