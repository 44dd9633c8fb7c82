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
//  * Two engines (DistanceSolverOptions::Engine). Stored windows: every window stays in one array
//    (paths trace back through it) and a new one is trimmed against all earlier windows on its
//    edge. Front only (after VTP, Qin et al. 2016): a window's slot is freed once it has crossed
//    its face, and a new window is trimmed against the queued windows of its edge, both ways
//    (addFrontWindow), and queued windows of one source image that touch are merged into one (on
//    a plane: windows ~n instead of ~n^1.5; bench plane, 17k vertices: 65k windows against 956k,
//    0.06 of the stored engine's time; on the bump and the caps one image's pieces differ by more
//    than rounding, so nothing merges there and the time is unchanged). The same dominated parts go, found in a different order: the distances
//    agree to rounding (1.5e-11 on the bench bump), the memory is the front's, not the windows'
//    (53 MB against 3.6 GB at 418k triangles). Time: within +-10 % up to 18k vertices, 0.55-1.02
//    of the stored engine's at 418k triangles (DistanceSolverOptions::engine).
//  * Wavefront (wavefront_engine.cpp, after VTP's triangle-oriented propagation): the front
//    engine's windows, queued per halfedge in first-in-first-out lists with one queue entry per
//    halfedge, propagated a halfedge's batch at a time, and trimmed against the first two windows
//    of their edge's list only (constant time; the cap's profile had the front engine's trimming
//    walk and its queue at half the time). More windows (+6 % on the 18k cap), each much cheaper:
//    0.4-0.6 of the stored engine's time on the bump and caps, exact mode unchanged (numbers:
//    DistanceSolverOptions::engine).
// A strictly dominated part never carries a shortest path, so the result is the exact polyhedral
// distance (to rounding) when every saddle is a pseudo-source (saddleAngleTolerance = 0) and no
// near images merge (DistanceSolverOptions::exact()); by default near-flat saddles are bent at
// instead (pathBentAt): 2-3x faster, 8e-6 at worst; and full wavefront fields merge windows of
// near images (imageMergeTolerance: 0.6x the windows of an 18k-vertex cap, 1.2e-7).
// Targets: every window entering a target's face offers sigma + |s q| if its ray to q crosses
// it, every vertex v of the face d(v) + |v q| at the end; paths are traced back through
// Window::parent. A directed query queues by d + chord to the targets and stops once they are
// final (goal_bound.hpp); a stale vertex event is recognised by its vertex having fired.
#include "core/geodesic/propagator.hpp"
#include "core/geodesic/window_geometry.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace egg::geodesic::detail {

void Propagator::run(const SurfacePoint& source, const std::vector<SurfacePoint>& targets, bool directed) {
  s_.splitQueues = s_.wavefront && !directed;
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
  if (s_.splitQueues) {
    runSplitQueues();
    finishTargets();
    return;
  }
  while (!s_.queue.empty()) {
    // Front and wavefront mode: their slots are a small pool (the wavefront queues halfedges,
    // whose record is the first window of the list); prefetching into the stored engine's array
    // made the 418k-triangle bump's stored field 1.2x slower (51 s against 40-42 s, twice each).
    if (s_.wavefront) {
      s_.queue.prefetchRecords(s_.slots.data(), sizeof(Propagation::Slot), &s_.lists.data()->head,
                               sizeof(Propagation::EdgeList));
    } else if (!s_.storeWindows) {
      s_.queue.prefetchRecords(s_.windows.data(), sizeof(Window));
    }
    const auto entry = s_.queue.pop();
    if (goal_.active() && entry.key >= directed_.farthestBound(t_, s_)) break;  // targets final
    if (entry.item < 0) {
      const int v = -entry.item - 1;
      if (s_.fired[v]) continue;  // a stale event: a later, no larger key for v popped first
      fire(v);
    } else if (s_.storeWindows) {
      const Window w = s_.windows[entry.item];  // its children may move the array
      propagateWindow(w, entry.item, faceCrossing(w.halfedge));
    } else if (s_.wavefront) {
      propagateHalfedge(entry.item, entry.key);
    } else if (takeFrontWindow(entry.item)) {
      const Window w = s_.windows[entry.item];
      propagateWindow(w, entry.item, faceCrossing(w.halfedge));
      s_.freeSlots.push_back(entry.item);
    }
  }
  finishTargets();
}

double Propagator::windowKey(const Window& w) const { return keyOfNearest(w, windowMinDistance(w)); }

