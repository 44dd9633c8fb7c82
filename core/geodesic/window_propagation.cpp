// Single-source geodesic distances on a triangle mesh by window propagation (exact, or within 1e-5).
//
// Algorithm (Chen-Han / ICH family: Mitchell-Mount-Papadimitriou 1987, Chen & Han 1990, Xin & Wang
// 2009 "Improving Chen and Han's algorithm on the discrete geodesic problem"):
//  * A window is an interval of an edge together with the unfolded image of the (pseudo-)source
//    that sees it in a straight line (see Window). Unfolding the next face about the edge keeps
//    rays straight, so a window crossing a face yields at most two child windows on the face's
//    other edges, and a candidate distance for the face's opposite vertex when the ray hits it.
//  * Shortest paths only bend at saddle vertices (angle sum > 2 pi) and at boundary vertices.
//    These are pseudo-sources: once their distance is final they emit new windows with
//    sigma = d(v) onto the edges opposite them.
//  * One priority queue (bucket_queue.hpp) holds windows (keyed by the smallest distance they
//    provide) and pseudo-source events (keyed by d(v)), so like Dijkstra a pseudo-source fires
//    exactly once, with its final distance.
//  * Pruning, all of it exact: Chen-Han's one angle, one split; trimming a new window where an
//    earlier window on the same edge is shorter (window_geometry.hpp); and Xin-Wang filtering by
//    the edge's own endpoints (a part where d(A) + |A p| < sigma + |s p| is cut, at a root since
//    the difference is monotone along the edge; the opposite-vertex tests are left out, prune()).
//  * Each window is pruned once, when it is added (see propagateWindow()).
// A strictly dominated part never carries a shortest path, so the result is the exact polyhedral
// distance (to rounding) when every saddle is a pseudo-source (saddleAngleTolerance = 0); by
// default near-flat saddles are bent at instead (pathBentAt): 2-3x faster, 8e-6 at worst.
// Targets: every window entering a target's face offers sigma + |s q| if its ray to q crosses
// it, every vertex v of the face d(v) + |v q| at the end; paths are traced back through
// Window::parent. A directed query queues by d + chord to the targets and stops once they are
// final (goal_bound.hpp); a stale vertex event is recognised by its vertex having fired.
#include "core/geodesic/window_propagation.hpp"
#include "core/geodesic/goal_bound.hpp"
#include "core/geodesic/window_geometry.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace egg::geodesic::detail {

namespace {

class Propagator {
 public:
  Propagator(const MeshTables& t, const DistanceSolverOptions& o, Propagation& s) : t_(t), o_(o), s_(s) {}

  void run(const SurfacePoint& source, const std::vector<SurfacePoint>& targets, bool directed) {
    reset(targets);  // cleans up after itself if a target is invalid
    // The scratch is reused by the thread's next query (thread_local): whatever happens below
    // (bad source, bad_alloc), leave its per-face target buckets clean, or that query would
    // follow stale target indices.
    struct CleanTargetBuckets {
      Propagation& s;
      ~CleanTargetBuckets() {
        for (int f : s.targetFace) s.faceFirstTarget[f] = -1;
      }
    } clean{s_};
    if (directed) directed_.set(t_, s_);
    seed(source);
    while (!s_.queue.empty()) {
      const auto entry = s_.queue.pop();
      if (goal_.active() && entry.key >= directed_.farthestBound(t_, s_)) break;  // targets final
      if (entry.item < 0) {
        const int v = -entry.item - 1;
        if (s_.fired[v]) continue;  // a stale event: a later, no larger key for v popped first
        fire(v);
      } else {
        propagateWindow(entry.item);
      }
    }
    finishTargets();
  }

 private:
  const MeshTables& t_;
  const DistanceSolverOptions& o_;
  Propagation& s_;
  DirectedTargets directed_;  // empty (a full field) unless the query is directed at its targets
  const GoalBound& goal_ = directed_.goal;
  double vertexKey(int v) const { return s_.vertexDistance[v] + (goal_.active() ? goal_.toPoint(t_.positions[v]) : 0.0); }
  double windowKey(const Window& w) const {
    const auto& e = t_.he[w.halfedge];
    return windowMinDistance(w) + (goal_.active() ? goal_.toSegment(t_.positions[e.fromVertex], t_.positions[e.toVertex],
                                                                   w.b0 / e.length, w.b1 / e.length)
                                                  : 0.0);
  }

