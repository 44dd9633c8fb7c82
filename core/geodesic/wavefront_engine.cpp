// The wavefront engine (DistanceSolverOptions::Engine::Wavefront, issue 19), after VTP (Qin et al.
// 2016): no queue entry per window. The queued windows of a halfedge wait in one first-in-first-
// out list through the slots, the bucket queue holds halfedges keyed by the smallest key of their
// windows, and popping a halfedge propagates all of its windows across its face in one batch; their
// children join the lists of the face's two other edges. A new window is trimmed (both ways) and
// merged against the first two windows of its edge's list only, in constant time as VTP's local
// pruning (addWavefrontWindow: why two). The rest (pruning against the edge's endpoints, one angle
// one split, pseudo-source firing, saddle skipping, targets) is the front engine's
// (window_propagation.cpp).
//
// Why a batch keeps pseudo-sources exact: a halfedge pops at the smallest key of its windows, and a
// window's children and everything it offers lie no nearer than that key, so when a vertex event
// pops at d(v), every window still to be propagated lies at d(v) or beyond and cannot shorten d(v)
// (as in Dijkstra); a window propagated early (it shares its halfedge with a nearer one) offers
// only real paths: upper bounds, which the later windows improve on. Keys in a batch are therefore
// out of order, which only changes how much trimming finds (the numbers: window_propagation.cpp).
// A full field goes one step further (runSplitQueues): halfedges are popped in any order within
// buckets one mean edge wide, and vertex events wait in a heap of their own until no halfedge is
// queued in their bucket or before it; directed queries keep the exact order of one queue.
#include "core/geodesic/face_crossing.hpp"
#include "core/geodesic/propagator.hpp"
#include "core/geodesic/window_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace egg::geodesic::detail {

// Takes `slot` (after `previous`, -1 if first) out of halfedge h's list and frees it.
void Propagator::unlinkWavefrontSlot(int h, int slot, int previous) {
  const int next = s_.slots[slot].next;
  auto& list = s_.lists[h];
  if (previous >= 0)
    s_.slots[previous].next = next;
  else
    list.head = next;
  if (list.tail == slot) list.tail = previous;
  s_.freeSlots.push_back(slot);
}

