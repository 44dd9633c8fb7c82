#pragma once
// The priority queue of the window propagation: a bucket queue (calendar queue) for the monotone,
// Dijkstra-like key sequence of the propagation, with exact (key, item) pop order.
//
// Why: a field pushes and pops hundreds of thousands of windows, and a heap spent a large share of
// the propagation sifting through the wavefront (docs/measurements.md). The keys of the queued
// windows all lie within a few edge lengths of the front, so buckets of width ~ edge/1024 hold a
// handful of entries each: a push is an append and a pop scans the current bucket; should the
// current bucket hold more than a few entries, it becomes a binary heap until it is empty. Entries
// beyond the calendar's horizon wait in an overflow heap. The pop order is exactly (key, item), as
// a heap's, so every bit of the result is the same (unless reset unordered: then only the buckets
// are in order). On a graded mesh (edges much shorter than the mean somewhere) a bucket can hold
// thousands of entries; it then costs what one heap of that size costs, not a linear scan per pop.
// Keys below the current bucket (by rounding in a full field, where a child window never lies
// nearer than its parent; truly lower in a directed one, whose keys are sums of two separate
// minima, goal_bound.hpp) are kept in the current bucket and still pop in key order. Keys must
// not be NaN.
// Fine meshes crowd the buckets, yet neither a narrower width nor one adapting to the crowding was
// faster (docs/measurements.md).
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace egg::geodesic::detail {

class BucketQueue {
 public:
  struct Entry {
    double key;
    int item;
  };

  // Starts empty with buckets of `width` (> 0, finite) beginning at key 0. `unordered`: pop()
  // takes any entry of the earliest bucket (the newest), not the smallest: no scan, no heap; the
  // wavefront engine's halfedges (why that stays exact: wavefront_engine.cpp, runSplitQueues).
  void reset(double width, bool unordered = false) {
    unordered_ = unordered;
    for (auto& b : buckets_) b.clear();
    if (buckets_.size() != kBuckets) buckets_.assign(kBuckets, {});
    overflow_.clear();
    width_ = width;
    inverseWidth_ = 1.0 / width;
    current_ = 0;
    currentIsHeap_ = false;
    bucketed_ = 0;
    peakSize_ = 0;
    prefetchBase_ = nullptr;
  }
  // The most entries held at once since reset() (the queue's share of a field's peak memory).
  std::size_t peakSize() const { return peakSize_; }
  // Records indexed by the (non-negative) items, `stride` bytes apart, to prefetch a bucket ahead
  // of the pops (nullptr: none). Call again whenever the records move. Why: a popped window's
  // record was written long before and is a cache miss on meshes whose front does not fit in
  // cache; one bucket ahead helps there, two was slower (docs/measurements.md). The propagation
  // asks for it in front and wavefront mode (window_propagation.cpp, run; wavefront_engine.cpp,
  // runSplitQueues).
  // `recordOfItem` (if given) maps an item to its record (-1: none), `mapStride` bytes from one
  // item's entry to the next: the wavefront engine
  // queues halfedges, whose first queued window is the record its pop reads first, and its map is
  // the head field of its per-halfedge list records (which reading it brings into cache too).
  void prefetchRecords(const void* base, std::size_t stride, const int* recordOfItem = nullptr,
                       std::size_t mapStride = sizeof(int)) {
    prefetchBase_ = static_cast<const char*>(base);
    prefetchStride_ = stride;
    recordOfItem_ = reinterpret_cast<const char*>(recordOfItem);
    mapStride_ = mapStride;
  }
  bool empty() const { return bucketed_ == 0 && overflow_.empty(); }
  // Unordered only: the item that the (after + 1)-th pop() from now returns if nothing is pushed
  // before it and the current bucket holds it; -1 if the current bucket holds fewer entries. A
  // hint for prefetching the records of the next pops (the calendar is not moved).
  int nextInCurrentBucket(std::size_t after = 0) const {
    if (buckets_.empty()) return -1;  // before reset()
    const auto& bucket = buckets_[current_ & kMask];
    return bucket.size() > after ? bucket[bucket.size() - 1 - after].item : -1;
  }

  // The bucket a key falls in (a key below the calendar's start counts as its first bucket).
  long long bucketOf(double key) const { return bucketIndex(key); }
  static constexpr long long kNoBucket = (1LL << 60) + 1;  // beyond bucketOf(+inf), kFar

  // The earliest non-empty bucket, if it is no later than `limit`; kNoBucket otherwise. The
  // calendar advances to that bucket, or to `limit` at most: entries pushed later with smaller
  // keys land in bucket max(bucket, current), so a caller that still holds events at `limit`
  // must not let the calendar pass it.
  long long earliestBucket(long long limit) {
    for (;;) {
      if (current_ > limit) return kNoBucket;
      if (bucketed_ == 0) {
        if (overflow_.empty()) return kNoBucket;
        const long long next = std::max(current_, bucketIndex(overflow_.front().key));
        if (next > limit) return kNoBucket;
        advanceTo(next);
        continue;
      }
      if (!buckets_[current_ & kMask].empty()) return current_;
      if (current_ >= limit) return kNoBucket;
      advanceTo(current_ + 1);
    }
  }

  [[gnu::always_inline]] inline void push(double key, int item) {
    const long long index = std::max(current_, bucketIndex(key));
    if (index - current_ < static_cast<long long>(kBuckets)) {
      auto& bucket = buckets_[index & kMask];
      bucket.push_back({key, item});
      if (index == current_ && currentIsHeap_)
        std::push_heap(bucket.begin(), bucket.end(), greater);
      ++bucketed_;
    } else {
      overflow_.push_back({key, item});
      std::push_heap(overflow_.begin(), overflow_.end(), greater);
    }
    peakSize_ = std::max(peakSize_, bucketed_ + overflow_.size());
  }

  // Removes and returns the entry with the smallest (key, item). Precondition: !empty().
  Entry pop() {
    for (;;) {
      if (bucketed_ == 0) {
        // Jump the calendar to the earliest waiting entry.
        advanceTo(std::max(current_, bucketIndex(overflow_.front().key)));
        continue;
      }
      auto& bucket = buckets_[current_ & kMask];
      if (!bucket.empty()) {
        --bucketed_;
        if (unordered_) {
          const Entry e = bucket.back();
          bucket.pop_back();
          return e;
        }
        if (!currentIsHeap_ && bucket.size() <= kScanLimit) {
          // The usual case: a handful of entries, a scan is cheaper than heap upkeep.
          std::size_t best = 0;
          for (std::size_t i = 1; i < bucket.size(); ++i) {
            if (less(bucket[i], bucket[best])) best = i;
          }
          const Entry e = bucket[best];
          bucket[best] = bucket.back();
          bucket.pop_back();
          return e;
        }
        if (!currentIsHeap_) {
          std::make_heap(bucket.begin(), bucket.end(), greater);
          currentIsHeap_ = true;
        }
        std::pop_heap(bucket.begin(), bucket.end(), greater);
        const Entry e = bucket.back();
        bucket.pop_back();
        return e;
      }
      advanceTo(current_ + 1);
    }
  }

 private:
  static constexpr std::size_t kBuckets = 4096;  // a power of two
  static constexpr long long kMask = kBuckets - 1;
  static constexpr long long kFar = 1LL << 60;
  static constexpr std::size_t kScanLimit = 16;  // larger current buckets become heaps

 public:
  // The order of entries, (key, item): also the wavefront engine's vertex-event heap's.
  static bool less(const Entry& a, const Entry& b) {
    return a.key < b.key || (a.key == b.key && a.item < b.item);
  }
  // A function object, not a function: the heap algorithms then inline the comparison (through a
  // function pointer it was a call per sift step).
  struct Greater {
    bool operator()(const Entry& a, const Entry& b) const { return less(b, a); }
  };
  static constexpr Greater greater{};

 private:
  // Bucket of `key`, clamped to [0, kFar]: negative keys (never pushed) count as 0, and far keys
  // (+inf included) as kFar, which stays beyond the horizon until the calendar gets there.
  // (Truncation is floor here, the value being positive: no call to floor per push.)
  long long bucketIndex(double key) const {
    const double scaled = key * inverseWidth_;
    if (!(scaled > 0.0)) return 0;
    return scaled < static_cast<double>(kFar) ? static_cast<long long>(scaled) : kFar;
  }

  void advanceTo(long long index) {
    current_ = index;
    currentIsHeap_ = false;
    refillFromOverflow();
    const auto& ahead = buckets_[(current_ + 1) & kMask];
    if (prefetchBase_ && ahead.size() <= kScanLimit) {
      // The next bucket's items are popped soon after this one's: ask for their records now, so
      // their cache misses overlap instead of stalling one pop each. Not for a crowded bucket
      // (a fine mesh's): its hundreds of records would evict each other before their pops.
      for (const Entry& e : ahead) {
        if (e.item < 0) continue;
        const int record = recordOfItem_
                               ? *reinterpret_cast<const int*>(
                                     recordOfItem_ + static_cast<std::size_t>(e.item) * mapStride_)
                               : e.item;
        if (record >= 0)
          __builtin_prefetch(prefetchBase_ + static_cast<std::size_t>(record) * prefetchStride_);
      }
    }
  }

  // Moves the overflow entries that now fall inside the calendar's horizon into their buckets.
  void refillFromOverflow() {
    while (!overflow_.empty()) {
      const long long index = std::max(current_, bucketIndex(overflow_.front().key));
      if (index - current_ >= static_cast<long long>(kBuckets)) break;
      auto& bucket = buckets_[index & kMask];
      bucket.push_back(overflow_.front());
      if (index == current_ && currentIsHeap_)
        std::push_heap(bucket.begin(), bucket.end(), greater);
      ++bucketed_;
      std::pop_heap(overflow_.begin(), overflow_.end(), greater);
      overflow_.pop_back();
    }
  }

  std::vector<std::vector<Entry>> buckets_;
  const char* prefetchBase_ = nullptr;
  std::size_t prefetchStride_ = 0;
  const char* recordOfItem_ = nullptr;
  std::size_t mapStride_ = sizeof(int);
  std::vector<Entry> overflow_;  // min-heap by (key, item)
  double width_ = 1.0, inverseWidth_ = 1.0;
  long long current_ = 0;
  bool currentIsHeap_ = false;  // the current bucket is heap-ordered (by `greater`)
  bool unordered_ = false;
  std::size_t bucketed_ = 0;
  std::size_t peakSize_ = 0;
};

}  // namespace egg::geodesic::detail
