// One patch cut from the layout mesh (layout.hpp): its sides are the layout's chains, so the
// patch meshes of two neighbours share their common side's vertices exactly. The region inside
// the four sides is found by flooding both sides of side 0's first edge in lockstep: the side that
// closes first without reaching the surface boundary is the patch, so the cost is O(patch).
#include "core/errors.hpp"
#include "patching/layout.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <set>

namespace egg::patching {
namespace {

using PatchEdgeKey = std::pair<int, int>;
PatchEdgeKey patchEdgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::string formatPoint(const Eigen::Vector3d& p) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", p.x(), p.y(), p.z());
}

// A breadth-first flood of faces that does not cross `constrained` edges.
struct Flood {
  std::deque<int> queue;
  std::set<int> faces;
  bool touchesBoundary = false;
  bool done() const { return queue.empty(); }
  void seed(int f) {
    if (f >= 0 && faces.insert(f).second) queue.push_back(f);
  }
  void step(const TriMesh& mesh, const std::set<PatchEdgeKey>& constrained) {
    const auto fh = TriMesh::FaceHandle(queue.front());
    queue.pop_front();
    for (auto heh : mesh.fh_range(fh)) {
      const int a = mesh.from_vertex_handle(heh).idx(), b = mesh.to_vertex_handle(heh).idx();
      if (constrained.count(patchEdgeKey(a, b))) continue;
      const auto opposite = mesh.opposite_face_handle(heh);
      if (!opposite.is_valid()) {
        touchesBoundary = true;
        continue;
      }
      seed(opposite.idx());
    }
  }
};

}  // namespace

LayoutPatch cutLayoutPatch(const PatchLayout& layout, int index, const LayoutOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const auto& mesh = layout.mesh.mesh;
  const auto& corners = layout.patches.at(index);
  const auto vertexPosition = [&](int v) { return toEigen(mesh.point(TriMesh::VertexHandle(v))); };

  // The four sides as vertex chains, corner k -> corner k+1.
  std::array<std::vector<int>, 4> chains;
  for (int k = 0; k < 4; ++k) {
    for (const auto& [segment, reversed] : layout.patchSides[index][k]) {
      const auto& seg = layout.segments[segment];
      const std::string& problem = layout.curveProblems[seg.curve];
      if (!problem.empty()) throw InfeasiblePatch(fmt::format("side {}: {}", k, problem));
      std::vector<int> piece = seg.chain;
      if (reversed) std::reverse(piece.begin(), piece.end());
      for (int v : piece)
        if (chains[k].empty() || chains[k].back() != v) chains[k].push_back(v);
    }
    if (chains[k].size() < 2) throw InfeasiblePatch(fmt::format("side {} has no length", k));
  }

  // Sides may share only their common corners.
  std::map<int, int> owner;
  std::set<PatchEdgeKey> constrained;
  for (int k = 0; k < 4; ++k) {
    for (size_t i = 0; i < chains[k].size(); ++i) {
      if (i > 0) constrained.insert(patchEdgeKey(chains[k][i - 1], chains[k][i]));
      const int v = chains[k][i];
      const bool corner = i == 0 || i + 1 == chains[k].size();
      if (corner) continue;
      auto [it, inserted] = owner.emplace(v, k);
      if (!inserted && it->second != k)
        throw InfeasiblePatch(fmt::format("boundaries {} and {} cross at {}", it->second, k,
                                          formatPoint(vertexPosition(v))));
    }
  }
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 4; ++c)
      if (c != k && c != (k + 1) % 4 && owner.count(layout.cornerVertex[corners[c]]))
        throw InfeasiblePatch(fmt::format(
            "boundary {} runs through corner {} (collinear or crossing corners)", k, c));

  // Flood both sides of side 0's first edge in lockstep.
  Flood left, right;
  int leftSeed = -1, rightSeed = -1;
  for (auto heh : mesh.voh_range(TriMesh::VertexHandle(chains[0][0]))) {
    if (mesh.to_vertex_handle(heh).idx() != chains[0][1]) continue;
    if (!mesh.is_boundary(heh)) leftSeed = mesh.face_handle(heh).idx();
    const auto opp = mesh.opposite_halfedge_handle(heh);
    if (!mesh.is_boundary(opp)) rightSeed = mesh.face_handle(opp).idx();
  }
  left.seed(leftSeed), right.seed(rightSeed);
  left.touchesBoundary = leftSeed < 0, right.touchesBoundary = rightSeed < 0;
  Flood* inside = nullptr;
  while (!inside) {
    const bool leftAlive = !left.touchesBoundary, rightAlive = !right.touchesBoundary;
    if (!leftAlive && !rightAlive)
      throw InfeasiblePatch(
          "the region inside the four boundaries contains part of the surface boundary or a hole");
    if (leftAlive && left.done())
      inside = &left;
    else if (rightAlive && right.done())
      inside = &right;
    else {
      if (leftAlive) left.step(mesh, constrained);
      if (rightAlive) right.step(mesh, constrained);
    }
  }
  // Both sides of side 0 in one region: the sides do not separate the surface.
  if (inside->faces.count(inside == &left ? rightSeed : leftSeed))
    throw InfeasiblePatch(
        "the four boundaries do not enclose a region: they cross or leave the surface");

  // The patch mesh, renumbered.
  LayoutPatch out;
  TriangleSoup soup;
  std::map<int, int> renumber;
  for (int f : inside->faces) {
    std::array<int, 3> t{};
    const auto ids = faceVertices(mesh, f);
    for (int i = 0; i < 3; ++i) {
      auto [it, inserted] = renumber.emplace(ids[i], static_cast<int>(soup.vertices.size()));
      if (inserted) {
        soup.vertices.push_back(vertexPosition(ids[i]));
        out.layoutVertex.push_back(ids[i]);
      }
      t[i] = it->second;
    }
    soup.triangles.push_back(t);
    out.layoutFace.push_back(f);
    out.surfaceFace.push_back(layout.mesh.parentFace[f]);
  }
  Patch& patch = out.patch;
  patch.mesh = meshFromSoup(soup);
  for (int k = 0; k < 4; ++k) {
    patch.cornerVertices[k] = renumber.at(layout.cornerVertex[corners[k]]);
    patch.corners[k] = layout.corners[corners[k]];
    patch.cornerOffsets[k] = layout.cornerOffsets[corners[k]];
    double s = 0.0;
    for (size_t i = 0; i < chains[k].size(); ++i) {
      const auto it = renumber.find(chains[k][i]);
      if (it == renumber.end())
        throw SolverFailure(fmt::format("layout patch {}: side {} is not on the patch", index, k));
      if (i > 0) s += (vertexPosition(chains[k][i]) - vertexPosition(chains[k][i - 1])).norm();
      patch.sides[k].push_back(it->second);
      patch.sideArcLength[k].push_back(s);
    }
    patch.sideLengths[k] = s;
  }
  refreshPatchGeometry(patch);
  for (int k = 0; k < 4; ++k)
    if (patch.innerAngles[k] >= M_PI - options.patch.angleMargin)
      throw InfeasiblePatch(
          fmt::format("inner angle at corner {} is {:.6g} rad, not below pi: the patch is not "
                      "convex (criterion iv)",
                      k, patch.innerAngles[k]));
  patch.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace egg::patching
