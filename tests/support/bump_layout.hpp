#pragma once
// Shared by the plan sheet tests (curvature.svg, plan.svg): a 2 x 2 layout on a bump (K = 4 / m^2
// at the top, r = 1.57 m) over the middle 5 x 5 m of an 8 x 8 m surface, whose cut-off is the ring
// outside the layout.
#include "core/geodesic/distance_solver.hpp"
#include "patching/injectivity.hpp"
#include "patching/layout.hpp"
#include "patching/patch_graph.hpp"
#include "samples/generators/samples.hpp"

#include <array>
#include <vector>

namespace egg::patching::testing {

inline std::vector<Eigen::Vector3d> bumpLayoutCorners(const TriMesh& surface, double half) {
  std::vector<Eigen::Vector3d> corners;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      corners.push_back(position(
          surface, geodesic::snapToSurface(surface, {-half + half * i, -half + half * j, 0.0})));
  return corners;
}

struct BumpLayout {
  TriMesh surface = samples::generateSample(
      "bump", {{"length", 8}, {"width", 8}, {"height", 2}, {"sigma", 1}}, 0.2);
  geodesic::DistanceSolver solver{surface};
  PatchLayout layout = makeLayout(surface, solver, bumpLayoutCorners(surface, 2.5),
                                  {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}});
  std::vector<SurfacePeak> peaks = findSurfacePeaks(surface);
  Coverage coverage;
  BumpLayout() {
    std::vector<std::vector<int>> faces(4);
    for (int p = 0; p < 4; ++p) faces[p] = cutLayoutPatch(layout, p).layoutFace;
    coverage = computeCoverage(layout, faces);
  }
};

}  // namespace egg::patching::testing
