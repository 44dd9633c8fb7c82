#pragma once
// Workflow 2, automatic (Algorithm 2, Section 3.4.3): an initial layout of the whole design
// surface with no hand input, which Workflow 1 then splits where a patch is infeasible. The thesis
// split its three architectural examples by hand ("some hours each") and names automating it
// future work (3.7.2); this version is for surfaces that are height fields over a plane:
//   - the footprint (the surface seen along its least-variance direction) gives blocks: one quad
//     block between four outer corners (the boundary points extreme in the diagonal directions:
//     the rectangle's corners, a superellipse's shoulders), or, around a single hole, a ring of
//     four blocks between the outer corners and the box round the hole;
//   - each block is cut into a grid of patches (Coons interpolation of its sides in the plan) with
//     cells no larger than max_patch_size_m measured along the surface. One block: every grid up to
//     16 x 16 is screened and the one predicting the fewest patches kept, the high-K regions first
//     (Algorithm 2: "introduce a corner at p_max": interior nodes move onto nearby peaks; a peak
//     left inside a large cell counts as Workflow 1's split), several holes each in a cell of its
//     own that becomes a ring of four patches round the hole;
//   - the box round a hole shrinks until its traced sides just clear the hole (tangent sides);
//   - boundary nodes lie on the design boundary and sides along it are its geodesics or chords;
//     a node whose traced side would wrap round the boundary is pulled inwards, leaving a cut-off,
//     and an outer corner on a straight (geodesic) boundary has its neighbours moved in.
#include "core/egg/patch.hpp"
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
  double maxPatchSizeM = 40.0;       // largest patch diagonal proposed (handling on site, 3.5.3)
  double holeMarginRelative = 0.03;  // the box around a hole, inflated by this fraction of its size
  double boundaryWrapToleranceRad =
      PatchOptions{}.boundaryWrapToleranceRad;  // a traced side along the boundary may turn this
                                                // much round it
  double peakSnapFraction = 0.45;  // a grid node moves onto a K peak within this fraction of its
                                   // cells along each grid direction
  // The architect's grid of patches for a surface with no hole or several ({0, 0}: screen every
  // grid up to 16 x 16 and keep the one predicting the fewest patches). Its cells must still fit
  // maxPatchSizeM; Workflow 1 may split its patches further.
  std::array<int, 2> blockGrid{0, 0};
  void validate() const;
};

struct Workflow2Layout {
  std::vector<Eigen::Vector3d> corners;   // on the surface
  std::vector<std::array<int, 4>> quads;  // corner indices, counter-clockwise seen from above
  int blocks = 0;
  int holes = 0;
  int peaksSnapped = 0;
  int nodesPulledIn = 0;
  int cornersMovedOffStraightBoundary = 0;
  int holeBoxesTightened =
      0;  // boxes round holes whose traced sides were moved in to just clear them
  int candidatesScreened = 0;      // grids tried (cheap: plan nodes lifted, cell chords measured)
  std::vector<std::string> notes;  // how the layout was made, for the report
  double seconds = 0.0;
};

// With `solver` (on `surface`) every boundary chord is traced, and a chord that bends round a
// boundary vertex (hugging a wall the plan view cannot see) has its ends pulled in further.
// Throws InvalidInput when the surface has no boundary, or no screened grid fits (the size, the
// holes).
Workflow2Layout proposeLayout(const TriMesh& surface, const Workflow2Options& options = {},
                              const geodesic::DistanceSolver* solver = nullptr);

}  // namespace egg::patching
