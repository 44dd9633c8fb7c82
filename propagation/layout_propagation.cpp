// Propagation over a layout (see layout_propagation.hpp).
#include "propagation/layout_propagation.hpp"

#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <tuple>

namespace egg::propagation {

void PropagationOptions::validate() const {
  if (members && *members < 2) throw InvalidInput("PropagationOptions.members must be at least 2 (the boundary members)");
  if (!(lamellaWidthM > 0.0)) throw InvalidInput("PropagationOptions.lamellaWidthM must be positive");
  if (!(spacingFactor > 0.0)) throw InvalidInput("PropagationOptions.spacingFactor must be positive");
  chain.validate();
}

std::pair<bool, bool> familySideRole(Family family, int side) {
  for (bool end : {false, true}) {
    const auto [k, reversed] = familySide(family, end);
    if (k == side) return {end, reversed};
  }
  throw InvalidInput(fmt::format("side {} carries no end of family {}", side, family == Family::U ? "u" : "v"));
}

std::vector<double> PropagatedChain::startParameters(int node) const {
  const PropagatedNode& n = nodes[node];
  // A forward node's members start on its entry boundary (node), a backward one's on its exit.
  std::vector<double> x = solution.positions[n.forward ? node : node + 1];
  if (n.mirrored) {
    std::reverse(x.begin(), x.end());
    for (double& t : x) t = 1.0 - t;
  }
  x.front() = 0.0;
  x.back() = 1.0;
  return x;
}

int PropagatedChain::memberIndex(int node, int member) const {
  const int m = static_cast<int>(solution.start.size());
  return nodes[node].mirrored ? m - 1 - member : member;
}

namespace {

int familyIndex(Family f) { return f == Family::U ? 0 : 1; }

struct Link {
  int boundary = -1;
  patching::BoundaryUse a, b;  // on the earlier node's patch, on the later node's
};

// The whole shared side between two nodes, if any.
std::optional<Link> findLink(const patching::PatchGraph& graph, const patching::ChainNode& a, const patching::ChainNode& b,
                             std::string& problem) {
  for (const auto& boundary : graph.boundaries) {
    if (boundary.uses.size() != 2) continue;
    for (int order = 0; order < 2; ++order) {
      const auto& ua = boundary.uses[order];
      const auto& ub = boundary.uses[1 - order];
      if (ua.patch != a.patch || ub.patch != b.patch) continue;
      if (patching::familyEndingAtSide(ua.side) != a.family || patching::familyEndingAtSide(ub.side) != b.family) continue;
      if (boundary.kind != "shared") {
        problem = fmt::format("patches {} and {} share only part of a side (boundary {}, {})", a.patch, b.patch, boundary.id, boundary.kind);
        return std::nullopt;
      }
      return Link{boundary.id, ua, ub};
    }
  }
  problem = fmt::format("no whole shared side between patches {} and {}", a.patch, b.patch);
  return std::nullopt;
}

// The family's parameter on a side runs against the segment's direction.
bool againstSegment(Family family, const patching::BoundaryUse& use) {
  return familySideRole(family, use.side).second != use.reversed;
}

int otherFamilySide(Family family, int side) {
  return familySide(family, !familySideRole(family, side).first).first;
}

struct Built {
  PropagatedChain chain;
  std::vector<std::unique_ptr<PiecewiseLinearMap>> maps;
  ChainProblem problem;
};

// Orients one run of nodes (all usable) into a chain problem; empty with `reason` when it cannot.
std::optional<Built> buildChain(const patching::PatchGraph& graph, const std::vector<PatchSideData>& patches,
                                const std::vector<patching::ChainNode>& nodes, bool ring, const PropagationOptions& options,
                                std::string& reason) {
  const size_t n = nodes.size();
  std::vector<Link> links;  // link k joins node k and k+1 (and, for a ring, the last and node 0)
  for (size_t k = 0; k + 1 < n + (ring ? 1 : 0); ++k) {
    auto link = findLink(graph, nodes[k], nodes[(k + 1) % n], reason);
    if (!link) return std::nullopt;
    links.push_back(*link);
  }
  Built built;
  built.chain.ring = ring;
  std::vector<int> entry(n), exit(n);
  for (size_t k = 0; k < n; ++k) {
    const Family f = nodes[k].family;
    const bool hasNext = k + 1 < n || ring, hasPrevious = k > 0 || ring;
    if (hasNext) exit[k] = links[k].a.side;
    if (hasPrevious) entry[k] = (k > 0 ? links[k - 1] : links.back()).b.side;
    if (!hasNext) exit[k] = otherFamilySide(f, entry[k]);
    if (!hasPrevious) entry[k] = otherFamilySide(f, exit[k]);
    if (entry[k] == exit[k]) {
      reason = fmt::format("members would enter and leave patch {} through its side {}", nodes[k].patch, entry[k]);
      return std::nullopt;
    }
  }
  // Orientation: G_k = mirror^m_k o H_k o mirror^m_k stays increasing; a link whose two sides run
  // opposite ways (in the families' own parameters) toggles the mirroring of the next node.
  bool mirrored = false;
  for (size_t k = 0; k < n; ++k) {
    const Family f = nodes[k].family;
    const bool forward = !familySideRole(f, entry[k]).first;
    if (k > 0) mirrored = mirrored != (againstSegment(nodes[k - 1].family, links[k - 1].a) != againstSegment(f, links[k - 1].b));
    built.chain.nodes.push_back({nodes[k].patch, f, forward, mirrored});
    const PatchSideData& data = patches[nodes[k].patch];
    PiecewiseLinearMap h = forward ? data.cladding[familyIndex(f)] : data.cladding[familyIndex(f)].inverted();
    built.maps.push_back(std::make_unique<PiecewiseLinearMap>(mirrored ? h.mirrored() : h));
    built.problem.maps.push_back(built.maps.back().get());
  }
  // Boundaries 0 .. n: lengths, footprints (the larger of the two patches' on a shared side).
  const auto sideGap = [&](size_t node, int side) {
    const Family f = nodes[node].family;
    const PatchSideData& data = patches[nodes[node].patch];
    return std::pair{data.sideLengths[side], data.minGapM[familyIndex(f)][familySideRole(f, side).first ? 1 : 0]};
  };
  double longest = 0.0;
  for (size_t i = 0; i <= n; ++i) {
    ChainBoundary b;
    double gap = 0.0;
    if (i < n) std::tie(b.lengthM, gap) = sideGap(i, entry[i]);
    if (i > 0) {
      const auto [length, g] = sideGap(i - 1, exit[i - 1]);
      if (i == n) b.lengthM = length;
      gap = std::max(gap, g);
    }
    if (ring && (i == 0 || i == n)) gap = std::max(sideGap(0, entry[0]).second, sideGap(n - 1, exit[n - 1]).second);
    b.minGap = std::min(gap / b.lengthM, 0.5);
    longest = std::max(longest, b.lengthM);
    built.problem.boundaries.push_back(b);
    built.chain.boundaries.push_back(i == 0 ? (ring ? links.back().boundary : -1) : i == n ? (ring ? links.back().boundary : -1)
                                                                                          : links[i - 1].boundary);
  }
  built.problem.members = options.members ? *options.members
                                          : 1 + std::max(1, static_cast<int>(std::lround(longest / (options.spacingFactor * options.lamellaWidthM))));
  return built;
}

}  // namespace

LayoutPropagation propagateLayout(const patching::PatchGraph& graph, const std::vector<PatchSideData>& patches,
                                  const PropagationOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  LayoutPropagation out;
  out.x1.resize(patches.size());
  out.nodeOf.assign(patches.size(), {std::pair{-1, -1}, std::pair{-1, -1}});
  for (size_t c = 0; c < graph.chains.size(); ++c) {
    const auto& chain = graph.chains[c];
    for (const auto& node : chain.nodes)
      if (node.patch < 0 || node.patch >= static_cast<int>(patches.size()))
        throw InvalidInput(fmt::format("propagateLayout: chain {} names patch {}, of {} patches", c, node.patch, patches.size()));
    const auto fallback = [&](std::vector<patching::ChainNode> nodes, std::string reason) {
      out.fallbacks.push_back({static_cast<int>(c), std::move(nodes), std::move(reason)});
    };
    if (chain.branching) {
      fallback(chain.nodes, "T-junction (branching chain): its patches place their own members, so its shared sides are not C0");
      continue;
    }
    // Runs of usable nodes; a ring broken by an unusable patch opens there.
    std::vector<patching::ChainNode> nodes = chain.nodes;
    bool ring = chain.ring;
    const auto unusable = [&](const patching::ChainNode& node) { return !patches[node.patch].usable; };
    if (ring && std::any_of(nodes.begin(), nodes.end(), unusable)) {
      std::rotate(nodes.begin(), std::find_if(nodes.begin(), nodes.end(), unusable), nodes.end());
      ring = false;
    }
    std::vector<std::vector<patching::ChainNode>> runs{{}};
    for (const auto& node : nodes) {
      if (unusable(node)) runs.push_back({});
      else runs.back().push_back(node);
    }
    for (auto& run : runs) {
      if (run.empty()) continue;
      if (run.size() == 1) {
        fallback(run, "the family continues into no usable patch: the patch places its own members (2.4.4)");
        continue;
      }
      std::string reason;
      auto built = buildChain(graph, patches, run, ring && run.size() == nodes.size(), options, reason);
      if (!built) {
        fallback(run, reason);
        continue;
      }
      built->chain.graphChain = static_cast<int>(c);
      try {
        built->chain.solution = solveChain(built->problem, options.chain);
      } catch (const InvalidInput& e) {
        fallback(run, std::string("Problem 3.3: ") + e.what());
        continue;
      }
      const int index = static_cast<int>(out.chains.size());
      for (size_t k = 0; k < built->chain.nodes.size(); ++k) {
        const auto& node = built->chain.nodes[k];
        out.x1[node.patch][familyIndex(node.family)] = built->chain.startParameters(static_cast<int>(k));
        out.nodeOf[node.patch][familyIndex(node.family)] = {index, static_cast<int>(k)};
      }
      out.evennessBefore += built->chain.solution.evennessBefore;
      out.evennessAfter += built->chain.solution.evennessAfter;
      out.iterations += built->chain.solution.iterations;
      out.originals += static_cast<int>(built->problem.originals.size());
      out.chains.push_back(std::move(built->chain));
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::propagation
