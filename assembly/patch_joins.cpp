#include "assembly/patch_joins.hpp"

#include "assembly/boundary_members.hpp"

#include <algorithm>
#include <utility>

namespace egg::assembly {
namespace {

int layerOf(Family family, bool swapped) {
  return (family == Family::U ? 0 : 1) ^ (swapped ? 1 : 0);
}

// The connections along a boundary lamella: where the other family's members end on it, with the
// position and the arc length s_bar along the lamella.
std::vector<std::pair<Eigen::Vector3d, double>> connectionsAlong(const EggGrid& grid,
                                                                 const BoundaryLamella& lamella) {
  std::vector<std::pair<Eigen::Vector3d, double>> out;
  for (const auto& c : grid.connections) {
    if (lamella.family == Family::U && c.memberU == lamella.member)
      out.push_back({c.spatial, c.sBarU});
    if (lamella.family == Family::V && c.memberV == lamella.member)
      out.push_back({c.spatial, c.sBarV});
  }
  return out;
}

}  // namespace

std::vector<char> layerSwaps(const patching::PatchGraph& graph,
                             const std::vector<const EggGrid*>& grids) {
  std::vector<char> swapped(grids.size(), 0), seen(grids.size(), 0);
  for (size_t root = 0; root < grids.size(); ++root) {
    if (seen[root] || !grids[root]) continue;
    std::vector<int> queue{static_cast<int>(root)};
    seen[root] = 1;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int p = queue[q];
      for (const auto& b : graph.boundaries) {
        if (!isWholeSharedSide(b)) continue;
        for (int i = 0; i < 2; ++i) {
          const auto &mine = b.uses[i], &other = b.uses[1 - i];
          if (mine.patch != p || !grids[other.patch] || seen[other.patch]) continue;
          const Family fa = PatchSide(mine.side).boundaryFamily();
          const Family fb = PatchSide(other.side).boundaryFamily();
          swapped[other.patch] = layerOf(fa, swapped[p]) == layerOf(fb, false) ? 1 : 0;
          seen[other.patch] = 1;
          queue.push_back(other.patch);
        }
      }
    }
  }
  return swapped;
}

PatchJoins patchJoins(const patching::PatchGraph& graph, const std::vector<const EggGrid*>& grids,
                      const std::vector<char>& swapped, double toleranceM) {
  PatchJoins out;
  for (const auto& b : graph.boundaries) {
    if (!isWholeSharedSide(b)) continue;
    const auto &ua = b.uses[0], &ub = b.uses[1];
    if (!grids[ua.patch] || !grids[ub.patch]) continue;
    const EggGrid& ga = *grids[ua.patch];
    const EggGrid& gb = *grids[ub.patch];
    const BoundaryLamella la = boundaryLamella(ga, PatchSide(ua.side)),
                          lb = boundaryLamella(gb, PatchSide(ub.side));
    if (layerOf(la.family, swapped[ua.patch]) == layerOf(lb.family, swapped[ub.patch])) {
      ++out.sidesSkipped;
      continue;
    }
    const auto ca = connectionsAlong(ga, la), cb = connectionsAlong(gb, lb);
    const double lengthA = (la.family == Family::U ? ga.u : ga.v)[la.member].planarLength;
    const double lengthB = (lb.family == Family::U ? gb.u : gb.v)[lb.member].planarLength;
    int bolts = 0;
    for (const auto& [position, sA] : ca) {
      const Eigen::Vector3d& pa = position;  // clang before 16 cannot capture a structured binding
      const auto nearest =
          std::min_element(cb.begin(), cb.end(), [&](const auto& x, const auto& y) {
            return (x.first - pa).squaredNorm() < (y.first - pa).squaredNorm();
          });
      if (nearest == cb.end() || (nearest->first - pa).norm() > toleranceM) continue;
      out.bolts.push_back({ua.patch, la.rod, std::clamp(sA, 0.0, lengthA), ub.patch, lb.rod,
                           std::clamp(nearest->second, 0.0, lengthB)});
      ++bolts;
    }
    out.sidesJoined += bolts > 0;
  }
  return out;
}

}  // namespace egg::assembly
