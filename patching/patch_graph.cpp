// The patch graph (see patch_graph.hpp).
#include "patching/patch_graph.hpp"

#include "core/egg/patch_side.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace egg::patching {

const char* toString(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::Free: return "free";
    case BoundaryKind::Shared: return "shared";
    case BoundaryKind::TJunction: return "t_junction";
  }
  return "unknown";
}

PatchGraph buildPatchGraph(const PatchLayout& layout, const std::vector<bool>& usable) {
  PatchGraph graph;
  const auto isUsable = [&](int p) { return usable.empty() || usable[p]; };
  std::vector<std::vector<BoundaryUse>> uses(layout.segments.size());
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    if (!isUsable(static_cast<int>(p))) continue;
    for (int k = 0; k < 4; ++k) {
      const auto& side = layout.patchSides[p][k];
      double total = 0.0;
      for (const auto& [seg, reversed] : side) total += layout.segments[seg].length;
      double at = 0.0;
      for (const auto& [seg, reversed] : side) {
        const double length = layout.segments[seg].length;
        BoundaryUse use{static_cast<int>(p), k, total > 0 ? at / total : 0.0,
                        total > 0 ? (at + length) / total : 1.0, reversed};
        uses[seg].push_back(use);
        at += length;
      }
    }
  }
  std::set<std::pair<int, int>> adjacent;
  for (size_t s = 0; s < layout.segments.size(); ++s) {
    if (uses[s].empty()) continue;
    Boundary b;
    b.id = static_cast<int>(s);
    b.uses = uses[s];
    b.lengthM = layout.segments[s].length;
    const bool partial = std::any_of(b.uses.begin(), b.uses.end(), [](const BoundaryUse& u) {
      return u.from > 0.0 || u.to < 1.0;
    });
    b.kind = b.uses.size() == 1 ? BoundaryKind::Free
             : partial          ? BoundaryKind::TJunction
                                : BoundaryKind::Shared;
    for (size_t i = 0; i < b.uses.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        adjacent.insert({std::min(b.uses[i].patch, b.uses[j].patch),
                         std::max(b.uses[i].patch, b.uses[j].patch)});
    graph.boundaries.push_back(std::move(b));
  }
  graph.adjacent.assign(adjacent.begin(), adjacent.end());

  // T-junctions: a corner inside a patch side.
  for (size_t c = 0; c < layout.curves.size(); ++c) {
    const auto& corners = layout.curves[c].corners;
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
      TJunction t;
      t.corner = corners[i];
      for (size_t p = 0; p < layout.patches.size(); ++p) {
        if (!isUsable(static_cast<int>(p))) continue;
        const auto& q = layout.patches[p];
        if (std::count(q.begin(), q.end(), t.corner)) {
          t.patchesAt.push_back(static_cast<int>(p));
          continue;
        }
        for (int k = 0; k < 4; ++k) {
          const auto& side = layout.patchSides[p][k];
          for (size_t j = 1; j < side.size(); ++j) {
            const auto& prev = layout.segments[side[j - 1].first];
            const int joint = side[j - 1].second ? prev.from : prev.to;
            if (joint == t.corner) t.patchesThrough.push_back(static_cast<int>(p));
          }
        }
      }
      // A corner in the middle of a free side, where only the patches meeting there use it, is no
      // T-junction: no patch's side passes through it.
      if (!t.patchesThrough.empty()) graph.tJunctions.push_back(std::move(t));
    }
  }

  // Chains: nodes (patch, family) linked across shared pieces of their start or end sides.
  const int n = static_cast<int>(layout.patches.size());
  const auto nodeId = [](int patch, Family f) { return 2 * patch + (f == Family::U ? 0 : 1); };
  std::vector<std::set<int>> neighbours(2 * n);
  std::vector<std::map<int, std::set<int>>> neighboursBySide(2 *
                                                             n);  // node -> side -> neighbour nodes
  for (const auto& b : graph.boundaries) {
    if (b.uses.size() < 2) continue;
    for (size_t i = 0; i < b.uses.size(); ++i)
      for (size_t j = 0; j < b.uses.size(); ++j) {
        if (i == j) continue;
        const int a = nodeId(b.uses[i].patch, PatchSide(b.uses[i].side).endingFamily());
        const int c = nodeId(b.uses[j].patch, PatchSide(b.uses[j].side).endingFamily());
        neighbours[a].insert(c);
        neighboursBySide[a][b.uses[i].side].insert(c);
      }
  }
  std::vector<int> component(2 * n, -1);
  for (int start = 0; start < 2 * n; ++start) {
    if (component[start] >= 0 || !isUsable(start / 2)) continue;
    std::vector<int> members{start};
    component[start] = start;
    for (size_t i = 0; i < members.size(); ++i)
      for (int m : neighbours[members[i]])
        if (component[m] < 0) component[m] = start, members.push_back(m);
    MemberChain chain;
    size_t edges = 0;
    for (int m : members) {
      edges += neighbours[m].size();
      if (neighbours[m].size() > 2) chain.branching = true;
      for (const auto& [side, ns] : neighboursBySide[m])
        if (ns.size() > 1) chain.branching = true;
    }
    edges /= 2;
    std::sort(members.begin(), members.end());
    if (!chain.branching && members.size() > 1) {
      // Walk from an end (the smallest node of degree 1), or round the ring from the smallest node.
      chain.ring = edges == members.size();
      int first = members.front();
      if (!chain.ring)
        for (int m : members)
          if (neighbours[m].size() == 1) {
            first = m;
            break;
          }
      std::vector<int> order{first};
      std::set<int> seen{first};
      while (order.size() < members.size()) {
        int next = -1;
        for (int m : neighbours[order.back()])
          if (!seen.count(m)) {
            next = m;
            break;
          }
        if (next < 0) break;
        order.push_back(next);
        seen.insert(next);
      }
      members = order;
    }
    for (int m : members) chain.nodes.push_back({m / 2, m % 2 == 0 ? Family::U : Family::V});
    graph.chains.push_back(std::move(chain));
  }
  return graph;
}

