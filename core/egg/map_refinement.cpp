#include "core/egg/map_refinement.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace egg {

namespace {

// Up to four nodes of a local cubic in x1: indices into the rows, sorted.
struct Stencil {
  int node[4] = {0, 0, 0, 0};
  int width = 0;
};

// The nodes of the cubic around sample i: the two bracketing it and one more on each side,
// shifted inward at the ends of the side. `nodes` is sorted and i lies strictly between two of
// them.
Stencil stencilAround(const std::vector<int>& nodes, int i) {
  const int count = static_cast<int>(nodes.size());
  const int p =
      static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), i) - nodes.begin()) - 1;
  Stencil s;
  s.width = std::min(4, count);
  const int first = std::clamp(p - 1, 0, count - s.width);
  for (int k = 0; k < s.width; ++k) s.node[k] = nodes[first + k];
  return s;
}

// The cubic through the exact rows of the stencil's nodes, at sample i (Lagrange form on the
// indices).
void evaluate(const Stencil& s, const std::vector<std::vector<double>>& rows, int i,
              std::vector<double>& out) {
  double weights[4];
  for (int k = 0; k < s.width; ++k) {
    double w = 1.0;
    for (int l = 0; l < s.width; ++l)
      if (l != k) w *= static_cast<double>(i - s.node[l]) / (s.node[k] - s.node[l]);
    weights[k] = w;
  }
  const size_t n2 = rows[s.node[0]].size();
  out.assign(n2, 0.0);
  for (int k = 0; k < s.width; ++k) {
    const auto& row = rows[s.node[k]];
    for (size_t j = 0; j < n2; ++j) out[j] += weights[k] * row[j];
  }
}

double largestDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (size_t j = 0; j < a.size(); ++j) {
    const double e = std::abs(a[j] - b[j]);
    if (!std::isfinite(e)) return INFINITY;  // a NaN or inf row must never pass a check
    d = std::max(d, e);
  }
  return d;
}

// A first-round check that misses by more than this many tolerances is "far": a smooth map's miss
// drops ~16x per halving of the node spacing (cubic interpolation, error ~ h^4), so it needs at
// least two more rounds over that interval; a kinked one drops ~2x and ends at adjacent samples.
// Smooth bench maps miss by 1-3x in the first round.
constexpr double kFarMiss = 32.0;

// An interval whose middle check passed: the cubic `checked` (the stencil before m was a node)
// predicted the exact row at m to within the tolerance.
struct Settled {
  int a = 0, m = 0, b = 0;
  Stencil checked;
};

}  // namespace

