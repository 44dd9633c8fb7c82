// Tangent sides round a hole (see hole_box.hpp).
#include "patching/hole_box.hpp"

#include "core/egg/patch.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>

namespace egg::patching {

double holeClearance(const Vec2& from, const Vec2& to, const Polygon& hole, const Plan& plan,
                     const PlanLifter& lifter, const TriMesh& surface,
                     const geodesic::DistanceSolver& solver) {
  const auto path = solver.path(geodesic::snapToSurface(surface, lifter.lift(from)),
                                geodesic::snapToSurface(surface, lifter.lift(to)));
  if (boundaryWrapTurning(surface, path.positions, path.bendVertices) >
      PatchOptions{}.boundaryWrapToleranceRad)
    return -std::numeric_limits<double>::infinity();
  double clearance = std::numeric_limits<double>::infinity();
  for (const auto& x : path.positions) {
    const Vec2 q = plan(x);
    clearance = std::min(clearance, insidePolygon(hole, q) ? -distanceToPolygon(hole, q)
                                                           : distanceToPolygon(hole, q));
  }
  return clearance;
}

double tightenHoleBox(std::array<double, 4>& scale, const std::function<Vec2(int)>& cornerAt,
                      const Polygon& hole, const Plan& plan, const PlanLifter& lifter,
                      const TriMesh& surface, const geodesic::DistanceSolver& solver,
                      double target) {
  const auto sideClearance = [&](int k) {
    return holeClearance(cornerAt(k), cornerAt((k + 1) % 4), hole, plan, lifter, surface, solver);
  };
  const auto feasible = [&](std::initializer_list<int> sides) {
    for (int k : sides)
      if (!(sideClearance(k) >= target)) return false;
    return true;
  };
  const double floor = 0.5;  // half the box: its sides cut through the hole
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k < (pass == 0 ? 1 : 4); ++k) {
      const auto set = [&](double s) {
        if (pass == 0)
          scale.fill(s);
        else
          scale[k] = s;
      };
      const std::initializer_list<int> all{0, 1, 2, 3};
      const auto ok = [&] { return pass == 0 ? feasible(all) : feasible({(k + 3) % 4, k}); };
      double hi = scale[k], lo = floor;
      set(hi);
      if (!ok()) return -1.0;  // the inflated box itself does not clear the hole: leave it as it is
      for (int it = 0; it < 10; ++it) {
        const double mid = 0.5 * (lo + hi);
        set(mid);
        if (ok())
          hi = mid;
        else
          lo = mid;
      }
      set(hi);
    }
  }
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 4; ++k) least = std::min(least, sideClearance(k));
  return least;
}

}  // namespace egg::patching
