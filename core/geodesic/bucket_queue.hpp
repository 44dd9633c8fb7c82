#pragma once
// The priority queue of the window propagation: a bucket queue (calendar queue) for the monotone,
// Dijkstra-like key sequence of the propagation, with exact (key, item) pop order.
//
// Why: a 4k-vertex field pushes and pops ~200k windows, and a heap spent about 300 instructions
// per pop (30 % of the propagation) sifting through the ~2k-entry wavefront. The keys of the queued
// windows all lie within a few edge lengths of the front, so buckets of width ~ edge/256 hold a
// handful of entries each: a push is an append, a pop scans one small bucket. Entries beyond the
// calendar's horizon wait in an overflow heap. Within a bucket the entry with the smallest
// (key, item) is taken, so the pop order - and every bit of the result - is the same as a heap's.
// Keys below the current bucket (only by rounding, since a child window never lies nearer than
// its parent) are kept in the current bucket and still pop in key order.
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

  // Starts empty with buckets of `width` (> 0) beginning at key 0.
  void reset(double width) {
    for (auto& b : buckets_) b.clear();
    if (buckets_.size() != kBuckets) buckets_.assign(kBuckets, {});
    overflow_.clear();
    width_ = width;
    inverseWidth_ = 1.0 / width;
    current_ = 0;
    bucketed_ = 0;
  }
  bool empty() const { return bucketed_ == 0 && overflow_.empty(); }

  void push(double key, int item) {
    const long long index = std::max(current_, bucketIndex(key));
    if (index - current_ < static_cast<long long>(kBuckets)) {
      buckets_[index & kMask].push_back({key, item});
      ++bucketed_;
    } else {
      overflow_.push_back({key, item});
      std::push_heap(overflow_.begin(), overflow_.end(), greater);
    }
  }

  // Removes and returns the entry with the smallest (key, item). Precondition: !empty().
  Entry pop() {
    for (;;) {
      if (bucketed_ == 0) {
        // Jump the calendar to the earliest waiting entry.
        current_ = std::max(current_, bucketIndex(overflow_.front().key));
        refillFromOverflow();
        continue;
      }
      auto& bucket = buckets_[current_ & kMask];
      if (!bucket.empty()) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < bucket.size(); ++i) {
          if (less(bucket[i], bucket[best])) best = i;
        }
        const Entry e = bucket[best];
        bucket[best] = bucket.back();
        bucket.pop_back();
        --bucketed_;
        return e;
      }
      ++current_;
      refillFromOverflow();
    }
  }

 private:
  static constexpr std::size_t kBuckets = 1024;  // a power of two
  static constexpr long long kMask = kBuckets - 1;

  static bool less(const Entry& a, const Entry& b) { return a.key < b.key || (a.key == b.key && a.item < b.item); }
  static bool greater(const Entry& a, const Entry& b) { return less(b, a); }

  long long bucketIndex(double key) const {
    const double scaled = std::floor(key * inverseWidth_);
    // Far keys (and +inf, which the propagation never pushes) stay beyond the horizon.
    return scaled < 1e15 ? static_cast<long long>(scaled) : static_cast<long long>(1e15);
  }

  // Moves the overflow entries that now fall inside the calendar's horizon into their buckets.
  void refillFromOverflow() {
    while (!overflow_.empty()) {
      const long long index = std::max(current_, bucketIndex(overflow_.front().key));
      if (index - current_ >= static_cast<long long>(kBuckets)) break;
      buckets_[index & kMask].push_back(overflow_.front());
      ++bucketed_;
      std::pop_heap(overflow_.begin(), overflow_.end(), greater);
      overflow_.pop_back();
    }
  }

  std::vector<std::vector<Entry>> buckets_;
  std::vector<Entry> overflow_;  // min-heap by (key, item)
  double width_ = 1.0, inverseWidth_ = 1.0;
  long long current_ = 0;
  std::size_t bucketed_ = 0;
};

}  // namespace egg::geodesic::detail
