#include "core/egg/map_refinement.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

namespace egg {
namespace {

// A synthetic map d(i, j) on an n1 x n2 grid (x1 = i / (n1 - 1)), with a row oracle that records
// which rows were asked for and in how many batches.
struct Oracle {
  Oracle(int samples1, int samples2, std::function<double(double, double)> map)
      : n1(samples1), n2(samples2), d(std::move(map)) {}
  int n1, n2;
  std::function<double(double, double)> d;
  std::set<int> asked;
  int calls = 0;
  std::vector<std::vector<double>> operator()(const std::vector<int>& indices) {
    ++calls;
    std::vector<std::vector<double>> rows;
    for (int i : indices) {
      EXPECT_TRUE(asked.insert(i).second) << "row " << i << " computed twice";
      std::vector<double> row;
      for (int j = 0; j < n2; ++j)
        row.push_back(d(static_cast<double>(i) / (n1 - 1), static_cast<double>(j) / (n2 - 1)));
      rows.push_back(row);
    }
    return rows;
  }
  double largestError(const std::vector<std::vector<double>>& rows) const {
    double e = 0.0;
    for (int i = 0; i < n1; ++i)
      for (int j = 0; j < n2; ++j)
        e = std::max(e, std::abs(rows[i][j] - d(static_cast<double>(i) / (n1 - 1),
                                                static_cast<double>(j) / (n2 - 1))));
    return e;
  }
};

MapRefinementStats refine(Oracle& oracle, double tolerance, int initialNodes,
                          std::vector<std::vector<double>>& rows) {
  return refineMapRows(
      oracle.n1, oracle.n2, tolerance, initialNodes,
      [&](const std::vector<int>& indices) { return oracle(indices); }, rows);
}

TEST(MapRefinement, CubicRowsAreReproducedFromTheInitialNodesAndOneCheckRound) {
  // A cubic in x1 is its own local cubic interpolant: every check passes at once, so 9 initial
  // nodes + 8 checks are all the exact rows needed for 100 samples.
  Oracle oracle{100, 30, [](double x1, double x2) {
                  return (1.0 + x2) * (0.3 + 1.2 * x1 - 0.7 * x1 * x1 + 0.25 * x1 * x1 * x1);
                }};
  std::vector<std::vector<double>> rows;
  const auto stats = refine(oracle, 1e-9, 9, rows);
  EXPECT_EQ(stats.exactRows, 17);
  EXPECT_EQ(stats.rounds, 1);
  EXPECT_EQ(stats.refinedIntervals, 0);
  EXPECT_EQ(oracle.calls, 2);
  EXPECT_LT(oracle.largestError(rows), 1e-12);
  EXPECT_LT(stats.largestMissM, 1e-12);
  EXPECT_TRUE(oracle.asked.count(0) && oracle.asked.count(99));  // both ends are nodes
}

TEST(MapRefinement, ZeroToleranceComputesEveryRowInOneBatch) {
  Oracle oracle{40, 5, [](double x1, double x2) { return std::exp(x1) + x2; }};
  std::vector<std::vector<double>> rows;
  const auto stats = refine(oracle, 0.0, 9, rows);
  EXPECT_EQ(stats.exactRows, 40);
  EXPECT_EQ(stats.rounds, 0);
  EXPECT_EQ(oracle.calls, 1);
  EXPECT_EQ(oracle.largestError(rows), 0.0);
  // More initial nodes than samples: also every row, exactly.
  Oracle small{5, 5, oracle.d};
  EXPECT_EQ(refine(small, 1e-3, 9, rows).exactRows, 5);
  EXPECT_EQ(small.largestError(rows), 0.0);
}

TEST(MapRefinement, SmoothRowsMeetTheToleranceWithFewFields) {
  // The planar distance between points on two opposite sides of a unit square: smooth, not cubic.
  Oracle oracle{100, 100, [](double x1, double x2) { return std::hypot(1.0, x2 - x1); }};
  std::vector<std::vector<double>> rows;
  const auto stats = refine(oracle, 1e-5, 9, rows);
  EXPECT_LE(oracle.largestError(rows), 1e-5);
  EXPECT_LT(stats.exactRows, 40);
  EXPECT_GT(stats.exactRows, 17);  // 1e-5 is not met from 9 nodes: some intervals were refined
  EXPECT_GT(stats.refinedIntervals, 0);
  // All 8 first checks miss here, but by less than 32x the tolerance: no switch to every row.
  EXPECT_EQ(stats.rounds, 2);
}

TEST(MapRefinement, AKinkAtAFixedX1IsFoundWhereverItLies) {
  // A kink at the same x1 for every x2 (slope jump 0.2), swept over the side. A single middle
  // check misses it when it lies near an end of the interval or when the errors cancel at the
  // middle (k = 0.91036: the check of (87, 99) at 93 passed, rows 88-98 were filled 18x off);
  // the stencil comparison must catch every position: each row within the tolerance of the
  // truth (rows computed exactly are the truth), with few exact rows.
  const double tolerance = 1e-4;
  int worstRows = 0;
  double worstRatio = 0.0;
  for (int t = 0; t <= 1000; ++t) {
    const double k = t == 1000 ? 0.91036 : 0.05 + 0.9 * t / 999.0;
    Oracle oracle{
        100, 3, [k](double x1, double x2) { return 3.0 + x2 + 0.5 * x1 + 0.1 * std::abs(x1 - k); }};
    std::vector<std::vector<double>> rows;
    const auto stats = refine(oracle, tolerance, 9, rows);
    worstRatio = std::max(worstRatio, oracle.largestError(rows) / tolerance);
    worstRows = std::max(worstRows, stats.exactRows);
    ASSERT_LE(oracle.largestError(rows), tolerance) << "kink at x1 = " << k;
  }
  EXPECT_LT(worstRows, 50);  // 34 measured: the rows next to the kink, not the whole side
  EXPECT_LE(worstRatio, 1.0);
}

TEST(MapRefinement, MostFarMissesInTheFirstRoundComputeTheRestInOneBatch) {
  // Kinks every ~8 samples (|sin| in x1): the first checks miss by far more than 32x the
  // tolerance, so after the first round the remaining rows come in one batch (3 calls in all)
  // instead of halving down to adjacent samples round after round.
  Oracle oracle{100, 10, [](double x1, double x2) {
                  return 2.0 + x2 + 0.05 * std::abs(std::sin(40.0 * x1 + x2));
                }};
  std::vector<std::vector<double>> rows;
  const auto stats = refine(oracle, 1e-5, 9, rows);
  EXPECT_EQ(oracle.calls, 3);
  EXPECT_EQ(stats.rounds, 2);
  EXPECT_EQ(stats.exactRows, 100);
  EXPECT_EQ(oracle.largestError(rows), 0.0);
}

TEST(MapRefinement, AKinkIsRefinedDownToAdjacentSamples) {
  // A geodesic bending around a non-convex boundary point puts a kink into D(., x2): here at
  // x1 = 0.37 + 0.1 x2, with a slope jump of 1. Away from it the rows are linear in x1.
  Oracle oracle{100, 20, [](double x1, double x2) {
                  return 2.0 + 0.5 * x1 + std::abs(x1 - 0.37 - 0.1 * x2) + x2;
                }};
  std::vector<std::vector<double>> rows;
  const double tolerance = 1e-6;
  const auto stats = refine(oracle, tolerance, 9, rows);
  EXPECT_GT(stats.refinedIntervals, 0);
  EXPECT_GE(stats.rounds, 3);
  // The kink sweeps samples 37..47 over x2: every sample there is computed exactly.
  for (int i = 37; i <= 47; ++i) EXPECT_TRUE(oracle.asked.count(i)) << "sample " << i;
  // Far from the kink the rows are linear and no refinement happened: few exact rows in all.
  EXPECT_LT(stats.exactRows, 50);
  EXPECT_FALSE(oracle.asked.count(5));
  EXPECT_FALSE(oracle.asked.count(90));
  EXPECT_LE(oracle.largestError(rows), tolerance);
}

TEST(MapRefinement, BadArgumentsAreRejected) {
  std::vector<std::vector<double>> rows;
  const auto good = [](const std::vector<int>& indices) {
    return std::vector<std::vector<double>>(indices.size(), std::vector<double>(4, 1.0));
  };
  EXPECT_THROW(refineMapRows(1, 4, 1e-6, 9, good, rows), InvalidInput);
  EXPECT_THROW(refineMapRows(10, 4, 1e-6, 1, good, rows), InvalidInput);
  const auto shortRows = [](const std::vector<int>& indices) {
    return std::vector<std::vector<double>>(indices.size(), std::vector<double>(3, 1.0));
  };
  EXPECT_THROW(refineMapRows(10, 4, 1e-6, 3, shortRows, rows), InvalidInput);
  const auto missingRows = [](const std::vector<int>&) {
    return std::vector<std::vector<double>>{};
  };
  EXPECT_THROW(refineMapRows(10, 4, 1e-6, 3, missingRows, rows), InvalidInput);
}

}  // namespace
}  // namespace egg