double Propagator::windowKey(const Window& w, const double* endLengths) const {
  return keyOfNearest(w, windowMinDistance(w, endLengths[0], endLengths[1]));
}

double Propagator::keyOfNearest(const Window& w, double nearest) const {
  if (!goal_.active()) return nearest;
  const auto& e = t_.he[w.halfedge];
  return nearest + goal_.toSegment(t_.positions[e.fromVertex], t_.positions[e.toVertex], w.b0 / e.length,
                                   w.b1 / e.length);
}

// Trims the parts of `w` dominated by the paths through the endpoints of its edge. Returns false
// if nothing is left.
bool Propagator::prune(Window& w, double* endLengths) const {
  const int h = w.halfedge;
  const double L = t_.he[h].length;
  const double dA = s_.vertexDistance[t_.he[h].fromVertex];
  const double dB = s_.vertexDistance[t_.he[h].toVertex];
  // |s - b0| and |s - b1|, recomputed only when an end moves: every test below needs them and
  // the square roots were the bulk of this function.
  // The window was just written field by field (propagateWindow): its fields are read one by
  // one (loadAlone). Perf samples of the 18k cap: prune 9.1-9.4 % of the run before, 7.2 % after.
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
  // killed 0 and 264 of 185k windows on a 3.6k-vertex bump (397, 930 of 15M on the Great Court)
  // for a lookup and two square roots per window; one-split and trimming do that work already.
  // Nor would any vertex filter (VTP's per-triangle pruning included) help where this engine is
  // slowest, the sphere caps of issue 19: even against the final distances of all four vertices
  // of the edge's two faces, 0 of the 191k windows kept at 4.6k vertices (stored engine) and 0 of
  // 1.02M at 18k (front engine) are beaten everywhere, 16 of 159k on the bench bump; the cap's
  // windows are its exact field's, and only cheaper windows make it faster (test_window_
  // propagation.cpp, WindowPruning). Switched off, this pruning changes the windows kept there by 2.
  return true;
}

// A path to (px, py) (frame of w's edge, in the face w enters) whose ray from the source image
// misses the window past end `side`, bent round that end or at the vertex on its boundary ray
// (window_geometry.hpp: why that makes skipping near-flat saddles accurate).
double Propagator::bentDistance(const Window& w, int side, double px, double py, bool& atVertex) const {
  const int x = w.endVertex[side];
  const BendVertex vertex{x >= 0 ? s_.vertexDistance[x] : 0.0, x >= 0 ? t_.shadowCone[x] : 0.0};
  return pathBentAt(w, side, px, py, t_.he[w.halfedge].length, x >= 0 ? &vertex : nullptr, atVertex);
}

void Propagator::addWindow(Window& w) {
  if (s_.storeWindows) addStoredWindow(w);
  else if (s_.wavefront) addWavefrontWindow(w);
  else addFrontWindow(w);
}

void Propagator::addStoredWindow(Window& w) {
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
  ++s_.windowsCreated;
  push(windowKey(w), index);
}

