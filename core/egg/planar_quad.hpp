#pragma once
// The planar side of a patch (Section 2.4.2): the planar quadrilateral with the same side lengths
// as the geodesic quad on the surface and a free angle alpha_bar at corner 0, its convexity range
// (criterion iv), and the planar distance maps in closed form.
//
// Corner and family conventions used throughout core/egg:
//   corners c0, c1, c2, c3 in order around the quad; side k runs from corner k to corner k+1.
//   u-family: members from the start side c0->c3 (parameter u1) to the end side c1->c2 (u2);
//             (u1,u2) = (0,0) is side c0c1, (1,1) is side c3c2.
//   v-family: members from the start side c0->c1 (v1) to the end side c3->c2 (v2);
//             (v1,v2) = (0,0) is side c0c3, (1,1) is side c1c2.
//   Boundary parameters run at constant speed (criterion ii, Section 3.3.2).
#include <Eigen/Dense>

#include <array>
#include <optional>

namespace egg {

enum class Family { U = 0, V = 1 };

// Side lengths: sides[k] = length of side k (corner k to corner k+1), metres.
using QuadSides = std::array<double, 4>;

struct PlanarQuad {
  std::array<Eigen::Vector2d, 4> corners;  // c0 at the origin, c1 on the +x axis, counter-clockwise
  double alphaBar = 0.0;                   // inner angle at c0, radians
};

// The planar quad with the given sides and angle alpha_bar at c0, or nullopt when it cannot be
// closed (four-bar linkage out of reach) or is not strictly convex: every inner angle must lie in
// (minAngle, pi - minAngle) (minAngle = 0: plain convexity, criterion iv).
std::optional<PlanarQuad> planarQuad(const QuadSides& sides, double alphaBar,
                                     double minAngle = 0.0);

// Inner angles of a quad (radians, at c0..c3); negative/over-pi values flag a non-convex quad.
std::array<double, 4> innerAngles(const std::array<Eigen::Vector2d, 4>& corners);

// The interval of alpha_bar for which planarQuad exists (the lower bound of Problem 2.3 comes
// from here, Section 2.4.3). Endpoints are pulled inwards by `margin` radians so that every
// value of the returned interval gives a strictly convex quad. nullopt if no such angle exists.
struct AngleInterval {
  double lo = 0.0;
  double hi = 0.0;
};
std::optional<AngleInterval> convexAlphaRange(const QuadSides& sides, double margin = 1e-6,
                                              double minAngle = 0.0);

// Endpoints of a planar member of `family` with boundary parameters (x1, x2) in [0,1]:
// start point on the start side, end point on the end side (constant speed).
std::array<Eigen::Vector2d, 2> planarMember(const PlanarQuad& quad, Family family, double x1,
                                            double x2);

// Closed-form planar distance |start(x1) - end(x2)| (the planar distance map, Section 2.4.2).
double planarDistance(const PlanarQuad& quad, Family family, double x1, double x2);

// Corner indices of a family's sides: {start side from, start side to, end side from, end side to}.
std::array<int, 4> familyCorners(Family family);

}  // namespace egg
