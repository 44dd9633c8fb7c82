#pragma once
// Tangent sides round a hole (Section 3.4.3: "a hole gets chords or tangent sides, with cut-offs
// reported"): the box of four corners round a hole, moved in until its traced sides just clear it.
// Only workflow2.cpp uses this.
#include "core/mesh/mesh.hpp"
#include "patching/footprint.hpp"

#include <array>
#include <functional>

namespace egg::geodesic {
class DistanceSolver;
}

namespace egg::patching {

// How far the geodesic between two plan points stays outside the hole: the least signed plan
// distance of the traced path to the hole's outline (negative inside), -infinity when the path
// bends round a boundary vertex (it wraps the hole or hugs the boundary).
double holeClearance(const Vec2& from, const Vec2& to, const Polygon& hole, const Plan& plan,
                     const PlanLifter& lifter, const TriMesh& surface,
                     const geodesic::DistanceSolver& solver);

// The corners cornerAt(k) = centre + scale[k] * (corner direction k) of the box round a hole move
// towards its centre (scale shrinks from its value) until each traced side clears the hole by
// `target`: first all four by one factor, then each alone. Geodesics bow away from the hole where
// K < 0 around it (the Great Court), so the plan's tangent box leaves more than the unavoidable
// ring between a square and its circle. Returns the least clearance, or -1 (scale unchanged) when
// the box as given does not clear the hole.
double tightenHoleBox(std::array<double, 4>& scale, const std::function<Vec2(int)>& cornerAt,
                      const Polygon& hole, const Plan& plan, const PlanLifter& lifter,
                      const TriMesh& surface, const geodesic::DistanceSolver& solver,
                      double target);

}  // namespace egg::patching