// Front mode: a new window meets only the queued windows of its halfedge (the propagated ones are
// gone), kept as spans in blocks as in stored mode: a walk over a halfedge's live windows reads a
// few contiguous lines, where a list through the window slots cost a cache miss per window (a
// third of the time at 100k vertices). Each overlapping pair is trimmed both ways - the part of
// either where the other is shorter carries no shortest path (Mitchell-Mount-Papadimitriou's
// overlap rule; VTP lets either of a pair die) - and a queued window trimmed to nothing loses its
// span (slotSpan -1): its queue entry is skipped when popped, and its slot freed then. A queued
// window's key stays its old, smaller minimum: a lower bound still, so it pops a little early,
// which changes no distance.
//
// Merging: a queued window with the same source image and sigma (to 1e-9 of the edge length) that
// overlaps or touches the new one carries the same distance function sigma + |s - x|, so the two
// are one window: the new one takes over the union and the queued one dies. On a plane every
// window splits at each vertex its rays pass and, unmerged, the pieces never join again: an edge
// at r edges from the source then holds ~r windows (n^1.5 in all, measured); merged, ~1. Exact:
// the union's rays are the two windows' rays. Front mode only: the stored engine's paths trace
// back through Window::parent, which a merged window has two of (paths always use stored mode).
void Propagator::addFrontWindow(Window& w) {
  double b0In = w.b0, b1In = w.b1;
  if (!prune(w)) return;
  const int h = w.halfedge;
  const auto& e = t_.he[h];
  const double minWidth = o_.minWindowWidthRelative * e.length;
  const double same = 1e-9 * e.length;
restart:
  for (int b = s_.firstBlock[h]; b >= 0;) {
    auto& block = s_.blocks[b];
    const int next = block.next;
    if (std::min(w.b1, block.hi) + same >= std::max(w.b0, block.lo)) {
      for (int k = 0; k < block.count; ++k) {
        auto& span = block.spans[k];
        if (span.window < 0) continue;  // a cleared span
        Window& other = s_.windows[span.window];
        if (std::min(w.b1, span.b1) + same >= std::max(w.b0, span.b0) && sameSourceImage(other, w, same)) {
          absorbSameImage(w, other, b0In, b1In);
          clearSpan(span.window);  // may recycle this block
          goto restart;  // w has grown: spans it missed may overlap it now
        }
        if (!(std::min(w.b1, span.b1) > std::max(w.b0, span.b0))) continue;  // disjoint
        const double o0 = other.b0, o1 = other.b1;
        bool wLeft, otherLeft;
        trimPair(w, other, wLeft, otherLeft);
        if (!wLeft || w.b1 - w.b0 <= minWidth) return;
        if (!otherLeft || other.b1 - other.b0 <= minWidth) {
          clearSpan(span.window);  // may recycle this block: its spans are all cleared then
        } else if (other.b0 != o0 || other.b1 != o1) {
          markEndVertices(other, o0, o1, e);
          span.b0 = other.b0;
          span.b1 = other.b1;
        }
      }
    }
    b = next;
  }
  markEndVertices(w, b0In, b1In, e);
  int slot;
  if (s_.freeHead < s_.freeSlots.size()) {
    // First freed, first reused: windows pop in about the order they were queued, so the slots
    // are then read in about the order they were written, as in the stored engine's array (a
    // stack of free slots scatters the reads; the two were within the bench's noise, +-10 %).
    slot = s_.freeSlots[s_.freeHead++];
    if (s_.freeHead > 4096 && 2 * s_.freeHead > s_.freeSlots.size()) {
      s_.freeSlots.erase(s_.freeSlots.begin(), s_.freeSlots.begin() + static_cast<std::ptrdiff_t>(s_.freeHead));
      s_.freeHead = 0;
    }
    s_.windows[slot] = w;
  } else {
    slot = static_cast<int>(s_.windows.size());
    s_.windows.push_back(w);
    s_.slotSpan.push_back(-1);
  }
  using SpanBlock = Propagation::SpanBlock;
  int first = s_.firstBlock[h];
  if (first < 0 || s_.blocks[first].count == SpanBlock::kCapacity) {
    int b;
    if (!s_.freeBlocks.empty()) {
      b = s_.freeBlocks.back();
      s_.freeBlocks.pop_back();
    } else {
      b = static_cast<int>(s_.blocks.size());
      s_.blocks.emplace_back();
      s_.blockLive.push_back(0);
      s_.blockPrev.push_back(-1);
    }
    SpanBlock& block = s_.blocks[b];
    block.lo = kInfinity;
    block.hi = -kInfinity;
    block.count = 0;
    block.next = first;
    s_.blockLive[b] = 0;
    s_.blockPrev[b] = -1;
    if (first >= 0) s_.blockPrev[first] = b;
    s_.firstBlock[h] = first = b;
  }
  SpanBlock& block = s_.blocks[first];
  s_.slotSpan[slot] = (first << 3) | block.count;
  block.spans[block.count] = {w.b0, w.b1, slot};
  block.lo = std::min(block.lo, w.b0);
  block.hi = std::max(block.hi, w.b1);
  ++block.count;
  ++s_.blockLive[first];
  ++s_.windowsCreated;
  push(windowKey(w), slot);
}

// Front mode: takes a window off its halfedge's spans; a block left without live spans goes back
// to the pool at once, so the blocks stay O(front) too.
void Propagator::clearSpan(int slot) {
  const unsigned ref = static_cast<unsigned>(s_.slotSpan[slot]);
  s_.slotSpan[slot] = -1;
  const int b = static_cast<int>(ref >> 3);
  auto& block = s_.blocks[b];
  block.spans[ref & 7] = {kInfinity, -kInfinity, -1};
  if (--s_.blockLive[b] > 0) return;
  const int prev = s_.blockPrev[b], next = block.next;
  if (prev >= 0) s_.blocks[prev].next = next;
  else s_.firstBlock[s_.windows[slot].halfedge] = next;
  if (next >= 0) s_.blockPrev[next] = prev;
  s_.freeBlocks.push_back(b);
}

