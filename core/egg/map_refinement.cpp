#include "core/egg/map_refinement.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace egg {

namespace {

// The cubic in x1 through the exact rows at up to four nodes around sample i (the two bracketing
// it and one more on each side, shifted inward at the ends of the side), in Lagrange form on the
// sample indices. `nodes` is sorted and i lies strictly between two of them.
void interpolateRow(const std::vector<int>& nodes, const std::vector<std::vector<double>>& rows, int i,
                    std::vector<double>& out) {
  const int count = static_cast<int>(nodes.size());
  const int p = static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), i) - nodes.begin()) - 1;
  const int width = std::min(4, count);
  const int first = std::clamp(p - 1, 0, count - width);
  double weights[4];
  for (int k = 0; k < width; ++k) {
    double w = 1.0;
    for (int l = 0; l < width; ++l)
      if (l != k) w *= static_cast<double>(i - nodes[first + l]) / (nodes[first + k] - nodes[first + l]);
    weights[k] = w;
  }
  const size_t n2 = rows[nodes[first]].size();
  out.assign(n2, 0.0);
  for (int k = 0; k < width; ++k) {
    const auto& row = rows[nodes[first + k]];
    for (size_t j = 0; j < n2; ++j) out[j] += weights[k] * row[j];
  }
}

}  // namespace

MapRefinementStats refineMapRows(int n1, int n2, double tolerance, int initialNodes,
                                 const std::function<std::vector<std::vector<double>>(const std::vector<int>&)>& exactRows,
                                 std::vector<std::vector<double>>& rows) {
  if (n1 < 2 || n2 < 1) throw InvalidInput("refineMapRows: a map needs at least 2 x 1 samples");
  if (initialNodes < 2) throw InvalidInput("refineMapRows: initialNodes must be >= 2 (both ends of the side)");
  MapRefinementStats stats;
  rows.assign(n1, {});
  const auto compute = [&](const std::vector<int>& indices) {
    auto computed = exactRows(indices);
    if (computed.size() != indices.size()) throw InvalidInput("refineMapRows: exactRows must return one row per index");
    for (size_t k = 0; k < indices.size(); ++k) {
      if (computed[k].size() != static_cast<size_t>(n2))
        throw InvalidInput("refineMapRows: a row has " + std::to_string(computed[k].size()) + " values, not " + std::to_string(n2));
      rows[indices[k]] = std::move(computed[k]);
    }
    stats.exactRows += static_cast<int>(indices.size());
  };

  std::vector<int> nodes;
  if (!(tolerance > 0.0) || initialNodes >= n1) {
    for (int i = 0; i < n1; ++i) nodes.push_back(i);
    compute(nodes);
    return stats;
  }
  for (int k = 0; k < initialNodes; ++k) nodes.push_back((k * (n1 - 1) + (initialNodes - 1) / 2) / (initialNodes - 1));
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  compute(nodes);

  std::vector<std::pair<int, int>> intervals;
  for (size_t k = 0; k + 1 < nodes.size(); ++k)
    if (nodes[k + 1] - nodes[k] >= 2) intervals.emplace_back(nodes[k], nodes[k + 1]);
  std::vector<double> predicted;
  while (!intervals.empty()) {
    ++stats.rounds;
    std::vector<int> middles;
    for (const auto& [a, b] : intervals) middles.push_back((a + b) / 2);
    compute(middles);
    std::vector<std::pair<int, int>> next;
    for (size_t k = 0; k < intervals.size(); ++k) {
      const auto [a, b] = intervals[k];
      const int m = middles[k];
      interpolateRow(nodes, rows, m, predicted);
      double miss = 0.0;
      for (int j = 0; j < n2; ++j) miss = std::max(miss, std::abs(predicted[j] - rows[m][j]));
      if (miss > tolerance || !std::isfinite(miss)) {
        ++stats.refinedIntervals;
        if (m - a >= 2) next.emplace_back(a, m);
        if (b - m >= 2) next.emplace_back(m, b);
      } else {
        stats.largestMissM = std::max(stats.largestMissM, miss);
      }
    }
    std::vector<int> merged;
    std::merge(nodes.begin(), nodes.end(), middles.begin(), middles.end(), std::back_inserter(merged));
    nodes = std::move(merged);
    intervals = std::move(next);
  }
  size_t p = 0;
  for (int i = 0; i < n1; ++i) {
    if (p < nodes.size() && nodes[p] == i) {
      ++p;
      continue;
    }
    interpolateRow(nodes, rows, i, rows[i]);
  }
  return stats;
}

}  // namespace egg
