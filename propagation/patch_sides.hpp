#pragma once
// What propagation reads of a patch design (Section 3.4.4): its cladding functions at the chosen
// alpha_bar, its side lengths and the lamella footprint on its sides.
#include "core/egg/patch_design.hpp"
#include "propagation/layout_propagation.hpp"

namespace egg::propagation {

// An infeasible design gives usable = false. The footprint is w / sin of the smallest angle the
// planar members meet the side at, over the cladding function's knots (boundaryAngles, 2.4.4).
PatchSideData patchSideData(const PatchDesign& design, double lamellaWidthM);

// F at the design's alpha_bar as a side map: the cladding curve's points, ends exactly at the
// corners, any point that does not increase strictly in both coordinates dropped.
PiecewiseLinearMap claddingMap(const CladdingFunction& cladding);

}  // namespace egg::propagation