// Front mode, a window taken from the queue: off its halfedge's spans. False if it was trimmed
// away while queued. Either way its slot is free once the window has crossed its face.
// (Re-pruning here against the edge's endpoints, whose distances may have dropped since the
// window was queued, killed 41 of 158k windows on the 4.4k bench bump, 0 on the plane, for two
// square roots per window: left out, as in stored mode.)
bool Propagator::takeFrontWindow(int slot) {
  if (s_.slotSpan[slot] >= 0) {
    clearSpan(slot);
    return true;
  }
  s_.freeSlots.push_back(slot);
  return false;
}

Propagator::FaceCrossing Propagator::faceCrossing(int h) const {
  const auto& e = t_.he[h];
  FaceCrossing face{h, e.face, e.oppositeVertex, e.length, e.oppositeX, e.oppositeY, -1, -1, 0.0, 0.0, {}, {}};
  const int left = t_.twin(e.prev), right = t_.twin(e.next);
  if (t_.he[left].face >= 0) {
    face.leftChild = left;
    face.leftLength = t_.he[left].length;  // = |A C| bit for bit
    face.leftFrame = {0.0, 0.0, face.cx / face.leftLength, face.cy / face.leftLength};
  }
  if (t_.he[right].face >= 0) {
    face.rightChild = right;
    face.rightLength = t_.he[right].length;
    face.rightFrame = {face.cx, face.cy, (face.length - face.cx) / face.rightLength, -face.cy / face.rightLength};
  }
  return face;
}

void Propagator::propagateWindow(const Window& w, int index, const FaceCrossing& face) {
  // No second pruning here (pruned when added): on a 3.6k-vertex bump re-pruning at the pop would
  // kill 24 of 183k windows for ~10 % of the time. An unpruned window is still a real path, so
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
      if (split.crossing < xc) leftChild = false;
      else rightChild = false;
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
    // tenth of the propagation's mispredictions (cachegrind --branch-sim, 18k cap, no cones).
    // With the face's data read once per batch (faceCrossing), interleaved runs on the 18k cap:
    // 0.88-0.98 of the earlier time (medians of 25-40 runs each); the 4.5k meshes within noise.
    const char bendsAtX = t_.hasShadowCone[x >= 0 ? x : 0];
    if ((x >= 0) & (bendsAtX != 0)) {
      bool atVertex;
      const double d = bentDistance(w, side, cx, cy, atVertex);
      relaxVertex(c, d, Predecessor::throughWindow(index, side, atVertex), &w);
    } else {
      // Round the end (bentDistance's value here): sigma + |s - end| + |end - C|, where
      // |end - C| >= cy. Most of these paths improve nothing (18k cap of issue 19: C lies outside
      // 98 % of the windows and 90 % of those bends were refused), so the second square root
      // waits for the bound; its margin, far above rounding, means a spared relaxation would
      // have been refused: the distances are bit-identical. Instructions per field (cachegrind):
      // 18k cap -6.7 %, 4.6k cap -6.2 %, 4.4k bump -1.0 %.
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
  // Child on edge A-C (rays left of the opposite vertex), on the halfedge A->C of the next face.
  if (leftChild && face.leftChild >= 0) {
    const double lac = face.leftLength;
    const FrameChange& frame = face.leftFrame;
    Window cw;
    cw.halfedge = face.leftChild;
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
  // Child on edge C-B (rays right of the opposite vertex), on the halfedge C->B of the next face.
  if (rightChild && face.rightChild >= 0) {
    const double lbc = face.rightLength;
    const FrameChange& frame = face.rightFrame;
    Window cw;
    cw.halfedge = face.rightChild;
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

void propagate(const MeshTables& tables, const DistanceSolverOptions& options, const SurfacePoint& source,
               const std::vector<SurfacePoint>& targets, Propagation& state, bool directedAtTargets,
               bool storeWindows, bool wavefront) {
  state.storeWindows = storeWindows;
  state.wavefront = wavefront && !storeWindows;
  Propagator(tables, options, state).run(source, targets, directedAtTargets && !targets.empty());
}

}  // namespace egg::geodesic::detail
