// The propagation's bucket queue must pop in exactly the (key, item) order of a heap: across bucket
// boundaries, beyond the calendar's horizon (overflow), for equal keys, for keys pushed below the
// front (rounding in the propagation), for crowded buckets (graded meshes) and for +inf. Unordered
// (the wavefront engine's halfedges): every entry once, buckets in order, and earliestBucket never
// takes the calendar past its limit.
#include "core/geodesic/bucket_queue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <utility>
#include <vector>

namespace egg::geodesic::detail {
namespace {

using Pair = std::pair<double, int>;
using Reference = std::priority_queue<Pair, std::vector<Pair>, std::greater<>>;

// Dijkstra-like use, mirrored into std::priority_queue: every pop is compared with the reference.
// Each pop pushes two children at or above the popped key, and now and then one just below it.
// Returns the number of pops.
int compareWithHeap(double width, double spread, double belowFront, int seed) {
  std::mt19937 rng(seed);
  BucketQueue queue;
  queue.reset(width);
  Reference reference;
  auto push = [&](double key, int item) {
    queue.push(key, item);
    reference.push({key, item});
  };
  std::uniform_real_distribution<double> initial(0.0, 100.0), step(0.0, spread), unit(0.0, 1.0);
  int item = 0;
  for (; item < 300; ++item) push(initial(rng), item);
  push(5.0, item++);
  push(5.0, item++);  // a tie, broken by the item
  push(std::numeric_limits<double>::infinity(), item++);
  int pops = 0;
  while (!reference.empty()) {
    EXPECT_FALSE(queue.empty());
    const auto e = queue.pop();
    const Pair expected = reference.top();
    reference.pop();
    EXPECT_EQ(e.key, expected.first) << "pop " << pops;
    EXPECT_EQ(e.item, expected.second) << "pop " << pops;
    if (e.key != expected.first || e.item != expected.second) return -1;
    ++pops;
    if (item < 5000 && std::isfinite(e.key)) {
      push(e.key + step(rng), item++);
      push(e.key + step(rng), item++);
      if (unit(rng) < 0.2) push(e.key - belowFront * unit(rng), item++);
    }
  }
  EXPECT_TRUE(queue.empty());
  return pops;
}

TEST(BucketQueue, PopsInHeapOrderAcrossBucketsOverflowTiesAndInfinity) {
  // Width 0.01: horizon 10.24, so the initial keys up to 100 start in the overflow.
  EXPECT_GE(compareWithHeap(0.01, 30.0, 0.0, 7), 5000);
}

TEST(BucketQueue, KeysBelowTheFrontStillPopInKeyOrder) {
  // Keys up to 3 widths below the last pop land in lower buckets than the current one.
  EXPECT_GE(compareWithHeap(0.01, 0.5, 0.03, 11), 5000);
}

TEST(BucketQueue, CrowdedBucketsOfAGradedMeshKeepTheOrder) {
  // Width 10 with keys spread over 0.5: thousands of entries share one bucket.
  EXPECT_GE(compareWithHeap(10.0, 0.5, 0.001, 13), 5000);
}

TEST(BucketQueue, PopJustAcrossABucketBoundaryThenPushBelowIt) {
  BucketQueue queue;
  queue.reset(1.0);
  queue.push(5.0000001, 1);
  queue.push(7.0, 2);
  EXPECT_EQ(queue.pop().item, 1);
  queue.push(4.9999999, 3);  // bucket 4, below the current bucket 5
  queue.push(6.0, 4);
  EXPECT_EQ(queue.pop().item, 3);
  EXPECT_EQ(queue.pop().item, 4);
  EXPECT_EQ(queue.pop().item, 2);
  EXPECT_TRUE(queue.empty());
  queue.push(1.0, 5);
  queue.reset(1.0);
  EXPECT_TRUE(queue.empty());
}

TEST(BucketQueue, PeakSizeCountsTheMostEntriesHeldAtOnceInBucketsAndOverflow) {
  BucketQueue queue;
  queue.reset(1.0);
  queue.push(3.0, 0);
  queue.push(1e9, 1);  // beyond the calendar: the overflow heap
  queue.push(2.0, 2);
  EXPECT_EQ(queue.peakSize(), 3u);
  EXPECT_EQ(queue.pop().item, 2);
  queue.push(4.0, 3);  // three again, not four
  EXPECT_EQ(queue.peakSize(), 3u);
  queue.push(5.0, 4);
  EXPECT_EQ(queue.peakSize(), 4u);
  while (!queue.empty()) queue.pop();
  EXPECT_EQ(queue.peakSize(), 4u);
  queue.reset(1.0);
  EXPECT_EQ(queue.peakSize(), 0u);
}

// The wavefront engine prefetches through a map from items (halfedges) to records (their first
// queued window, -1 for an empty list): the pop order is the heap's, and no record is touched for
// an item mapped to -1 or a vertex event (negative item). Under the sanitizer build a read through
// -1 (before the records) or past them would fail this test.
// The map is a plain int array, or a field of a per-item record (the wavefront engine's lists):
// under ASan a read of the map past its items (a wrong stride) fails.
void popsInOrderWithAPrefetchMap(bool mapInRecords) {
  std::vector<double> records(4, 0.0);
  std::vector<int> recordOfItem(64);
  struct ListRecord {
    double key;
    int head, tail;
  };
  std::vector<ListRecord> lists(64);
  for (int i = 0; i < 64; ++i) recordOfItem[i] = lists[i].head = i % 3 == 0 ? -1 : i % 4;
  BucketQueue queue;
  queue.reset(0.5);
  if (mapInRecords)
    queue.prefetchRecords(records.data(), sizeof(double), &lists.data()->head, sizeof(ListRecord));
  else
    queue.prefetchRecords(records.data(), sizeof(double), recordOfItem.data());
  Reference reference;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> key(0.0, 40.0);
  for (int i = 0; i < 64; ++i) {
    const double k = key(rng);
    const int item = i % 5 == 0 ? -i - 1 : i;  // some vertex events
    queue.push(k, item);
    reference.push({k, item});
  }
  while (!reference.empty()) {
    ASSERT_FALSE(queue.empty());
    const auto e = queue.pop();
    EXPECT_EQ(e.key, reference.top().first);
    EXPECT_EQ(e.item, reference.top().second);
    reference.pop();
  }
  EXPECT_TRUE(queue.empty());
}

TEST(BucketQueue, UnorderedPopsEveryEntryOnceWithTheBucketsInOrder) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> key(0.0, 300.0), step(0.0, 3.0);
  BucketQueue queue;
  const double width = 1.0;
  queue.reset(width, /*unordered=*/true);
  std::vector<int> pushed(20000, 0), popped(20000, 0);
  int next = 0;
  for (; next < 400; ++next) {
    queue.push(key(rng), next);  // some beyond the horizon (4096 buckets of 1): the overflow heap
    ++pushed[next];
  }
  queue.push(1e5, next);  // far beyond
  ++pushed[next++];
  long long lastBucket = 0;
  while (!queue.empty()) {
    const long long bucket = queue.earliestBucket(BucketQueue::kNoBucket);
    ASSERT_NE(bucket, BucketQueue::kNoBucket);
    const int announced = queue.nextInCurrentBucket();
    const auto e = queue.pop();
    ASSERT_EQ(e.item, announced);
    ASSERT_LE(queue.bucketOf(e.key), bucket) << "popped from a later bucket than announced";
    EXPECT_GE(bucket, lastBucket);  // children never lie below their parent here
    lastBucket = bucket;
    ++popped[e.item];
    if (next + 2 < static_cast<int>(pushed.size()) && e.key < 250.0) {
      for (int c = 0; c < 2; ++c, ++next) {
        queue.push(e.key + step(rng), next);
        ++pushed[next];
      }
    }
  }
  EXPECT_GT(next, 10000);
  EXPECT_EQ(popped, pushed);
}

TEST(BucketQueue, EarliestBucketStopsAtItsLimitSoLaterPushesKeepTheirBucket) {
  BucketQueue queue;
  queue.reset(1.0, /*unordered=*/true);
  queue.push(5.5, 1);
  queue.push(9.5, 2);
  EXPECT_EQ(queue.earliestBucket(7), 5);
  EXPECT_EQ(queue.pop().item, 1);
  // Nothing up to 7: the calendar waits at 7, so a key in bucket 6 pushed now still pops before 9.
  EXPECT_EQ(queue.earliestBucket(7), BucketQueue::kNoBucket);
  queue.push(6.5, 3);
  EXPECT_EQ(queue.earliestBucket(6), BucketQueue::kNoBucket);  // the calendar is at 7 already
  EXPECT_EQ(queue.earliestBucket(7), 7);                       // 6.5 waits in the current bucket
  EXPECT_EQ(queue.pop().item, 3);
  EXPECT_EQ(queue.earliestBucket(8), BucketQueue::kNoBucket);
  EXPECT_EQ(queue.earliestBucket(BucketQueue::kNoBucket), 9);
  EXPECT_EQ(queue.pop().item, 2);
  EXPECT_TRUE(queue.empty());
  EXPECT_EQ(queue.earliestBucket(BucketQueue::kNoBucket), BucketQueue::kNoBucket);
  EXPECT_LT(queue.bucketOf(std::numeric_limits<double>::infinity()), BucketQueue::kNoBucket);
}

// The wavefront engine prefetches the records of the next two batches by these announcements
// (wavefront_engine.cpp, prefetchNextBatches): they must name what pop() returns next.
TEST(BucketQueue, NextInCurrentBucketAnnouncesTheUnorderedPops) {
  BucketQueue queue;
  queue.reset(1.0, /*unordered=*/true);
  queue.push(2.2, 7);
  queue.push(2.7, 8);
  queue.push(2.5, 9);
  queue.push(3.1, 10);
  EXPECT_EQ(queue.nextInCurrentBucket(), -1);  // the calendar is still at bucket 0
  EXPECT_EQ(queue.earliestBucket(BucketQueue::kNoBucket), 2);
  EXPECT_EQ(queue.nextInCurrentBucket(0), 9);  // the newest first
  EXPECT_EQ(queue.nextInCurrentBucket(1), 8);
  EXPECT_EQ(queue.nextInCurrentBucket(2), 7);
  EXPECT_EQ(queue.nextInCurrentBucket(3), -1);
  EXPECT_EQ(queue.pop().item, 9);
  EXPECT_EQ(queue.nextInCurrentBucket(), 8);
  queue.push(2.9, 11);  // into the current bucket: it is next now
  EXPECT_EQ(queue.nextInCurrentBucket(0), 11);
  EXPECT_EQ(queue.nextInCurrentBucket(1), 8);
  for (const int item : {11, 8, 7}) EXPECT_EQ(queue.pop().item, item);
  EXPECT_EQ(queue.nextInCurrentBucket(), -1);  // bucket 2 is empty and the calendar has not moved
  EXPECT_EQ(queue.earliestBucket(BucketQueue::kNoBucket), 3);
  EXPECT_EQ(queue.nextInCurrentBucket(), 10);
  EXPECT_EQ(queue.pop().item, 10);
  EXPECT_TRUE(queue.empty());
}

TEST(BucketQueue, PrefetchThroughAnItemToRecordMapKeepsTheOrderAndSkipsItemsWithoutARecord) {
  popsInOrderWithAPrefetchMap(false);
  popsInOrderWithAPrefetchMap(true);
}

}  // namespace
}  // namespace egg::geodesic::detail