namespace {
double faceArea(const TriMesh& mesh, int f) {
  const auto ids = faceVertices(mesh, f);
  const auto p = [&](int i) { return toEigen(mesh.point(TriMesh::VertexHandle(ids[i]))); };
  return 0.5 * (p(1) - p(0)).cross(p(2) - p(0)).norm();
}
}  // namespace

Coverage computeCoverage(const PatchLayout& layout,
                         const std::vector<std::vector<int>>& patchFaces) {
  const TriMesh& mesh = layout.mesh.mesh;
  Coverage out;
  std::vector<char> covered(mesh.n_faces(), 0);
  for (const auto& faces : patchFaces)
    for (int f : faces) covered[f] = 1;  // a face in two patches counts once
  for (auto fh : mesh.faces()) {
    const double a = faceArea(mesh, fh.idx());
    out.surfaceAreaM2 += a;
    if (covered[fh.idx()]) out.coveredAreaM2 += a;
  }
  out.fraction = out.surfaceAreaM2 > 0 ? out.coveredAreaM2 / out.surfaceAreaM2 : 0.0;
  // Cut-offs: flood the uncovered faces without crossing a layout side.
  std::set<std::pair<int, int>> constrained;
  for (const auto& chain : layout.mesh.chains)
    for (size_t i = 1; i < chain.size(); ++i)
      constrained.insert({std::min(chain[i - 1], chain[i]), std::max(chain[i - 1], chain[i])});
  std::vector<char> seen(mesh.n_faces(), 0);
  for (auto seed : mesh.faces()) {
    if (covered[seed.idx()] || seen[seed.idx()]) continue;
    CutOff cut;
    std::vector<int> stack{seed.idx()};
    seen[seed.idx()] = 1;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      cut.faces.push_back(f);
      const double a = faceArea(mesh, f);
      const auto ids = faceVertices(mesh, f);
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : ids) c += toEigen(mesh.point(TriMesh::VertexHandle(v))) / 3.0;
      weighted += a * c;
      cut.areaM2 += a;
      for (auto heh : mesh.fh_range(TriMesh::FaceHandle(f))) {
        const int x = mesh.from_vertex_handle(heh).idx(), y = mesh.to_vertex_handle(heh).idx();
        if (constrained.count({std::min(x, y), std::max(x, y)})) continue;
        const auto g = mesh.opposite_face_handle(heh);
        if (g.is_valid() && !covered[g.idx()] && !seen[g.idx()])
          seen[g.idx()] = 1, stack.push_back(g.idx());
      }
    }
    cut.centroid = cut.areaM2 > 0 ? Eigen::Vector3d(weighted / cut.areaM2) : weighted;
    out.cutOffs.push_back(std::move(cut));
  }
  std::stable_sort(out.cutOffs.begin(), out.cutOffs.end(),
                   [](const CutOff& a, const CutOff& b) { return a.areaM2 > b.areaM2; });
  return out;
}

}  // namespace egg::patching
