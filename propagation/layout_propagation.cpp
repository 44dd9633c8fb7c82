// Propagation over a layout (see layout_propagation.hpp).
#include "propagation/layout_propagation.hpp"

#include "core/egg/patch_maps.hpp"
#include "core/egg/patch_side.hpp"
#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <tuple>

namespace egg::propagation {

void PropagationOptions::validate() const {
  if (members && *members < 2)
    throw InvalidInput("PropagationOptions.members must be at least 2 (the boundary members)");
  if (!(lamellaWidthM > 0.0))
    throw InvalidInput("PropagationOptions.lamellaWidthM must be positive");
  if (!(spacingFactor > 0.0))
    throw InvalidInput("PropagationOptions.spacingFactor must be positive");
  chain.validate();
}

const char* toString(PieceKind kind) {
  switch (kind) {
    case PieceKind::WholeSide: return "whole side";
    case PieceKind::TJunction: return "t_junction";
    case PieceKind::RingCut: return "ring cut";
  }
  return "unknown";
}

std::pair<bool, bool> familySideRole(Family family, int side) {
  const PatchSide patchSide(side);
  if (patchSide.endingFamily() == family)
    return {patchSide.isMembersEnd(), patchSide.againstCorners()};
  throw InvalidInput(
      fmt::format("side {} carries no end of family {}", side, family == Family::U ? "u" : "v"));
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

int familySlot(Family f) { return f == Family::U ? 0 : 1; }

struct Link {
  int boundary = -1;
  patching::BoundaryUse a, b;  // on the earlier node's patch, on the later node's
};

// The whole shared side between two nodes, if any.
std::optional<Link> findLink(const patching::PatchGraph& graph, const patching::ChainNode& a,
                             const patching::ChainNode& b, std::string& problem) {
  for (const auto& boundary : graph.boundaries) {
    if (boundary.uses.size() != 2) continue;
    for (int order = 0; order < 2; ++order) {
      const auto& ua = boundary.uses[order];
      const auto& ub = boundary.uses[1 - order];
      if (ua.patch != a.patch || ub.patch != b.patch) continue;
      if (PatchSide(ua.side).endingFamily() != a.family ||
          PatchSide(ub.side).endingFamily() != b.family)
        continue;
      if (boundary.kind != patching::BoundaryKind::Shared) {
        problem = fmt::format("patches {} and {} share only part of a side (boundary {}, {})",
                              a.patch, b.patch, boundary.id, toString(boundary.kind));
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
std::optional<Built> buildChain(const patching::PatchGraph& graph,
                                const std::vector<PatchSideData>& patches,
                                const std::vector<patching::ChainNode>& nodes, bool ring,
                                const PropagationOptions& options, std::string& reason) {
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
    if (!hasNext && !hasPrevious) {
      // A lone node of a branching chain (linked by T-junction pieces only): read forwards.
      entry[k] = familySide(f, false).first;
      exit[k] = familySide(f, true).first;
    }
    if (!hasNext && hasPrevious) exit[k] = otherFamilySide(f, entry[k]);
    if (!hasPrevious && hasNext) entry[k] = otherFamilySide(f, exit[k]);
    if (entry[k] == exit[k]) {
      reason = fmt::format("members would enter and leave patch {} through its side {}",
                           nodes[k].patch, entry[k]);
      return std::nullopt;
    }
  }
  // Orientation: G_k = mirror^m_k o H_k o mirror^m_k stays increasing; a link whose two sides run
  // opposite ways (in the families' own parameters) toggles the mirroring of the next node.
  bool mirrored = false;
  for (size_t k = 0; k < n; ++k) {
    const Family f = nodes[k].family;
    const bool forward = !familySideRole(f, entry[k]).first;
    if (k > 0)
      mirrored = mirrored != (againstSegment(nodes[k - 1].family, links[k - 1].a) !=
                              againstSegment(f, links[k - 1].b));
    built.chain.nodes.push_back({nodes[k].patch, f, forward, mirrored});
    const PatchSideData& data = patches[nodes[k].patch];
    PiecewiseLinearMap h =
        forward ? data.cladding[familySlot(f)] : data.cladding[familySlot(f)].inverted();
    built.maps.push_back(std::make_unique<PiecewiseLinearMap>(mirrored ? h.mirrored() : h));
    built.problem.maps.push_back(built.maps.back().get());
  }
  // Boundaries 0 .. n: lengths, footprints (the larger of the two patches' on a shared side).
  const auto sideGap = [&](size_t node, int side) {
    const Family f = nodes[node].family;
    const PatchSideData& data = patches[nodes[node].patch];
    return std::pair{data.sideLengths[side],
                     data.minGapM[familySlot(f)][familySideRole(f, side).first ? 1 : 0]};
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
    if (ring && (i == 0 || i == n))
      gap = std::max(sideGap(0, entry[0]).second, sideGap(n - 1, exit[n - 1]).second);
    b.minGap = std::min(gap / b.lengthM, 0.5);
    longest = std::max(longest, b.lengthM);
    built.problem.boundaries.push_back(b);
    built.chain.boundaries.push_back(i == 0   ? (ring ? links.back().boundary : -1)
                                     : i == n ? (ring ? links.back().boundary : -1)
                                              : links[i - 1].boundary);
  }
  built.problem.members =
      options.members
          ? *options.members
          : 1 + std::max(1, static_cast<int>(std::lround(
                                longest / (options.spacingFactor * options.lamellaWidthM))));
  return built;
}

// Where a node of a propagated chain meets side `side` of its patch: the chain boundary, and the
// maps between the family's own parameter x and the chain's parameter t there.
int chainBoundaryOf(const PropagatedChain& chain, int node, int side) {
  const PropagatedNode& n = chain.nodes[node];
  const bool entry = familySide(n.family, !n.forward).first == side;
  return entry ? node : node + 1;
}
double chainOfFamily(const PropagatedNode& n, double x) { return n.mirrored ? 1.0 - x : x; }
// The family's parameter on side `side` <-> the fraction along the side (corner k -> k+1).
double sideFraction(Family family, int side, double x) {
  return familySideRole(family, side).second ? 1.0 - x : x;
}
// The fraction along a side <-> the parameter along the piece (its segment's own direction).
double pieceToSide(const patching::BoundaryUse& u, double rho) {
  return u.reversed ? u.to - rho * (u.to - u.from) : u.from + rho * (u.to - u.from);
}
double sideToPiece(const patching::BoundaryUse& u, double s) {
  const double r = (s - u.from) / (u.to - u.from);
  return u.reversed ? 1.0 - r : r;
}

// The members' family parameters (index = member, x1 increasing) of node k on its side `side`.
std::vector<double> sideParameters(const PropagatedChain& chain, int node, int side) {
  const auto& t = chain.solution.positions[chainBoundaryOf(chain, node, side)];
  const int m = static_cast<int>(t.size());
  std::vector<double> x(m);
  for (int j = 0; j < m; ++j)
    x[chain.memberIndex(node, j)] = chainOfFamily(chain.nodes[node], t[j]);
  return x;
}

constexpr double kPieceTolerance = 1e-9;  // parameters this close count as the same point

// The members of a family on a piece: (piece parameter, member index), increasing in the former.
std::vector<std::pair<double, int>> membersOnPiece(const std::vector<double>& x, Family family,
                                                   const patching::BoundaryUse& use) {
  std::vector<std::pair<double, int>> out;
  for (int i = 0; i < static_cast<int>(x.size()); ++i) {
    const double sigma = sideFraction(family, use.side, x[i]);
    if (sigma >= use.from - kPieceTolerance && sigma <= use.to + kPieceTolerance)
      out.push_back({sideToPiece(use, sigma), i});
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct NodeKey {
  int patch;
  Family family;
  bool operator<(const NodeKey& o) const {
    return std::tie(patch, family) < std::tie(o.patch, o.family);
  }
};
NodeKey keyOf(const patching::BoundaryUse& use) {
  return {use.patch, PatchSide(use.side).endingFamily()};
}

using Fallback = std::function<void(std::vector<patching::ChainNode>, std::string)>;

// A branching chain (see the header): sub-chains of whole sides, solved breadth first over the
// T-junction pieces that join them, each taking its solved neighbours' members as originals.
void propagateBranching(const patching::PatchGraph& graph,
                        const std::vector<PatchSideData>& patches,
                        const patching::MemberChain& chain, const PropagationOptions& options,
                        const Fallback& fallback, const std::function<void(Built&)>& record,
                        const LayoutPropagation& out) {
  std::set<NodeKey> nodes;
  for (const auto& n : chain.nodes)
    if (patches[n.patch].usable) nodes.insert({n.patch, n.family});
  std::map<NodeKey, std::vector<NodeKey>> whole;
  std::vector<const patching::Boundary*> tPieces;
  for (const auto& b : graph.boundaries) {
    if (b.uses.size() != 2) continue;
    const NodeKey a = keyOf(b.uses[0]), c = keyOf(b.uses[1]);
    if (!nodes.count(a) || !nodes.count(c)) continue;
    if (b.kind == patching::BoundaryKind::Shared)
      whole[a].push_back(c), whole[c].push_back(a);
    else if (b.kind == patching::BoundaryKind::TJunction)
      tPieces.push_back(&b);
  }
  // Sub-chains: a family has one start and one end side, so whole sides link it to at most two
  // neighbours: paths, or rings.
  std::vector<std::vector<patching::ChainNode>> subs;
  std::vector<bool> rings;
  std::map<NodeKey, int> subOf;
  for (const NodeKey& seed : nodes) {
    if (subOf.count(seed)) continue;
    std::vector<NodeKey> component{seed};
    std::set<NodeKey> seen{seed};
    for (size_t i = 0; i < component.size(); ++i)
      for (const auto& m : whole[component[i]])
        if (seen.insert(m).second) component.push_back(m);
    NodeKey first = *std::min_element(component.begin(), component.end());
    bool ring = true;
    for (const auto& m : seen)
      if (whole[m].size() < 2) {
        first = m, ring = false;
        break;
      }
    std::vector<NodeKey> order{first};
    std::set<NodeKey> walked{first};
    for (bool more = true; more;) {
      more = false;
      for (const auto& m : whole[order.back()])
        if (walked.insert(m).second) {
          order.push_back(m), more = true;
          break;
        }
    }
    const int index = static_cast<int>(subs.size());
    std::vector<patching::ChainNode> sub;
    for (const auto& m : (order.size() == component.size() ? order : component))
      sub.push_back({m.patch, m.family}), subOf[m] = index;
    if (order.size() != component.size()) {
      fallback(sub, "whole shared sides join these patches in no path or ring");
      sub.clear();
    }
    subs.push_back(std::move(sub));
    rings.push_back(ring && order.size() >= 3);
  }
  // Breadth first over the T-junction pieces, from the sub-chain of most patches.
  std::vector<int> queue;
  std::vector<char> queued(subs.size(), 0);
  while (queue.size() < subs.size()) {
    int best = -1;
    for (size_t s = 0; s < subs.size(); ++s)
      if (!queued[s] && (best < 0 || subs[s].size() > subs[best].size()))
        best = static_cast<int>(s);
    queue.push_back(best), queued[best] = 1;
    for (size_t i = queue.size() - 1; i < queue.size(); ++i)
      for (const auto* b : tPieces) {
        const int s0 = subOf[keyOf(b->uses[0])], s1 = subOf[keyOf(b->uses[1])];
        for (int s : {s0, s1})
          if ((s0 == queue[i] || s1 == queue[i]) && !queued[s]) queue.push_back(s), queued[s] = 1;
      }
  }
  for (int s : queue) {
    if (subs[s].empty()) continue;
    std::string reason;
    auto built = buildChain(graph, patches, subs[s], rings[s], options, reason);
    if (!built) {
      fallback(subs[s], reason);
      continue;
    }
    ChainProblem& problem = built->problem;
    const auto addOriginal = [&](int boundary, double t) {
      if (!(t > kPieceTolerance && t < 1.0 - kPieceTolerance)) return;  // a boundary member
      for (const auto& o : problem.originals)
        if (o.boundary == boundary && std::abs(o.value - t) < 1e-12) return;
      problem.originals.push_back({boundary, t});
    };
    for (const auto* b : tPieces)
      for (int u = 0; u < 2; ++u) {
        const auto &use = b->uses[u], &other = b->uses[1 - u];
        const NodeKey key = keyOf(use);
        const auto it = std::find_if(subs[s].begin(), subs[s].end(), [&](const auto& n) {
          return n.patch == key.patch && n.family == key.family;
        });
        if (it == subs[s].end()) continue;
        const int k = static_cast<int>(it - subs[s].begin());
        const int boundary = chainBoundaryOf(built->chain, k, use.side);
        const PropagatedNode& node = built->chain.nodes[k];
        const auto chainAt = [&](double sigma) {
          return chainOfFamily(node, sideFraction(key.family, use.side, sigma));
        };
        // A T-junction of boundary members: a piece ending inside the side ends at a smaller
        // patch's corner, whose boundary member the member here continues (Fig. 3.8).
        if (use.from > kPieceTolerance) addOriginal(boundary, chainAt(use.from));
        if (use.to < 1.0 - kPieceTolerance) addOriginal(boundary, chainAt(use.to));
        const NodeKey otherKey = keyOf(other);
        const auto [oc, on] = out.nodeOf[otherKey.patch][familySlot(otherKey.family)];
        if (oc < 0) continue;  // not solved yet (or not propagated): it will take ours
        for (const auto& [rho, i] :
             membersOnPiece(sideParameters(out.chains[oc], on, other.side), otherKey.family, other))
          addOriginal(boundary, chainAt(pieceToSide(use, rho)));
        const double t0 = chainAt(use.from), t1 = chainAt(use.to);
        problem.closed.push_back({boundary, std::min(t0, t1), std::max(t0, t1)});
      }
    try {
      if (!problem.originals.empty()) {
        // The spacing rule (the chain's longest boundary over its member intervals) applied to
        // every open gap between fixed members, on the boundary where the gap is widest.
        std::vector<bool> closedGaps;
        const std::vector<double> fixed = fixedStarts(problem, &closedGaps);
        const auto across = propagateMembers(problem, fixed);
        double longest = 0.0;
        for (const auto& b : problem.boundaries) longest = std::max(longest, b.lengthM);
        const double spacingM = longest / (problem.members - 1);
        int free = 0;
        for (size_t g = 0; g + 1 < fixed.size(); ++g) {
          if (closedGaps[g]) continue;
          long most = 0;
          for (size_t i = 0; i < across.size(); ++i)
            most = std::max(most, std::lround((across[i][g + 1] - across[i][g]) *
                                              problem.boundaries[i].lengthM / spacingM));
          free += static_cast<int>(std::max(0L, most - 1));
        }
        problem.members = static_cast<int>(fixed.size()) + free;
      }
      built->chain.solution = solveChain(problem, options.chain);
    } catch (const InvalidInput& e) {
      fallback(subs[s], std::string("Problem 3.3: ") + e.what());
      continue;
    }
    record(*built);
  }
}

// The joints of every piece between two propagated families (after all chains are solved).
void addJoints(const patching::PatchGraph& graph, LayoutPropagation& out) {
  for (const auto& boundary : graph.boundaries) {
    if (boundary.uses.size() != 2) continue;
    const auto &ua = boundary.uses[0], &ub = boundary.uses[1];
    const NodeKey ka = keyOf(ua), kb = keyOf(ub);
    const auto [ca, na] = out.nodeOf[ka.patch][familySlot(ka.family)];
    const auto [cb, nb] = out.nodeOf[kb.patch][familySlot(kb.family)];
    if (ca < 0 || cb < 0) continue;
    SharedPiece piece;
    piece.boundary = boundary.id;
    piece.patchA = ua.patch, piece.patchB = ub.patch;
    const PropagatedChain &chainA = out.chains[ca], &chainB = out.chains[cb];
    const bool ringCut = ca == cb && chainA.ring && boundary.id == chainA.boundaries.front();
    piece.kind = ringCut                                           ? PieceKind::RingCut
                 : boundary.kind == patching::BoundaryKind::Shared ? PieceKind::WholeSide
                                                                   : PieceKind::TJunction;
    if (ringCut) piece.chain = ca;
    const auto onA = membersOnPiece(sideParameters(chainA, na, ua.side), ka.family, ua);
    const auto onB = membersOnPiece(sideParameters(chainB, nb, ub.side), kb.family, ub);
    piece.membersA = static_cast<int>(onA.size());
    piece.membersB = static_cast<int>(onB.size());
    if (!ringCut) {
      if (onA.size() != onB.size()) {
        out.notes.push_back(
            fmt::format("boundary {} (patches {}, {}): {} members on one side, {} on the other",
                        boundary.id, ua.patch, ub.patch, onA.size(), onB.size()));
      } else {
        // x_b as an affine function of x_a through the piece's own parameter.
        const auto map = [&](double xa) {
          return sideFraction(
              kb.family, ub.side,
              pieceToSide(ub, sideToPiece(ua, sideFraction(ka.family, ua.side, xa))));
        };
        const double offset = map(0.0), scale = map(1.0) - map(0.0);
        const int countA = static_cast<int>(chainA.solution.start.size()),
                  countB = static_cast<int>(chainB.solution.start.size());
        for (size_t k = 0; k < onA.size(); ++k) {
          if (std::abs(onA[k].first - onB[k].first) > kPieceTolerance)
            out.notes.push_back(
                fmt::format("boundary {}: member {} of patch {} and member {} of patch {} lie "
                            "{:.3g} apart (piece parameter)",
                            boundary.id, onA[k].second, ua.patch, onB[k].second, ub.patch,
                            std::abs(onA[k].first - onB[k].first)));
          const int ia = onA[k].second, ib = onB[k].second;
          const bool boundaryA = ia == 0 || ia == countA - 1,
                     boundaryB = ib == 0 || ib == countB - 1;
          if (boundaryA && boundaryB)
            continue;  // two patch sides meeting at a corner: nothing to trace
          MemberJoint joint;
          joint.boundary = boundary.id;
          joint.a = {ua.patch, ka.family, ia, familySideRole(ka.family, ua.side).first};
          joint.b = {ub.patch, kb.family, ib, familySideRole(kb.family, ub.side).first};
          joint.offset = offset, joint.scale = scale;
          piece.joints.push_back(static_cast<int>(out.joints.size()));
          out.joints.push_back(joint);
        }
      }
    }
    out.pieces.push_back(std::move(piece));
  }
}

}  // namespace

LayoutPropagation propagateLayout(const patching::PatchGraph& graph,
                                  const std::vector<PatchSideData>& patches,
                                  const PropagationOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  LayoutPropagation out;
  out.x1.resize(patches.size());
  out.nodeOf.assign(patches.size(), {std::pair{-1, -1}, std::pair{-1, -1}});
  const auto record = [&](Built& built, int graphChain) {
    built.chain.graphChain = graphChain;
    const int index = static_cast<int>(out.chains.size());
    for (size_t k = 0; k < built.chain.nodes.size(); ++k) {
      const auto& node = built.chain.nodes[k];
      out.x1[node.patch][familySlot(node.family)] =
          built.chain.startParameters(static_cast<int>(k));
      out.nodeOf[node.patch][familySlot(node.family)] = {index, static_cast<int>(k)};
    }
    out.evennessBefore += built.chain.solution.evennessBefore;
    out.evennessAfter += built.chain.solution.evennessAfter;
    out.iterations += built.chain.solution.iterations;
    out.originals += static_cast<int>(built.problem.originals.size());
    out.chains.push_back(std::move(built.chain));
  };
  for (size_t c = 0; c < graph.chains.size(); ++c) {
    const auto& chain = graph.chains[c];
    for (const auto& node : chain.nodes)
      if (node.patch < 0 || node.patch >= static_cast<int>(patches.size()))
        throw InvalidInput(fmt::format("propagateLayout: chain {} names patch {}, of {} patches", c,
                                       node.patch, patches.size()));
    const auto fallback = [&](std::vector<patching::ChainNode> nodes, std::string reason) {
      out.fallbacks.push_back({static_cast<int>(c), std::move(nodes), std::move(reason)});
    };
    if (chain.branching) {
      propagateBranching(
          graph, patches, chain, options, fallback,
          [&](Built& b) { record(b, static_cast<int>(c)); }, out);
      continue;
    }
    // Runs of usable nodes; a ring broken by an unusable patch opens there.
    std::vector<patching::ChainNode> nodes = chain.nodes;
    bool ring = chain.ring;
    const auto unusable = [&](const patching::ChainNode& node) {
      return !patches[node.patch].usable;
    };
    if (ring && std::any_of(nodes.begin(), nodes.end(), unusable)) {
      std::rotate(nodes.begin(), std::find_if(nodes.begin(), nodes.end(), unusable), nodes.end());
      ring = false;
    }
    std::vector<std::vector<patching::ChainNode>> runs{{}};
    for (const auto& node : nodes) {
      if (unusable(node))
        runs.push_back({});
      else
        runs.back().push_back(node);
    }
    for (auto& run : runs) {
      if (run.empty()) continue;
      if (run.size() == 1) {
        fallback(
            run,
            "the family continues into no usable patch: the patch places its own members (2.4.4)");
        continue;
      }
      std::string reason;
      auto built =
          buildChain(graph, patches, run, ring && run.size() == nodes.size(), options, reason);
      if (!built) {
        fallback(run, reason);
        continue;
      }
      try {
        built->chain.solution = solveChain(built->problem, options.chain);
      } catch (const InvalidInput& e) {
        fallback(run, std::string("Problem 3.3: ") + e.what());
        continue;
      }
      record(*built, static_cast<int>(c));
    }
  }
  addJoints(graph, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::propagation
