#pragma once
// Distance maps (Section 2.4.2): for one family, the geodesic distance between every pair of
// boundary points (x1 on the start side, x2 on the end side) sampled on a regular grid in [0,1]^2.
// The surface maps D_u, D_v come from the geodesic engine (patch_maps.hpp); the planar maps are in
// closed form (planar_quad.hpp). Both are read as the piecewise-linear interpolant over the grid
// cells split along the anti-diagonal, the same interpolant the cladding functions intersect.
#include "core/egg/planar_quad.hpp"

#include <vector>

namespace egg {

struct DistanceMap {
  int n1 = 0;                  // samples along the start side, x1_i = i / (n1 - 1)
  int n2 = 0;                  // samples along the end side, x2_j = j / (n2 - 1)
  std::vector<double> values;  // values[i * n2 + j] = d(x1_i, x2_j), metres

  DistanceMap() = default;
  DistanceMap(int samples1, int samples2);
  double& at(int i, int j) { return values[static_cast<size_t>(i) * n2 + j]; }
  double at(int i, int j) const { return values[static_cast<size_t>(i) * n2 + j]; }
  // Piecewise-linear interpolation at (x1, x2) in [0,1]^2 (anti-diagonal cell split).
  double interpolate(double x1, double x2) const;
};

// Everything the planar side of the solver needs to know about a surface patch.
struct PatchDistanceMaps {
  DistanceMap u;              // D_u(u1, u2)
  DistanceMap v;              // D_v(v1, v2)
  QuadSides sides{};          // geodesic side lengths (boundary k from corner k to k+1), metres
  double diagonalE = 0.0;     // e = d(c0, c2), metres
  double diagonalF = 0.0;     // f = d(c1, c3), metres
  double alphaSpatial = 0.0;  // inner angle of the surface patch at c0 (the "unrolled" alpha_bar)
  int propagations = 0;       // exact source fields spent on both maps (at most 2 x resolution)

  const DistanceMap& map(Family family) const { return family == Family::U ? u : v; }
  // Throws InvalidInput when maps are too small, sizes disagree or values are not finite.
  void validate() const;
};

// The planar distance map D_bar(alpha_bar) sampled on the same grid as `like`.
DistanceMap planarDistanceMap(const PlanarQuad& quad, Family family, int n1, int n2);

// Planar diagonals e_bar = |c0 c2|, f_bar = |c1 c3|.
double planarDiagonalE(const PlanarQuad& quad);
double planarDiagonalF(const PlanarQuad& quad);

// Inequality (2.2): (e - e_bar)(f - f_bar), negative when the maps can intersect properly.
double diagonalProduct(const PatchDistanceMaps& maps, const PlanarQuad& quad);

}  // namespace egg