// As addFrontWindow, but against the first windows of the edge's list only: a new window is pruned
// against its edge's endpoints, merged with a queued window of the same source image it touches,
// and trimmed both ways against the others (either of a pair may die); it then joins the end of
// the edge's list, and the edge is queued anew only if the window's key is below its queued key.
// Inline in the batch loop (propagateHalfedge): the crossing, the pruning and this compile into one
// function, with no call, spill or reload of the propagation's state per child (4.6k cap of issue
// 19: 80.7M -> 74.8M instructions per field, callgrind; distances bit-identical).
[[gnu::always_inline]] inline void Propagator::insertWavefrontWindow(Window& w) {
  double b0In = w.b0, b1In = w.b1;
  double endLengths[2];
  if (!prune(w, endLengths)) return;
  const double prunedB0 = w.b0, prunedB1 = w.b1;
  const int h = w.halfedge;
  const auto& e = t_.he[h];
  const double minWidth = o_.minWindowWidthRelative * e.length;
  const double same = 1e-9 * e.length;
  // A full field merges near images too (DistanceSolverOptions::imageMergeTolerance); directed
  // queries stay exact, so distance() agrees with the paths traced through stored windows.
  const double merge = s_.splitQueues ? o_.imageMergeTolerance : 0.0;
  // Only the first kCompared windows of the list (the oldest queued) are compared with: constant
  // time per window, as VTP's neighbour checks. Trimming less keeps more windows, every one a real
  // path, so the distances do not change (exact mode: equal to the full walk's), only the work.
  // Measured (thread CPU per field, interleaved with the full walk, 3 vertex sources): 4.6k cap
  // 0.66 of the full walk's time at 2 (192k windows against 180k), 18k cap 0.55 at 2 (1.25M against
  // 1.18M), 0.75 at 4; 4.4k bump 0.82 at 2 (148k against 141k); plane unchanged (merging still
  // finds its partner). 1 was no faster than 2 and kept more windows.
  constexpr int kCompared = 2;
  int compared = 0;
restart:
  for (int slot = s_.lists[h].head, previous = -1; slot >= 0 && compared < kCompared; ++compared) {
    Window& other = s_.slots[slot].window;
    const int next = s_.slots[slot].next;
    const bool touches = std::min(w.b1, other.b1) + same >= std::max(w.b0, other.b0);
    if (!touches) {
      previous = slot;
      slot = next;
      continue;
    }
    if (sameSourceImage(other, w, same)) {
      absorbSameImage(w, other, b0In, b1In);
      unlinkWavefrontSlot(h, slot, previous);
      goto restart;  // w has grown: windows it missed may overlap it now
    }
    if (merge > 0.0 && absorbNearImage(w, other, merge, e.length, b0In, b1In)) {
      unlinkWavefrontSlot(h, slot, previous);
      ++s_.nearImagesMerged;
      goto restart;
    }
    if (std::min(w.b1, other.b1) > std::max(w.b0, other.b0)) {
      const double o0 = other.b0, o1 = other.b1;
      bool wLeft, otherLeft;
      trimPair(w, other, wLeft, otherLeft);
      if (!wLeft || w.b1 - w.b0 <= minWidth) return;
      if (!otherLeft || other.b1 - other.b0 <= minWidth) {
        unlinkWavefrontSlot(h, slot, previous);
        slot = next;
        continue;
      }
      if (other.b0 != o0 || other.b1 != o1) markEndVertices(other, o0, o1, e);
    }
    previous = slot;
    slot = next;
  }
  markEndVertices(w, b0In, b1In, e);
  int slot;
  if (!s_.freeSlots.empty()) {
    slot = s_.freeSlots.back();
    s_.freeSlots.pop_back();
    copyJustWritten(s_.slots[slot].window, w);
  } else {
    slot = static_cast<int>(s_.slots.size());
    s_.slots.emplace_back();
    copyJustWritten(s_.slots[slot].window, w);
  }
  s_.slots[slot].next = -1;
  auto& list = s_.lists[h];
  if (list.tail >= 0)
    s_.slots[list.tail].next = slot;
  else
    list.head = slot;
  list.tail = slot;
  ++s_.windowsCreated;
  // Untrimmed since pruning (the usual case), the key reuses prune's end lengths: two square roots
  // fewer per window.
  const double key = w.b0 == prunedB0 && w.b1 == prunedB1 ? windowKey(w, endLengths) : windowKey(w);
  // A full field (splitQueues) pops a bucket's halfedges in any order, so h is queued anew only if
  // the window moves it to an earlier bucket (runSplitQueues); otherwise whenever its key drops.
  // 18k-vertex cap: 74k entries for 59k batches (with the exact order: 256k for 54k).
  if (s_.splitQueues ? s_.queue.bucketOf(key) < s_.queue.bucketOf(list.key) : key < list.key) {
    // The earlier entry of h (larger key) goes stale: it no longer matches list.key when popped.
    list.key = key;
    push(key, h);
  }
}

void Propagator::addWavefrontWindow(Window& w) { insertWavefrontWindow(w); }

// A full field pops the newest halfedge of its bucket first (runSplitQueues), so the next two
// batches are known while this one runs, unless it queues a halfedge into the same bucket. A batch
// starts by reading its halfedge's record and those of the face's two other edges (faceCrossing),
// the one-split record, the opposite vertex's distance, and the two children's list records: on
// the 18k-vertex cap of issue 19, records scattered over 110k halfedges, half of the simulated
// second-level misses were faceCrossing's alone. They are asked for here, one batch ahead (the
// record of the batch after it two ahead, as its fields lead to the others). Interleaved runs
// (warm fields, medians of 5 x 11): 18k cap 0.94, 4.6k cap 0.96 of the time before; distances
// bit-identical. Inline on purpose: as a call of its own it gained nothing (18k cap 0.53 of VTP's
// time before and after), the call costing the batch loop what the prefetches saved.
[[gnu::always_inline]] inline void Propagator::prefetchNextBatches() const {
  const int second = s_.queue.nextInCurrentBucket(1);
  if (second >= 0) __builtin_prefetch(&t_.he[second]);
  const int next = s_.queue.nextInCurrentBucket(0);
  if (next < 0) return;
  const auto& e = t_.he[next];
  if (e.face < 0) return;  // never queued; this only keeps the indices below in range
  const int left = t_.twin(e.prev), right = t_.twin(e.next);
  __builtin_prefetch(&t_.he[left]);
  __builtin_prefetch(&t_.he[right]);
  __builtin_prefetch(&s_.split[next]);
  __builtin_prefetch(&s_.vertexDistance[e.oppositeVertex]);
  __builtin_prefetch(&s_.lists[left]);
  __builtin_prefetch(&s_.lists[right]);
}

