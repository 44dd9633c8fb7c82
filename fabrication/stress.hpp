#pragma once
// Stress check of Section 3.5.2: a lamella wrapped onto the surface bends about its weak axis with
// the normal curvature kappa_n of its centreline, sigma_B = E kappa t / 2 (the same under linear
// scaling), and twists with the geodesic torsion theta' of the surface, tau = G theta' t (thin
// rectangle, St Venant: T = G J theta', J = w t^3 / 3, tau_max = T t / J).
#include "core/materials/materials.hpp"

#include <Eigen/Core>
#include <vector>

namespace egg::fabrication {

// Curvature vector at every interior point of a polyline: the circle through the point and its two
// neighbours (Menger curvature, 1/R towards the centre; exact for points on a circle). The end
// points get their neighbour's value; fewer than three points give zeros.
std::vector<Eigen::Vector3d> polylineCurvature(const std::vector<Eigen::Vector3d>& points);

// Twist rate (rad/m) of the frame given by `normals` about the polyline, per segment: the angle
// between consecutive normals projected on the plane normal to the segment, over its length.
std::vector<double> polylineTwistRate(const std::vector<Eigen::Vector3d>& points,
                                      const std::vector<Eigen::Vector3d>& normals);

struct LamellaStress {
  double maxCurvaturePerM = 0.0;    // largest weak-axis curvature along the lamella
  double maxBendingStressPa = 0.0;  // E kappa t / 2
  double maxTwistRateRadPerM = 0.0;
  double maxTorsionStressPa = 0.0;  // G theta' t
  double stressRatio = 0.0;         // max(sigma / f_m, tau / f_v)
  bool fromSimulation = false;  // bending from the deployed centreline (else the traced geodesic)
  // Where along the lamella (arc length from its first point, m) each stress was measured: the
  // splice checks read them over a joint's length (maxStressOver).
  std::vector<double> bendingArcM, bendingPa, torsionArcM, torsionPa;
  std::vector<double>
      scarfRatios;  // per splice (fabricate): a scarf's stress over its strength, 0 for a plate
};

// The largest of `values` measured at arc lengths within [from, to]; with none there, the one
// measured nearest to the middle (0 when nothing was measured).
double maxStressOver(const std::vector<double>& arc, const std::vector<double>& values, double from,
                     double to);

// Bending: with `normals` (one per point) the normal curvature kappa . n, else the whole curvature
// (a deployed lamella is a geodesic: its curvature is normal curvature). Torsion: from `normals`
// when given, else zero. thicknessM is t; the material gives E, G, f_m, f_v.
// With windowM > 0 both are measured over that arc length instead of vertex by vertex: the circle
// through the points at s - window, s, s + window (still exact on a circle) and the turn of the
// normal from s - window to s + window. A geodesic traced on a triangle mesh kinks at every edge it
// crosses, and vertex-by-vertex curvature of such a polyline measures the mesh, not the lamella,
// which cannot bend over less than about its width anyway. A polyline with no vertex a window from
// both ends is measured over the window its most central vertex allows (the whole lamella), never
// vertex by vertex.
LamellaStress lamellaStress(const std::vector<Eigen::Vector3d>& centreline,
                            const std::vector<Eigen::Vector3d>* normals, double thicknessM,
                            const MaterialProperties& material, double windowM = 0.0);

// The window fabricate() measures over: twice the lamella width, and at least three median segments
// of the polyline (its resolution).
double curvatureWindowM(const std::vector<Eigen::Vector3d>& centreline, double lamellaWidthM);

}  // namespace egg::fabrication
