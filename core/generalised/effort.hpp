#pragma once
// The effort energy of grid members (thesis Sections 4.6.1 and 4.6.3). A member is a geodesic, so
// its curvature is all normal curvature, and its bending energy is the integral of kappa_n^2
// (Eq. 4.8). Euler's theorem gives kappa_n from the principal curvatures and the angle between the
// member's tangent and the first principal direction v1:
//   kappa_n = (kappa_1 - kappa_2) <t, v1>^2 + kappa_2.
// The effort of a member is that integral over its length (Eq. 4.10); the grid's effort energy is
// minus the variance sum of its members' efforts (Eq. 4.11), low when the grid holds both
// least-effort members (along hyperbolic valleys) and most-effort ones (over the bumps).
#include "core/curvature/curvature.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <vector>

namespace egg::generalised {

// The principal curvatures at one point (1/m) and the first principal direction (unit, tangent).
struct PrincipalCurvature {
  double kappa1 = 0.0;
  double kappa2 = 0.0;
  Eigen::Vector3d direction1 = Eigen::Vector3d::UnitX();
};

// kappa_n in the direction `tangent` (any length; it is projected onto the plane of the principal
// directions and normalised). Throws InvalidInput for a tangent along the normal.
double normalCurvature(const PrincipalCurvature& curvature, const Eigen::Vector3d& tangent);

// kappa_n at a surface point: the vertices' kappa_n in that direction (each from its own
// principal frame, so the sign of a principal direction never matters), interpolated
// barycentrically. `field` is computeCurvature(mesh) (its kappaMax / directionMax as kappa_1 /
// v1).
double normalCurvatureAt(const TriMesh& mesh, const CurvatureField& field,
                         const SurfacePoint& point, const Eigen::Vector3d& tangent);

// E_c of Eq. 4.10, discretised as in the thesis: (1 / l) sum_j kappa_n(q_j)^2 times half the
// lengths of the edges at q_j, the tangent at q_j the normalised mean of its edges (1/m^2).
// kappaN[j] is kappa_n at points[j] along that tangent, e.g. from memberTangents.
double memberEffort(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& kappaN);

// The tangents memberEffort assumes: the normalised mean of the unit edge vectors at each point
// (the one edge at an end). Throws InvalidInput for fewer than two points or a zero-length edge.
std::vector<Eigen::Vector3d> memberTangents(const std::vector<Eigen::Vector3d>& points);

// E_effort of Eq. 4.11: minus the sum of squared deviations of the members' efforts from their
// mean (1/m^4); 0 for fewer than two members.
double gridEffortEnergy(const std::vector<double>& memberEfforts);

}  // namespace egg::generalised
