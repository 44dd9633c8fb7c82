// Designing a layout's patches and Workflow 1 (see workflow1.hpp).
#include "patching/workflow1.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

namespace egg::patching {

void LayoutDesignOptions::validate() const {
  design.validate();
  layout.validate();
  if (maxSplits < 0) throw InvalidInput("patching.max_splits must be >= 0");
  if (!(minSideM >= 0.0)) throw InvalidInput("patching.min_patch_size_m must be >= 0");
}

namespace {

DesignedPatch evaluate(const PatchLayout& layout, int p, const LayoutDesignOptions& options) {
  DesignedPatch out;
  try {
    out.cut = cutLayoutPatch(layout, p, options.layout);
  } catch (const InfeasiblePatch& e) {
    out.failure = std::string("infeasible: ") + e.what();
    return out;
  }
  try {
    out.design = designPatch(out.cut->patch, options.design);
    if (!out.design->feasible) out.failure = "infeasible: " + out.design->failure.message;
  } catch (const InfeasiblePatch& e) {
    out.failure = std::string("infeasible: ") + e.what();
  } catch (const SolverFailure& e) {
    out.failure = std::string("solver failure: ") + e.what();
  }
  return out;
}

int curveOfSide(const PatchLayout& layout, int p, int k) {
  return layout.segments[layout.patchSides[p][k].front().first].curve;
}

// A corner on side k of patch p at the point of the side nearest to `point`, kept clear of the
// side's ends (a tenth of the side) so that no sliver patch appears; an existing corner of the
// curve close to it (2 % of the side) is reused.
int cornerOnSide(PatchLayout& layout, int p, int k, const Eigen::Vector3d& point,
                 std::set<int>& changedCurves) {
  const int curve = curveOfSide(layout, p, k);
  const int a = layout.patches[p][k], b = layout.patches[p][(k + 1) % 4];
  const double sa = nearestArcLength(layout, curve, layout.corners[a]),
               sb = nearestArcLength(layout, curve, layout.corners[b]);
  const double lo = std::min(sa, sb), hi = std::max(sa, sb), margin = 0.1 * (hi - lo);
  const double s = std::clamp(nearestArcLength(layout, curve, point), lo + margin, hi - margin);
  for (int c : layout.curves[curve].corners) {
    if (c == a || c == b) continue;
    const double sc = nearestArcLength(layout, curve, layout.corners[c]);
    if (sc > lo && sc < hi && std::abs(sc - s) <= 0.02 * (hi - lo)) return c;
  }
  changedCurves.insert(curve);
  return addCornerOnCurve(layout, curve, s);
}

double sideDistance(const Patch& patch, int k, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int v : patch.sides[k])
    best = std::min(best, (toEigen(patch.mesh.point(TriMesh::VertexHandle(v))) - p).norm());
  return best;
}

// Splits patch p by a new side between the start and end sides of `family` through the two
// points (each is moved to the nearest point of its side). Returns the two children.
std::vector<int> splitAlong(PatchLayout& layout, const geodesic::DistanceSolver& solver, int p,
                            Family family, const Patch& patch, Eigen::Vector3d first,
                            Eigen::Vector3d second, const LayoutOptions& options,
                            std::set<int>& changed) {
  const int startSide = familySide(family, false).first, endSide = familySide(family, true).first;
  if (sideDistance(patch, startSide, first) + sideDistance(patch, endSide, second) >
      sideDistance(patch, startSide, second) + sideDistance(patch, endSide, first))
    std::swap(first, second);
  const auto c = layout.patches[p];
  const int x = cornerOnSide(layout, p, startSide, first, changed);
  const int y = cornerOnSide(layout, p, endSide, second, changed);
  addCurve(layout, solver, x, y, options);
  const size_t n = layout.patches.size();
  if (family == Family::U) {  // x on side 3 (c3 -> c0), y on side 1 (c1 -> c2)
    layout.patches.push_back({c[0], c[1], y, x});
    layout.patches.push_back({x, y, c[2], c[3]});
  } else {  // x on side 0 (c0 -> c1), y on side 2 (c2 -> c3)
    layout.patches.push_back({c[0], x, y, c[3]});
    layout.patches.push_back({x, c[1], c[2], y});
  }
  return {static_cast<int>(n), static_cast<int>(n + 1)};
}

// Splits patch p by a corner at `peak` with sides to the nearest points of its four sides.
std::vector<int> splitAtCorner(PatchLayout& layout, const geodesic::DistanceSolver& solver, int p,
                               const Eigen::Vector3d& peak, const LayoutOptions& options,
                               std::set<int>& changed) {
  const auto c = layout.patches[p];
  std::array<int, 4> x{};
  for (int k = 0; k < 4; ++k) x[k] = cornerOnSide(layout, p, k, peak, changed);
  const int m = addCorner(layout, geodesic::snapToSurface(*layout.surface, peak));
  for (int k = 0; k < 4; ++k) addCurve(layout, solver, m, x[k], options);
  const size_t n = layout.patches.size();
  layout.patches.push_back({c[0], x[0], m, x[3]});
  layout.patches.push_back({x[0], c[1], x[1], m});
  layout.patches.push_back({m, x[1], c[2], x[2]});
  layout.patches.push_back({x[3], m, x[2], c[3]});
  return {static_cast<int>(n), static_cast<int>(n + 1), static_cast<int>(n + 2),
          static_cast<int>(n + 3)};
}

const char* familyName(Family f) { return f == Family::U ? "u" : "v"; }

}  // namespace

