#pragma once
// Workflow 2, automatic (Algorithm 2, Section 3.4.3): an initial layout of the whole design
// surface with no hand input, which Workflow 1 then splits where a patch is infeasible. The thesis
// split its three architectural examples by hand ("some hours each") and names automating it
// future work (3.7.2); this is a first automatic version for surfaces that are height fields over
// a plane with at most one hole:
//   - the footprint (the surface seen along its least-variance direction) gives blocks: one quad
//     block between four outer corners (the boundary points extreme in the diagonal directions:
//     the rectangle's corners, a superellipse's shoulders), or, around a hole, a ring of four
//     blocks between the outer corners and the corners of the box tangent to the hole;
//   - each block is cut into a grid of patches (Coons interpolation of its sides in the plan)
//     with cells no larger than max_patch_size_m, its neighbours' counts matching on shared sides;
//   - the high-K regions first: an interior grid node near a K peak moves onto p_max (Algorithm 2:
//     "introduce a corner at p_max");
//   - boundary nodes lie on the design boundary, and patch sides along it are chords; a node whose
//     chord would leave the footprint (a concave stretch) is pulled inwards, leaving a cut-off.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace egg::geodesic {
class DistanceSolver;
}

namespace egg::patching {

struct Workflow2Options {
  double maxPatchSizeM = 40.0;     // largest patch diagonal proposed (handling on site, 3.5.3)
  double holeMarginRelative = 0.03;  // the box around a hole, inflated by this fraction of its size
  double peakSnapFraction = 0.45;  // a grid node moves onto a K peak within this fraction of its cells along each grid direction
  void validate() const;
};

struct Workflow2Layout {
  std::vector<Eigen::Vector3d> corners;    // on the surface
  std::vector<std::array<int, 4>> quads;   // corner indices, counter-clockwise seen from above
  int blocks = 0;
  int holes = 0;
  int peaksSnapped = 0;
  int nodesPulledIn = 0;
  int candidatesScreened = 0;             // grids tried (cheap: plan nodes lifted, cell chords measured)
  std::vector<std::string> notes;          // how the layout was made, for the report
  double seconds = 0.0;
};

// With `solver` (on `surface`) every boundary chord is traced, and a chord that bends round a
// boundary vertex (hugging a wall the plan view cannot see) has its ends pulled in further.
// Throws InvalidInput when the surface has no boundary or more than one hole.
Workflow2Layout proposeLayout(const TriMesh& surface, const Workflow2Options& options = {},
                              const geodesic::DistanceSolver* solver = nullptr);

}  // namespace egg::patching