MapRefinementStats refineMapRows(
    int n1, int n2, double tolerance, int initialNodes,
    const std::function<std::vector<std::vector<double>>(const std::vector<int>&)>& exactRows,
    std::vector<std::vector<double>>& rows) {
  if (n1 < 2 || n2 < 1) throw InvalidInput("refineMapRows: a map needs at least 2 x 1 samples");
  if (initialNodes < 2)
    throw InvalidInput("refineMapRows: initialNodes must be >= 2 (both ends of the side)");
  MapRefinementStats stats;
  rows.assign(n1, {});
  const auto compute = [&](const std::vector<int>& indices) {
    auto computed = exactRows(indices);
    if (computed.size() != indices.size())
      throw InvalidInput("refineMapRows: exactRows must return one row per index");
    for (size_t k = 0; k < indices.size(); ++k) {
      if (computed[k].size() != static_cast<size_t>(n2))
        throw InvalidInput("refineMapRows: a row has " + std::to_string(computed[k].size()) +
                           " values, not " + std::to_string(n2));
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
  for (int k = 0; k < initialNodes; ++k)
    nodes.push_back((k * (n1 - 1) + (initialNodes - 1) / 2) / (initialNodes - 1));
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  compute(nodes);

  std::vector<std::pair<int, int>> intervals;
  for (size_t k = 0; k + 1 < nodes.size(); ++k)
    if (nodes[k + 1] - nodes[k] >= 2) intervals.emplace_back(nodes[k], nodes[k + 1]);
  std::vector<Settled> settled;
  std::vector<double> predicted, filled;
  const auto split = [&](int a, int m, int b, std::vector<std::pair<int, int>>& next) {
    ++stats.refinedIntervals;
    if (m - a >= 2) next.emplace_back(a, m);
    if (b - m >= 2) next.emplace_back(m, b);
  };
  // The fill of a settled interval is the cubic through the nodes around each sample, m among
  // them, which is not the cubic that was checked, and a single check can pass by accident: a
  // kink at a fixed x1 near an end of (a, b) hardly moves the check at m, or its errors cancel
  // there. So at every sample of (a, b) the fill is compared with the checked cubic and with
  // the cubics through the node stencils shifted by one node to each side (no extra fields):
  // on a smooth stretch all of them agree to about the interpolation error, while a kink
  // between the nodes puts three nodes of a shifted stencil on one side of it and one on the
  // other, which moves that cubic by about the slope jump times the node spacing. A difference
  // above the tolerance splits the interval; true when it was split.
  const auto fillDisagrees = [&](const Settled& s, std::vector<std::pair<int, int>>& next) {
    double largest = 0.0;
    const int count = static_cast<int>(nodes.size());
    for (int i = s.a + 1; i < s.b && largest <= tolerance; ++i) {
      if (std::binary_search(nodes.begin(), nodes.end(), i)) continue;
      const Stencil fill = stencilAround(nodes, i);
      evaluate(fill, rows, i, filled);
      evaluate(s.checked, rows, i, predicted);
      largest = std::max(largest, largestDifference(filled, predicted));
      if (count >= 5) {
        const int first = static_cast<int>(
            std::lower_bound(nodes.begin(), nodes.end(), fill.node[0]) - nodes.begin());
        for (int shift : {-1, 1}) {
          const int f = first + shift;
          if (f < 0 || f + 4 > count) continue;
          Stencil shifted;
          shifted.width = 4;
          for (int k = 0; k < 4; ++k) shifted.node[k] = nodes[f + k];
          evaluate(shifted, rows, i, predicted);
          largest = std::max(largest, largestDifference(filled, predicted));
        }
      }
    }
    if (largest <= tolerance) return false;
    split(s.a, s.m, s.b, next);
    return true;
  };

  while (!intervals.empty()) {
    while (!intervals.empty()) {
      ++stats.rounds;
      std::sort(intervals.begin(), intervals.end());  // splits of failed fill comparisons come last
      std::vector<int> middles;
      for (const auto& [a, b] : intervals) middles.push_back((a + b) / 2);
      compute(middles);
      std::vector<std::pair<int, int>> next;
      std::vector<Settled> fresh;
      size_t farMisses = 0;
      for (size_t k = 0; k < intervals.size(); ++k) {
        const auto [a, b] = intervals[k];
        const int m = middles[k];
        const Stencil checked = stencilAround(nodes, m);
        evaluate(checked, rows, m, predicted);
        const double miss = largestDifference(predicted, rows[m]);
        if (miss > kFarMiss * tolerance) ++farMisses;
        if (miss > tolerance) {
          split(a, m, b, next);
        } else {
          stats.largestMissM = std::max(stats.largestMissM, miss);
          fresh.push_back({a, m, b, checked});
        }
      }
      std::vector<int> merged;
      std::merge(nodes.begin(), nodes.end(), middles.begin(), middles.end(),
                 std::back_inserter(merged));
      nodes = std::move(merged);
      // At least 3/4 of the first checks missed far: kinks all along the side (the bench bump of
      // height 2 m, whose maps carry cut-locus kinks before and after smoothing, misses by
      // 48-85x a 1e-3 m tolerance in all 8, and the misses only halve with each halving).
      // Refining on would end at every row anyway, in several sequential batches, so the
      // remaining rows are computed in one. One kink spoils at most 5 of 8 checks (each check's
      // stencil spans three intervals), which stays below the 3/4.
      if (stats.rounds == 1 && 4 * farMisses >= 3 * intervals.size()) {
        std::vector<int> rest;
        for (int i = 0; i < n1; ++i)
          if (!std::binary_search(nodes.begin(), nodes.end(), i)) rest.push_back(i);
        compute(rest);
        ++stats.rounds;
        return stats;
      }
      for (const Settled& s : fresh)
        if (!fillDisagrees(s, next)) settled.push_back(s);
      intervals = std::move(next);
    }
    // Later rounds may have added nodes next to an interval settled earlier, which changes the
    // stencils of its fill: compare again with the final nodes.
    std::vector<Settled> kept;
    for (const Settled& s : settled)
      if (!fillDisagrees(s, intervals)) kept.push_back(s);
    settled = std::move(kept);
  }
  for (int i = 0; i < n1; ++i)
    if (!std::binary_search(nodes.begin(), nodes.end(), i))
      evaluate(stencilAround(nodes, i), rows, i, rows[i]);
  return stats;
}

}  // namespace egg
