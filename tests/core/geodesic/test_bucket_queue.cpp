// The propagation's bucket queue must pop in exactly the (key, item) order of a heap, across bucket
// boundaries, beyond the calendar's horizon (overflow) and for equal keys.
#include "core/geodesic/bucket_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

namespace egg::geodesic::detail {
namespace {

using Pair = std::pair<double, int>;

// Dijkstra-like use: pops interleaved with pushes whose keys are never below the last pop.
std::vector<Pair> popAllMonotone(BucketQueue& queue, std::vector<Pair> initial, std::mt19937& rng, double spread) {
  for (const auto& [k, i] : initial) queue.push(k, i);
  std::vector<Pair> popped;
  std::uniform_real_distribution<double> step(0.0, spread);
  int nextItem = 1000000;
  while (!queue.empty()) {
    const auto e = queue.pop();
    popped.push_back({e.key, e.item});
    if (popped.size() < 3000) {
      for (int c = 0; c < 2; ++c) queue.push(e.key + step(rng), nextItem++);
    }
  }
  return popped;
}

TEST(BucketQueue, PopsInKeyThenItemOrderAcrossBucketsAndOverflow) {
  std::mt19937 rng(7);
  BucketQueue queue;
  queue.reset(0.01);  // horizon 1024 * 0.01 = 10.24: keys up to 100 start in the overflow
  std::uniform_real_distribution<double> key(0.0, 100.0);
  std::vector<Pair> initial;
  for (int i = 0; i < 500; ++i) initial.push_back({key(rng), i});
  initial.push_back({initial[3].first, 9999});  // a tie, broken by the item
  const auto popped = popAllMonotone(queue, initial, rng, 30.0);
  ASSERT_GT(popped.size(), 3000u);
  for (size_t i = 1; i < popped.size(); ++i) {
    ASSERT_LE(popped[i - 1], popped[i]) << "at pop " << i;
  }
}

TEST(BucketQueue, SameSequenceAsASortOfAllPushesWithoutInterleaving) {
  std::mt19937 rng(11);
  BucketQueue queue;
  queue.reset(0.5);
  std::vector<Pair> all;
  std::uniform_real_distribution<double> key(0.0, 2000.0);
  for (int i = 0; i < 2000; ++i) all.push_back({i % 7 == 0 ? 3.0 : key(rng), i});  // many equal keys
  for (const auto& [k, i] : all) queue.push(k, i);
  std::sort(all.begin(), all.end());
  for (const auto& expected : all) {
    ASSERT_FALSE(queue.empty());
    const auto e = queue.pop();
    EXPECT_EQ(e.key, expected.first);
    EXPECT_EQ(e.item, expected.second);
  }
  EXPECT_TRUE(queue.empty());
}

TEST(BucketQueue, KeyJustBelowTheFrontStillPopsNextAndResetEmpties) {
  BucketQueue queue;
  queue.reset(1.0);
  queue.push(5.5, 1);
  queue.push(7.0, 2);
  EXPECT_EQ(queue.pop().item, 1);
  queue.push(5.4999999999, 3);  // below the last pop (rounding in the propagation)
  EXPECT_EQ(queue.pop().item, 3);
  EXPECT_EQ(queue.pop().item, 2);
  EXPECT_TRUE(queue.empty());
  queue.push(1.0, 4);
  queue.reset(1.0);
  EXPECT_TRUE(queue.empty());
}

}  // namespace
}  // namespace egg::geodesic::detail