  void reset(const std::vector<SurfacePoint>& targets) {
    s_.vertexDistance.assign(t_.vertexCount, kInfinity);
    s_.vertexPredecessor.assign(t_.vertexCount, Predecessor{});
    s_.fired.assign(t_.vertexCount, 0);
    s_.splitDistance.assign(t_.halfedgeCount, kInfinity);
    s_.splitCrossing.assign(t_.halfedgeCount, 0.0);
    s_.firstBlock.assign(t_.halfedgeCount, -1);
    s_.blocks.clear();
    s_.windows.clear();
    // Buckets of 1/1024 edge: a handful of queued windows each (see bucket_queue.hpp); measured
    // on the 3.6k bump, 1/256 left crowded buckets (8 % more instructions).
    s_.queue.reset(t_.meanEdgeLength / 1024.0);
    if (static_cast<int>(s_.faceFirstTarget.size()) != t_.faceCount) s_.faceFirstTarget.assign(t_.faceCount, -1);
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
        throw InvalidInput("geodesic: target " + std::to_string(i) + " refers to face " + std::to_string(f) +
                           ", but the mesh has " + std::to_string(t_.faceCount) + " faces");
      }
      s_.targetWeights[i] = normalisedWeights(targets[i], "target " + std::to_string(i));
      s_.targetFace[i] = f;
      s_.nextTarget[i] = s_.faceFirstTarget[f];
      s_.faceFirstTarget[f] = i;
    }
  }

  static Eigen::Vector3d normalisedWeights(const SurfacePoint& p, const std::string& what) {
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

  void push(double key, int item) {
    s_.queue.push(key, item);
  }

  void relaxVertex(int v, double d, Predecessor pred) {
    if (!(d < s_.vertexDistance[v])) return;
    s_.vertexDistance[v] = d;
    s_.vertexPredecessor[v] = pred;
    if (t_.pseudoSource[v] && !s_.fired[v]) push(vertexKey(v), -v - 1);
  }

  // Position of barycentric weights (in face circulator order) in the frame of halfedge h of face f.
  void frameCoordinates(int f, int h, const Eigen::Vector3d& w, double& x, double& y) const {
    const auto& fv = t_.faceVerts[f];
    const int a = t_.he[h].fromVertex, b = t_.he[h].toVertex;
    double wb = 0, wc = 0;  // the from-vertex sits at the frame's origin
    for (int i = 0; i < 3; ++i) {
      if (fv[i] == b) wb = w[i];
      else if (fv[i] != a) wc = w[i];
    }
    x = wb * t_.he[h].length + wc * t_.he[h].oppositeX;
    y = wc * t_.he[h].oppositeY;
  }

  void seed(const SurfacePoint& source) {
    s_.sourceVertex = -1;
    s_.sourceFaces.clear();
    if (source.face < 0 || source.face >= t_.faceCount) {
      throw InvalidInput("geodesic: the source refers to face " + std::to_string(source.face) + ", but the mesh has " +
                         std::to_string(t_.faceCount) + " faces");
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
  void seedTargetsInFaces() {
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
  void fire(int v) {
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
      if (static_cast<int>(fan_.size()) > t_.outgoingStart[v + 1] - t_.outgoingStart[v]) break;  // non-manifold guard
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
      if (backAngle >= 0.0 && !allowedFanInterval(a0, a1, backAngle, total, boundary, tol, lo, hi)) continue;
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
  double incomingAngle(int v) const {
    const Predecessor pred = s_.vertexPredecessor[v];
    Eigen::Vector3d back;
    if (pred.kind == Predecessor::ThroughWindow || pred.kind == Predecessor::BentAtVertex) {
      // Where the path entered v's face: on the window's ray, or on the segment from the bend.
      const Window& w = s_.windows[pred.index];
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
      back = t_.positions[t_.he[h].fromVertex] + (xc / L) * (t_.positions[t_.he[h].toVertex] - t_.positions[t_.he[h].fromVertex]);
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

  std::vector<int> fan_;

  // Trims the parts of `w` dominated by the paths through the endpoints of its edge. Returns false
  // if nothing is left.
  bool prune(Window& w) const {
    const int h = w.halfedge;
    const double L = t_.he[h].length;
    const double dA = s_.vertexDistance[t_.he[h].fromVertex];
    const double dB = s_.vertexDistance[t_.he[h].toVertex];
    // |s - b0| and |s - b1|, recomputed only when an end moves: every test below needs them and
    // the square roots were the bulk of this function.
    double r0, r1;
    planarLengths(w.b0 - w.sx, w.sy, w.b1 - w.sx, w.sy, r0, r1);
    // Endpoint A at (0,0): f(x) = sigma + |s - x| - dA - x is non-increasing in x.
    if (dA < kInfinity) {
      const double k = dA - w.sigma;
      const double f1 = r1 - k - w.b1;
      if (f1 > 0.0) return false;
      const double f0 = r0 - k - w.b0;
      if (f0 > 0.0) {
        const double denom = 2.0 * (k + w.sx);
        if (denom > 0.0) {
          const double root = (w.sx * w.sx + w.sy * w.sy - k * k) / denom;
          w.b0 = std::clamp(root, w.b0, w.b1);
          r0 = planarLength(w.b0 - w.sx, w.sy);
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
        const double mx = L - w.sx;
        const double denom = 2.0 * (k + mx);
        if (denom > 0.0) {
          const double root = L - (mx * mx + w.sy * w.sy - k * k) / denom;
          w.b1 = std::clamp(root, w.b0, w.b1);
          r1 = planarLength(w.b1 - w.sx, w.sy);
        }
      }
    }
    if (w.b1 - w.b0 <= o_.minWindowWidthRelative * L) return false;
    // Xin-Wang's other two tests (the vertex ahead, the one behind the edge) are not made: they
    // killed 0 and 264 of 185k windows on a 3.6k-vertex bump (397, 930 of 15M on the Great Court)
    // for a lookup and two square roots per window; one-split and trimming do that work already.
    return true;
  }

  // A path to (px, py) (frame of w's edge, in the face w enters) whose ray from the source image
  // misses the window past end `side`, bent round that end or at the vertex on its boundary ray
  // (window_geometry.hpp: why that makes skipping near-flat saddles accurate).
  double bentDistance(const Window& w, int side, double px, double py, bool& atVertex) const {
    const int x = w.endVertex[side];
    const BendVertex vertex{x >= 0 ? s_.vertexDistance[x] : 0.0, x >= 0 ? t_.shadowCone[x] : 0.0};
    return pathBentAt(w, side, px, py, t_.he[w.halfedge].length, x >= 0 ? &vertex : nullptr, atVertex);
  }

  void addWindow(Window& w) {
    const double b0In = w.b0, b1In = w.b1;
    if (!prune(w)) return;
    const double L = t_.he[w.halfedge].length;
    int& first = s_.firstBlock[w.halfedge];
    for (int b = first; b >= 0; b = s_.blocks[b].next) {
      const auto& block = s_.blocks[b];
      // Windows reach an edge roughly in the order the front sweeps across it, so a block's
      // windows tend to lie close together and most blocks are skipped whole.
      if (!(std::min(w.b1, block.hi) > std::max(w.b0, block.lo))) continue;
      for (int k = 0; k < block.count; ++k) {
        const auto& span = block.spans[k];
        if (!(std::min(w.b1, span.b1) > std::max(w.b0, span.b0))) continue;  // disjoint: nothing to trim
        if (!trimAgainst(w, s_.windows[span.window]) || w.b1 - w.b0 <= o_.minWindowWidthRelative * L) return;
      }
    }
    markEndVertices(w, b0In, b1In, t_.he[w.halfedge]);
    s_.windows.push_back(w);
    const int index = static_cast<int>(s_.windows.size()) - 1;
    using SpanBlock = Propagation::SpanBlock;
    if (first < 0 || s_.blocks[first].count == SpanBlock::kCapacity) {
      SpanBlock block;
      block.lo = kInfinity;
      block.hi = -kInfinity;
      block.count = 0;
      block.next = first;
      s_.blocks.push_back(block);
      first = static_cast<int>(s_.blocks.size()) - 1;
    }
    SpanBlock& block = s_.blocks[first];
    block.spans[block.count] = {w.b0, w.b1, index};
    block.lo = std::min(block.lo, w.b0);
    block.hi = std::max(block.hi, w.b1);
    ++block.count;
    push(windowKey(w), index);
  }

  void propagateWindow(int index) {
    // No second pruning here (pruned when added): on a 3.6k-vertex bump re-pruning at the pop would
    // kill 24 of 183k windows for ~10 % of the time. An unpruned window is still a real path, so
    // what it offers and the pruning it feeds stay valid: it only costs its own propagation.
    const Window w = s_.windows[index];
    const int h = w.halfedge;
    const int f = t_.he[h].face;
    const double L = t_.he[h].length;
    const double cx = t_.he[h].oppositeX, cy = t_.he[h].oppositeY;
    const int c = t_.he[h].oppositeVertex;
    const double slack = 1e-9 * L;
    // Where the ray through the opposite vertex crosses the edge.
    const double xc = rayCrossing(w.sx, w.sy, cx, cy);
    bool leftChild = xc > w.b0, rightChild = xc < w.b1;
    if (xc >= w.b0 - slack && xc <= w.b1 + slack) {
      const double dc = w.sigma + planarLength(cx - w.sx, cy - w.sy);
      if (dc > s_.splitDistance[h] * (1.0 + 1e-10)) {
        // One angle, one split (Chen & Han 1990): a shorter path to C already enters this face
        // through this edge at splitCrossing. It and this window's ray to C bound a region; this
        // window's rays on that path's side must cross it and are beaten there, so only the
        // child on the far side can carry shortest paths.
        if (s_.splitCrossing[h] < xc) leftChild = false;
        else rightChild = false;
      } else {
        if (dc < s_.splitDistance[h]) {
          s_.splitDistance[h] = dc;
          s_.splitCrossing[h] = xc;
        }
        relaxVertex(c, dc, {Predecessor::ThroughWindow, index});
      }
    } else {
      // C lies just outside the window: a path bent round the window's end (a valid upper bound),
      // or at the vertex its boundary ray runs through - the only way into the shadow of a
      // near-flat saddle that is not a pseudo-source (see pathBentAt).
      const int side = xc < w.b0 ? 0 : 1;
      bool atVertex;
      const double d = bentDistance(w, side, cx, cy, atVertex);
      relaxVertex(c, d, Predecessor::throughWindow(index, side, atVertex));
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
    // Child on edge A-C (rays left of the opposite vertex), on the halfedge A->C of the next face.
    if (leftChild) {
      const int hca = t_.he[h].prev;
      const int child = t_.twin(hca);
      if (t_.he[child].face >= 0) {
        const double lac = t_.he[hca].length;
        const FrameChange frame{0.0, 0.0, cx / lac, cy / lac};
        Window cw;
        cw.halfedge = child;
        cw.parent = index;
        cw.sigma = w.sigma;
        std::copy_n(w.endVertex, 2, cw.endVertex);
        frame.apply(w.sx, w.sy, cw.sx, cw.sy);
        if (cw.sy < 0.0) {
          double px, py;
          frame.apply(w.b0, 0.0, px, py);
          cw.b0 = (w.b0 == 0.0) ? 0.0 : rayCrossing(cw.sx, cw.sy, px, py);
          if (xc < w.b1) {
            cw.b1 = lac;
          } else {
            frame.apply(w.b1, 0.0, px, py);
            cw.b1 = rayCrossing(cw.sx, cw.sy, px, py);
          }
          cw.b0 = std::clamp(cw.b0, 0.0, lac);
          cw.b1 = std::clamp(cw.b1, 0.0, lac);
          if (cw.b1 > cw.b0) addWindow(cw);
        }
      }
    }
    // Child on edge C-B (rays right of the opposite vertex), on the halfedge C->B of the next face.
    if (rightChild) {
      const int hbc = t_.he[h].next;
      const int child = t_.twin(hbc);
      if (t_.he[child].face >= 0) {
        const double lbc = t_.he[hbc].length;
        const FrameChange frame{cx, cy, (L - cx) / lbc, -cy / lbc};
        Window cw;
        cw.halfedge = child;
        cw.parent = index;
        cw.sigma = w.sigma;
        std::copy_n(w.endVertex, 2, cw.endVertex);
        frame.apply(w.sx, w.sy, cw.sx, cw.sy);
        if (cw.sy < 0.0) {
          double px, py;
          if (xc > w.b0) {
            cw.b0 = 0.0;
          } else {
            frame.apply(w.b0, 0.0, px, py);
            cw.b0 = rayCrossing(cw.sx, cw.sy, px, py);
          }
          frame.apply(w.b1, 0.0, px, py);
          cw.b1 = (w.b1 == L) ? lbc : rayCrossing(cw.sx, cw.sy, px, py);
          cw.b0 = std::clamp(cw.b0, 0.0, lbc);
          cw.b1 = std::clamp(cw.b1, 0.0, lbc);
          if (cw.b1 > cw.b0) addWindow(cw);
        }
      }
    }
  }

  // Vertex paths into the targets' faces: d(v) + |v q| for the three vertices.
  void finishTargets() {
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
};

}  // namespace

void propagate(const MeshTables& tables, const DistanceSolverOptions& options, const SurfacePoint& source,
               const std::vector<SurfacePoint>& targets, Propagation& state, bool directedAtTargets) {
  Propagator(tables, options, state).run(source, targets, directedAtTargets && !targets.empty());
}

}  // namespace egg::geodesic::detail
