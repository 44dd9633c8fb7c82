#include "fabrication/stress.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace egg::fabrication {

std::vector<Eigen::Vector3d> polylineCurvature(const std::vector<Eigen::Vector3d>& points) {
  const size_t n = points.size();
  std::vector<Eigen::Vector3d> kappa(n, Eigen::Vector3d::Zero());
  if (n < 3) return kappa;
  for (size_t i = 1; i + 1 < n; ++i) {
    // Circumcentre of (p0, p1, p2) relative to p1: with a = p0 - p1, b = p2 - p1,
    // c = ((|a|^2 b - |b|^2 a) x (a x b)) / (2 |a x b|^2); the curvature vector is c / |c|^2.
    const Eigen::Vector3d a = points[i - 1] - points[i], b = points[i + 1] - points[i];
    const Eigen::Vector3d axb = a.cross(b);
    const double den = 2.0 * axb.squaredNorm();
    if (den <= 1e-30 * std::pow(a.norm() * b.norm(), 2)) continue;  // straight: zero curvature
    const Eigen::Vector3d centre = (a.squaredNorm() * b - b.squaredNorm() * a).cross(axb) / den;
    kappa[i] = centre / centre.squaredNorm();
  }
  kappa[0] = kappa[1];
  kappa[n - 1] = kappa[n - 2];
  return kappa;
}

std::vector<double> polylineTwistRate(const std::vector<Eigen::Vector3d>& points,
                                      const std::vector<Eigen::Vector3d>& normals) {
  std::vector<double> rate;
  if (points.size() < 2 || normals.size() != points.size()) return rate;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const Eigen::Vector3d segment = points[i + 1] - points[i];
    const double length = segment.norm();
    if (length <= 0.0) {
      rate.push_back(0.0);
      continue;
    }
    const Eigen::Vector3d t = segment / length;
    const Eigen::Vector3d n0 = normals[i] - normals[i].dot(t) * t, n1 = normals[i + 1] - normals[i + 1].dot(t) * t;
    const double angle = std::atan2(t.dot(n0.cross(n1)), n0.dot(n1));
    rate.push_back(angle / length);
  }
  return rate;
}

LamellaStress lamellaStress(const std::vector<Eigen::Vector3d>& centreline, const std::vector<Eigen::Vector3d>* normals,
                            double thicknessM, const MaterialProperties& material) {
  LamellaStress s;
  const auto kappa = polylineCurvature(centreline);
  const bool useNormals = normals && normals->size() == centreline.size();
  for (size_t i = 0; i < kappa.size(); ++i) {
    const double k = useNormals ? std::abs(kappa[i].dot((*normals)[i].normalized())) : kappa[i].norm();
    s.maxCurvature_1_m = std::max(s.maxCurvature_1_m, k);
  }
  if (useNormals) {
    for (double r : polylineTwistRate(centreline, *normals)) s.maxTwistRate_rad_m = std::max(s.maxTwistRate_rad_m, std::abs(r));
  }
  s.maxBendingStress_pa = material.youngs_modulus_pa * s.maxCurvature_1_m * thicknessM / 2.0;
  s.maxTorsionStress_pa = material.shear_modulus_pa * s.maxTwistRate_rad_m * thicknessM;
  const double bendingRatio = material.bending_strength_pa > 0 ? s.maxBendingStress_pa / material.bending_strength_pa : 0.0;
  const double torsionRatio = material.shear_strength_pa > 0 ? s.maxTorsionStress_pa / material.shear_strength_pa : 0.0;
  s.stressRatio = std::max(bendingRatio, torsionRatio);
  return s;
}

}  // namespace egg::fabrication
