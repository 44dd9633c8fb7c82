// Single-source geodesic distances on a triangle mesh by window propagation (exact, or within
// 1e-5).
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
//  * Each window is pruned once, when it is added (see Propagator::crossFace, face_crossing.hpp).
//  * Two engines (DistanceSolverOptions::Engine). Stored windows: every window stays in one array
//    (paths trace back through it) and a new one is trimmed against all earlier windows on its
//    edge. Front only (after VTP, Qin et al. 2016): a window's slot is freed once it has crossed
//    its face, and a new window is trimmed against the queued windows of its edge, both ways
//    (addFrontWindow), and queued windows of one source image that touch are merged into one (on
//    a plane: windows ~n instead of ~n^1.5; bench plane, 17k vertices: 65k windows against 956k,
//    0.06 of the stored engine's time; on the bump and the caps one image's pieces differ by more
//    than rounding, so nothing merges there and the time is unchanged). The same dominated parts
//    go, found in a different order: the distances agree to rounding (1.5e-11 on the bench bump),
//    the memory is the front's, not the windows' (53 MB against 3.6 GB at 418k triangles). Time:
//    within +-10 % up to 18k vertices, 0.55-1.02 of the stored engine's at 418k triangles
//    (DistanceSolverOptions::engine).
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
#include "core/geodesic/face_crossing.hpp"
#include "core/geodesic/propagator.hpp"
#include "core/geodesic/window_geometry.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>

namespace egg::geodesic::detail {

void Propagator::run(const SurfacePoint& source, const std::vector<SurfacePoint>& targets,
                     bool directed) {
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

double Propagator::windowKey(const Window& w) const {
  return keyOfNearest(w, windowMinDistance(w));
}

double Propagator::windowKey(const Window& w, const double* endLengths) const {
  return keyOfNearest(w, windowMinDistance(w, endLengths[0], endLengths[1]));
}

double Propagator::keyOfNearest(const Window& w, double nearest) const {
  if (!goal_.active()) return nearest;
  const auto& e = t_.he[w.halfedge];
  return nearest + goal_.toSegment(t_.positions[e.fromVertex], t_.positions[e.toVertex],
                                   w.b0 / e.length, w.b1 / e.length);
}

// A path to (px, py) (frame of w's edge, in the face w enters) whose ray from the source image
// misses the window past end `side`, bent round that end or at the vertex on its boundary ray
// (window_geometry.hpp: why that makes skipping near-flat saddles accurate).
double Propagator::bentDistance(const Window& w, int side, double px, double py,
                                bool& atVertex) const {
  const int x = w.endVertex[side];
  const BendVertex vertex{x >= 0 ? s_.vertexDistance[x] : 0.0, x >= 0 ? t_.shadowCone[x] : 0.0};
  return pathBentAt(w, side, px, py, t_.he[w.halfedge].length, x >= 0 ? &vertex : nullptr,
                    atVertex);
}

void Propagator::addWindow(Window& w) {
  if (s_.storeWindows)
    addStoredWindow(w);
  else if (s_.wavefront)
    addWavefrontWindow(w);
  else
    addFrontWindow(w);
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
      if (!(std::min(w.b1, span.b1) > std::max(w.b0, span.b0)))
        continue;  // disjoint: nothing to trim
      if (!trimAgainst(w, s_.windows[span.window]) || w.b1 - w.b0 <= o_.minWindowWidthRelative * L)
        return;
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
        if (std::min(w.b1, span.b1) + same >= std::max(w.b0, span.b0) &&
            sameSourceImage(other, w, same)) {
          absorbSameImage(w, other, b0In, b1In);
          clearSpan(span.window);  // may recycle this block
          goto restart;            // w has grown: spans it missed may overlap it now
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
      s_.freeSlots.erase(s_.freeSlots.begin(),
                         s_.freeSlots.begin() + static_cast<std::ptrdiff_t>(s_.freeHead));
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
  if (prev >= 0)
    s_.blocks[prev].next = next;
  else
    s_.firstBlock[s_.windows[slot].halfedge] = next;
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
  FaceCrossing face{
      h, e.face, e.oppositeVertex, e.length, e.oppositeX, e.oppositeY, -1, -1, 0.0, 0.0, {}, {}};
  const int left = t_.twin(e.prev), right = t_.twin(e.next);
  if (t_.he[left].face >= 0) {
    face.leftChild = left;
    face.leftLength = t_.he[left].length;  // = |A C| bit for bit
    face.leftFrame = {0.0, 0.0, face.cx / face.leftLength, face.cy / face.leftLength};
  }
  if (t_.he[right].face >= 0) {
    face.rightChild = right;
    face.rightLength = t_.he[right].length;
    face.rightFrame = {face.cx, face.cy, (face.length - face.cx) / face.rightLength,
                       -face.cy / face.rightLength};
  }
  return face;
}

// The stored and front engines, one window at a time (the wavefront engine batches:
// propagateHalfedge).
void Propagator::propagateWindow(const Window& w, int index, const FaceCrossing& face) {
  crossFace(w, index, face, [this](Window& child) { addWindow(child); });
}

void propagate(const MeshTables& tables, const DistanceSolverOptions& options,
               const SurfacePoint& source, const std::vector<SurfacePoint>& targets,
               Propagation& state, bool directedAtTargets, bool storeWindows, bool wavefront) {
  state.storeWindows = storeWindows;
  state.wavefront = wavefront && !storeWindows;
  Propagator(tables, options, state).run(source, targets, directedAtTargets && !targets.empty());
}

}  // namespace egg::geodesic::detail