// A popped halfedge: all its windows cross its face, in the order they arrived. A stale entry (a
// smaller key was pushed for h since, or h has been propagated since) is skipped.
void Propagator::propagateHalfedge(int h, double key) {
  auto& list = s_.lists[h];
  if (list.key != key) return;
  int slot = list.head;
  list = {kInfinity, -1, -1};
  ++s_.halfedgePops;
  if (s_.splitQueues) prefetchNextBatches();
  const FaceCrossing face =
      faceCrossing(h);  // once per batch: the child frames divide once, not per window
  // The children go to other halfedges (the face's other two edges, seen from their far side), so
  // the detached list is not touched while it is walked; each slot is freed once its window has
  // crossed the face.
  while (slot >= 0) {
    const Window w = s_.slots[slot].window;  // children may move the slots (a new one at the end)
    const int next = s_.slots[slot].next;
    if (next >= 0) __builtin_prefetch(&s_.slots[next]);  // its cache miss overlaps this crossing
    crossFace(w, slot, face, [this](Window& child) { insertWavefrontWindow(child); });
    s_.freeSlots.push_back(slot);
    slot = next;
  }
}

// The vertex events: a heap by the queue's own (key, item) order, smallest on top.
void Propagator::pushVertexEvent(double key, int item) {
  s_.vertexEvents.push_back({key, item});
  std::push_heap(s_.vertexEvents.begin(), s_.vertexEvents.end(), BucketQueue::greater);
  s_.vertexEventsPeak = std::max(s_.vertexEventsPeak, s_.vertexEvents.size());
}

BucketQueue::Entry Propagator::popVertexEvent() {
  std::pop_heap(s_.vertexEvents.begin(), s_.vertexEvents.end(), BucketQueue::greater);
  const BucketQueue::Entry e = s_.vertexEvents.back();
  s_.vertexEvents.pop_back();
  return e;
}

// A full field: halfedges in the bucket queue, popped in any order within a bucket (no scan for
// the smallest key, and a halfedge whose key drops within its bucket is not queued again), vertex
// events in a heap of their own. Exact as the single queue is, for the reason batches are
// (propagateHalfedge): a vertex event fires only once no halfedge is queued in its bucket or an
// earlier one. Every window still to be propagated then has a key at or beyond the event's bucket;
// those in the same bucket were all propagated first, and their children lie no nearer than they
// (in a full field a child's key is never below its parent's), so nothing left can shorten d(v).
// The calendar is never advanced past the earliest vertex event (earliestBucket's limit), so a
// window queued after the event still lands in its own bucket, not a later one.
void Propagator::runSplitQueues() {
  for (;;) {
    s_.queue.prefetchRecords(s_.slots.data(), sizeof(Propagation::Slot), &s_.lists.data()->head,
                             sizeof(Propagation::EdgeList));
    const long long eventBucket = s_.vertexEvents.empty()
                                      ? BucketQueue::kNoBucket
                                      : s_.queue.bucketOf(s_.vertexEvents.front().key);
    if (s_.queue.earliestBucket(eventBucket) != BucketQueue::kNoBucket) {
      const auto entry = s_.queue.pop();
      propagateHalfedge(entry.item, entry.key);
      continue;
    }
    if (s_.vertexEvents.empty()) return;
    const int v = -popVertexEvent().item - 1;
    if (!s_.fired[v]) fire(v);  // else a stale event: a later, no larger key for v popped first
  }
}

}  // namespace egg::geodesic::detail