LayoutDesign designLayout(PatchLayout layout, const geodesic::DistanceSolver& solver,
                          const LayoutDesignOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  LayoutDesign out;
  const double minSide =
      options.minSideM > 0.0 ? options.minSideM : 2.5 * meanEdgeLength(*layout.surface);
  std::vector<char> alive(layout.patches.size(), 1);
  std::vector<std::optional<DesignedPatch>> designed(layout.patches.size());
  std::vector<int> dirty(layout.patches.size());
  for (size_t p = 0; p < dirty.size(); ++p) dirty[p] = static_cast<int>(p);
  int splits = 0;
  std::vector<std::string> stopped(layout.patches.size());  // why an infeasible patch was not split
  while (!dirty.empty()) {
    ++out.rounds;
    std::vector<DesignedPatch> results(dirty.size());
    const auto designStart = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), dirty.size(),
                      [&](size_t i) { results[i] = evaluate(layout, dirty[i], options); });
    out.designSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - designStart).count();
    out.evaluations += static_cast<int>(dirty.size());
    for (size_t i = 0; i < dirty.size(); ++i) designed[dirty[i]] = std::move(results[i]);
    dirty.clear();
    if (!options.split) break;

    // Split the infeasible patches whose design says where (in id order: deterministic).
    std::set<int> changedCurves;
    std::vector<int> children;
    const size_t existing = layout.patches.size();  // children made in this round wait for the next
    for (size_t p = 0; p < existing; ++p) {
      if (!alive[p] || !designed[p] || designed[p]->feasible() || !designed[p]->design ||
          !stopped[p].empty())
        continue;
      const PatchDesign& d = *designed[p]->design;
      const Patch& patch = d.patch;
      if (splits >= options.maxSplits) {
        stopped[p] =
            fmt::format("the split budget (patching.max_splits = {}) is spent", options.maxSplits);
        continue;
      }
      bool u = d.failure.familyU, v = d.failure.familyV;
      if (!u && !v) u = v = true;
      const bool eta = d.failure.kind == DesignFailureKind::Eta;
      // The sides the split cuts in two: the start and end sides of the family the new side runs
      // along (the failing one for eta, the other one for slopes), all four for a corner.
      std::vector<int> cut{0, 1, 2, 3};
      if (u != v) {
        const Family along = u ? Family::V : Family::U;
        cut = {familySide(along, false).first, familySide(along, true).first};
      }
      double shortest = std::numeric_limits<double>::infinity();
      for (int k : cut) shortest = std::min(shortest, patch.sideLengths[k]);
      if (shortest < 2.0 * minSide) {
        stopped[p] = fmt::format(
            "the sides a split would halve are {:.3g} m long, less than twice the minimum patch "
            "size "
            "({:.3g} m): not split further",
            shortest, minSide);
        continue;
      }
      SplitRecord record;
      record.parent = static_cast<int>(p);
      record.peak = d.failure.peak;
      std::vector<int> made;
      try {
        if (u != v) {
          // Across the failing family's members, parallel to the other family's, through p_max:
          // the peak ends up on the new side (3.4.1) and the failing members are halved. The
          // other way (along the failing members, from p1 to q1) is no cure: a shortest geodesic
          // that long avoids the peak just as the members do.
          const Family failing = u ? Family::U : Family::V;
          const Family other = failing == Family::U ? Family::V : Family::U;
          made = splitAlong(layout, solver, static_cast<int>(p), other, patch, d.failure.peak,
                            d.failure.peak, options.layout, changedCurves);
          record.kind = fmt::format("side over p_max across the {} members ({})",
                                    familyName(failing), eta ? "eta" : "slopes");
        } else {
          made = splitAtCorner(layout, solver, static_cast<int>(p), d.failure.peak, options.layout,
                               changedCurves);
          record.kind = fmt::format("corner at p_max ({}, u and v)", eta ? "eta" : "slopes");
        }
      } catch (const InvalidInput& e) {
        stopped[p] = std::string("could not be split: ") + e.what();
        continue;
      }
      alive[p] = 0;
      ++splits;
      record.children = made;
      children.insert(children.end(), made.begin(), made.end());
      out.splits.push_back(record);
    }
    if (children.empty()) break;
    alive.resize(layout.patches.size(), 1);
    designed.resize(layout.patches.size());
    stopped.resize(layout.patches.size());
    finishLayout(layout, options.layout);
    // The new patches, and every live neighbour whose side now carries a new corner.
    std::set<int> again(children.begin(), children.end());
    for (size_t p = 0; p < layout.patches.size(); ++p) {
      if (!alive[p]) continue;
      for (int k = 0; k < 4; ++k)
        if (changedCurves.count(curveOfSide(layout, static_cast<int>(p), k)))
          again.insert(static_cast<int>(p));
    }
    dirty.assign(again.begin(), again.end());
  }

  // Compact: the live patches in id order, each cut again from the final layout mesh (its
  // faces there count for coverage; the design keeps the mesh it was made on, the same patch).
  PatchLayout final = std::move(layout);
  std::vector<std::array<int, 4>> patches;
  std::vector<std::array<PatchSideSegments, 4>> sides;
  std::vector<DesignedPatch> results;
  for (size_t p = 0; p < final.patches.size(); ++p) {
    if (!alive[p]) continue;
    patches.push_back(final.patches[p]);
    sides.push_back(final.patchSides[p]);
    DesignedPatch d = std::move(*designed[p]);
    if (!stopped[p].empty() && !d.feasible()) d.failure += " (Workflow 1: " + stopped[p] + ")";
    results.push_back(std::move(d));
  }
  final.patches = std::move(patches);
  final.patchSides = std::move(sides);
  tbb::parallel_for(size_t(0), results.size(), [&](size_t i) {
    if (!results[i].cut) return;
    try {
      results[i].cut = cutLayoutPatch(final, static_cast<int>(i), options.layout);
    } catch (const InfeasiblePatch&) {
      results[i].cut.reset();
    }
  });
  out.layout = std::move(final);
  out.patches = std::move(results);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::patching
