#include "assembly/boundary_members.hpp"

#include <algorithm>

namespace egg::assembly {

BoundaryLamella boundaryLamella(const EggGrid& grid, PatchSide side) {
  const Family family = side.boundaryFamily();
  const int count = static_cast<int>(family == Family::U ? grid.u.size() : grid.v.size());
  const int member = side.boundaryMember(count);
  return {family, member, family == Family::U ? member : static_cast<int>(grid.u.size()) + member};
}

std::vector<int> sideConnections(const EggGrid& grid, PatchSide side) {
  const int nu = static_cast<int>(grid.u.size()), nv = static_cast<int>(grid.v.size());
  const BoundaryLamella lamella = boundaryLamella(grid, side);
  std::vector<int> connections;
  if (lamella.family == Family::U) {
    for (int j = 0; j < nv; ++j) connections.push_back(lamella.member * nv + j);
  } else {
    for (int i = 0; i < nu; ++i) connections.push_back(i * nv + lamella.member);
  }
  return connections;
}

bool isWholeSharedSide(const patching::Boundary& boundary) {
  return boundary.kind == patching::BoundaryKind::Shared && boundary.uses.size() == 2;
}

std::array<bool, 4> freeSides(const patching::PatchGraph& graph, int patch) {
  std::array<bool, 4> free{false, false, false, false};
  bool known = false;
  for (const auto& b : graph.boundaries) {
    for (const auto& use : b.uses) {
      if (use.patch != patch || use.side < 0 || use.side > 3) continue;
      known = true;
      if (b.kind == patching::BoundaryKind::Free) free[use.side] = true;
    }
  }
  return known ? free : std::array<bool, 4>{true, true, true, true};
}

std::vector<fabrication::SharedBoundary> sharedLamellae(const patching::PatchGraph& graph,
                                                        const std::vector<const EggGrid*>& grids) {
  std::vector<fabrication::SharedBoundary> out;
  for (const auto& b : graph.boundaries) {
    if (!isWholeSharedSide(b)) continue;
    const auto &a = b.uses[0], &c = b.uses[1];
    if (!grids[a.patch] || !grids[c.patch]) continue;
    const PatchSide sideA(a.side), sideB(c.side);
    const BoundaryLamella la = boundaryLamella(*grids[a.patch], sideA),
                          lb = boundaryLamella(*grids[c.patch], sideB);
    // Each lamella runs against the shared segment when its side runs against the segment or
    // against its own corners, not both.
    const bool againstA = sideA.againstCorners() != a.reversed;
    const bool againstB = sideB.againstCorners() != c.reversed;
    fabrication::SharedBoundary shared;
    shared.patchA = a.patch, shared.familyA = la.family, shared.indexA = la.member;
    shared.patchB = c.patch, shared.familyB = lb.family, shared.indexB = lb.member;
    shared.reversed = againstA != againstB;
    out.push_back(shared);
  }
  return out;
}

int supportDesignBoundary(const patching::PatchGraph& graph, const std::vector<EggGrid*>& grids) {
  int added = 0;
  for (const auto& b : graph.boundaries) {
    if (b.kind != patching::BoundaryKind::Free) continue;
    const auto& use = b.uses.front();
    EggGrid* grid = grids[use.patch];
    if (!grid) continue;
    for (int c : sideConnections(*grid, PatchSide(use.side))) {
      const bool known = std::any_of(grid->anchors.begin(), grid->anchors.end(),
                                     [&](const GridAnchor& a) { return a.connection == c; });
      if (known) continue;
      grid->anchors.push_back({c, "design boundary support"});
      ++added;
    }
  }
  return added;
}

}  // namespace egg::assembly
