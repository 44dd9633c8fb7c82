// Tracing a layout in member order (see chain_tracing.hpp).
#include "propagation/chain_tracing.hpp"

#include "core/errors.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <set>

namespace egg::propagation {
namespace {

using Clock = std::chrono::steady_clock;
int familyIndex(Family f) { return f == Family::U ? 0 : 1; }

const std::vector<GridMember>& familyMembers(const EggGrid& grid, Family f) { return f == Family::U ? grid.u : grid.v; }

// The node whose moving end (x2, refined by tracing) lies on node k's fixed side, if any: the
// previous node when both run forwards, the next one when both run backwards. Ring cut: none.
int upstreamNode(const PropagatedChain& chain, int k) {
  const int n = static_cast<int>(chain.nodes.size());
  const auto& node = chain.nodes[k];
  if (node.forward) return k > 0 && chain.nodes[k - 1].forward ? k - 1 : -1;
  return k + 1 < n && !chain.nodes[k + 1].forward ? k + 1 : -1;
}

// The chain parameter of a traced member end x of node k on one of its boundaries.
double chainParameter(const PropagatedNode& node, double x) { return node.mirrored ? 1.0 - x : x; }

}  // namespace

double traceGap(const PropagatedChain& chain, int node, const EggGrid& before, const EggGrid& after) {
  const int n = static_cast<int>(chain.nodes.size());
  const int prev = node == 0 ? n - 1 : node - 1;
  const auto& a = chain.nodes[prev];
  const auto& b = chain.nodes[node];
  const auto& membersA = familyMembers(before, a.family);
  const auto& membersB = familyMembers(after, b.family);
  const int m = static_cast<int>(chain.solution.start.size());
  if (static_cast<int>(membersA.size()) != m || static_cast<int>(membersB.size()) != m)
    throw InvalidInput("traceGap: the traced grids do not carry the chain's members");
  double worst = 0.0;
  for (int j = 1; j + 1 < m; ++j) {
    const GridMember& ma = membersA[chain.memberIndex(prev, j)];
    const GridMember& mb = membersB[chain.memberIndex(node, j)];
    // A's members leave over the side (their end if forward), B's enter over it (start if forward).
    const Eigen::Vector3d& pa = a.forward ? ma.spatial.back() : ma.spatial.front();
    const Eigen::Vector3d& pb = b.forward ? mb.spatial.front() : mb.spatial.back();
    worst = std::max(worst, (pa - pb).norm());
  }
  return worst;
}

LayoutTracing traceLayout(const std::vector<const PatchDesign*>& designs, const LayoutPropagation& propagation) {
  const auto started = Clock::now();
  const size_t count = designs.size();
  if (propagation.x1.size() != count) throw InvalidInput("traceLayout: the propagation covers another number of patches");
  LayoutTracing out;
  out.patches.resize(count);
  std::vector<std::array<std::vector<double>, 2>> x1 = propagation.x1;
  // Dependencies: patch p waits for the patches whose traced ends its members start from.
  std::vector<std::set<int>> waitsFor(count);
  for (size_t p = 0; p < count; ++p)
    for (int f = 0; f < 2; ++f) {
      const auto [c, k] = propagation.nodeOf[p][f];
      if (c < 0) continue;
      const int up = upstreamNode(propagation.chains[c], k);
      if (up >= 0) waitsFor[p].insert(propagation.chains[c].nodes[up].patch);
    }
  std::vector<char> done(count, 0);
  const auto usable = [&](size_t p) { return designs[p] && designs[p]->feasible; };
  for (size_t p = 0; p < count; ++p)
    if (!usable(p)) done[p] = 1, out.patches[p].failure = designs[p] ? designs[p]->failure.message : "not designed";
  const auto tracePatch = [&](size_t p) {
    TracedPatch& traced = out.patches[p];
    const PatchDesign& design = *designs[p];
    try {
      auto t = Clock::now();
      const auto members = [&](Family f) {
        const auto& given = x1[p][familyIndex(f)];
        return given.empty() ? placeDesignMembers(design, f, design.options.members) : membersAt(design, f, given);
      };
      traced.u = members(Family::U);
      traced.v = members(Family::V);
      traced.membersSeconds = std::chrono::duration<double>(Clock::now() - t).count();
      t = Clock::now();
      traced.grid = traceDesignGrid(design, *traced.u, *traced.v, design.options.grid);
      traced.tracingSeconds = std::chrono::duration<double>(Clock::now() - t).count();
    } catch (const InfeasiblePatch& e) {
      traced.failure = std::string("infeasible: ") + e.what();
    } catch (const SolverFailure& e) {
      traced.failure = std::string("solver failure: ") + e.what();
    } catch (const InvalidInput& e) {
      traced.failure = std::string("invalid members: ") + e.what();
    }
  };
  // The downstream patches take their members' starts from the traced ends (C0 closed there).
  const auto takeTracedEnds = [&](size_t p) {
    for (int f = 0; f < 2; ++f) {
      const auto [c, k] = propagation.nodeOf[p][f];
      if (c < 0) continue;
      const PropagatedChain& chain = propagation.chains[c];
      const int up = upstreamNode(chain, k);
      if (up < 0) continue;
      const TracedPatch& source = out.patches[chain.nodes[up].patch];
      if (!source.grid) continue;  // its trace failed: keep the propagated values
      const auto& members = familyMembers(*source.grid, chain.nodes[up].family);
      auto& mine = x1[p][f];
      for (int j = 1; j + 1 < static_cast<int>(mine.size()); ++j) {
        const double t = chainParameter(chain.nodes[up], members[chain.memberIndex(up, j)].x2);
        mine[chain.memberIndex(k, j)] = chainParameter(chain.nodes[k], t);
      }
    }
  };
  size_t remaining = std::count(done.begin(), done.end(), 0);
  while (remaining > 0) {
    std::vector<size_t> ready;
    for (size_t p = 0; p < count; ++p) {
      if (done[p]) continue;
      if (std::all_of(waitsFor[p].begin(), waitsFor[p].end(), [&](int q) { return done[q]; })) ready.push_back(p);
    }
    // A cycle of dependencies (members running round through both families): the first waiting
    // patch goes with the propagated values; its gap is then what tracing leaves.
    if (ready.empty())
      for (size_t p = 0; p < count; ++p)
        if (!done[p]) {
          ready.push_back(p);
          break;
        }
    for (size_t p : ready) takeTracedEnds(p);
    tbb::parallel_for(size_t(0), ready.size(), [&](size_t i) { tracePatch(ready[i]); });
    for (size_t p : ready) done[p] = 1;
    remaining -= ready.size();
    ++out.rounds;
  }
  // C0 on every shared side of the propagated chains, measured on the traced member ends.
  for (size_t c = 0; c < propagation.chains.size(); ++c) {
    const PropagatedChain& chain = propagation.chains[c];
    const int n = static_cast<int>(chain.nodes.size());
    for (int k = chain.ring ? 0 : 1; k < n; ++k) {
      const int prev = k == 0 ? n - 1 : k - 1;
      SideGap gap;
      gap.boundary = chain.boundaries[k];
      gap.chain = static_cast<int>(c);
      gap.patchA = chain.nodes[prev].patch;
      gap.patchB = chain.nodes[k].patch;
      const bool aEnds = chain.nodes[prev].forward, bStarts = chain.nodes[k].forward;
      gap.kind = k == 0 ? "ring cut" : aEnds && !bStarts ? "head-on" : !aEnds && bStarts ? "both start" : "closed";
      const auto& a = out.patches[gap.patchA].grid;
      const auto& b = out.patches[gap.patchB].grid;
      if (!a || !b) {
        gap.kind = "not traced";
      } else {
        gap.maxGapM = traceGap(chain, k, *a, *b);
        if (k > 0) out.c0MaxGapM = std::max(out.c0MaxGapM, gap.maxGapM);
      }
      out.gaps.push_back(gap);
    }
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return out;
}

}  // namespace egg::propagation
