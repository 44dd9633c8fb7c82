#include "propagation/patch_sides.hpp"

#include <algorithm>

namespace egg::propagation {

PiecewiseLinearMap claddingMap(const CladdingFunction& cladding) {
  std::vector<Eigen::Vector2d> knots{Eigen::Vector2d(0, 0)};
  for (const auto& p : cladding.points) {
    if (p.x() >= 1.0 || p.y() >= 1.0) break;
    if (p.x() > knots.back().x() && p.y() > knots.back().y()) knots.push_back(p);
  }
  knots.emplace_back(1.0, 1.0);
  return PiecewiseLinearMap(std::move(knots));
}

PatchSideData patchSideData(const PatchDesign& design, double lamellaWidthM) {
  PatchSideData data;
  data.usable = design.feasible;
  data.sideLengths = design.patch.sideLengths;
  if (!design.feasible) return data;
  for (Family family : {Family::U, Family::V}) {
    const CladdingFunction& f =
        family == Family::U ? design.alphaBar.claddingU : design.alphaBar.claddingV;
    const int index = family == Family::U ? 0 : 1;
    data.cladding[index] = claddingMap(f);
    double smallest[2] = {M_PI / 2, M_PI / 2};
    for (const auto& knot : data.cladding[index].knots()) {
      const auto angles = boundaryAngles(design.alphaBar.quad, family, knot.x(), knot.y());
      for (int end = 0; end < 2; ++end) smallest[end] = std::min(smallest[end], angles[end]);
    }
    for (int end = 0; end < 2; ++end)
      data.minGapM[index][end] = lamellaFootprint(lamellaWidthM, smallest[end]);
  }
  return data;
}

}  // namespace egg::propagation
