#include "fabrication/stress.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

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
    const Eigen::Vector3d n0 = normals[i] - normals[i].dot(t) * t,
                          n1 = normals[i + 1] - normals[i + 1].dot(t) * t;
    const double angle = std::atan2(t.dot(n0.cross(n1)), n0.dot(n1));
    rate.push_back(angle / length);
  }
  return rate;
}

namespace {

void finish(LamellaStress& s, double thicknessM, const MaterialProperties& material) {
  s.maxBendingStressPa = material.youngsModulusPa * s.maxCurvaturePerM * thicknessM / 2.0;
  s.maxTorsionStressPa = material.shearModulusPa * s.maxTwistRateRadPerM * thicknessM;
  const double bendingRatio =
      material.bendingStrengthPa > 0 ? s.maxBendingStressPa / material.bendingStrengthPa : 0.0;
  const double torsionRatio =
      material.shearStrengthPa > 0 ? s.maxTorsionStressPa / material.shearStrengthPa : 0.0;
  s.stressRatio = std::max(bendingRatio, torsionRatio);
}

}  // namespace

double curvatureWindowM(const std::vector<Eigen::Vector3d>& centreline, double lamellaWidthM) {
  std::vector<double> segments;
  for (size_t i = 0; i + 1 < centreline.size(); ++i)
    segments.push_back((centreline[i + 1] - centreline[i]).norm());
  double median = 0.0;
  if (!segments.empty()) {
    std::nth_element(segments.begin(), segments.begin() + segments.size() / 2, segments.end());
    median = segments[segments.size() / 2];
  }
  return std::max(2.0 * lamellaWidthM, 3.0 * median);
}

LamellaStress lamellaStress(const std::vector<Eigen::Vector3d>& centreline,
                            const std::vector<Eigen::Vector3d>* normals, double thicknessM,
                            const MaterialProperties& material, double windowM) {
  LamellaStress s;
  const bool useNormals = normals && normals->size() == centreline.size();
  const size_t n = centreline.size();
  if (windowM > 0.0 && n >= 3) {
    // For every vertex i the vertices j < i and k > i at least a window away along the polyline
    // (the nearest such): the circle through j, i, k. Vertices, not interpolated points, so that a
    // polyline inscribed in a circle still gives its exact curvature.
    std::vector<double> arc(n, 0.0);
    for (size_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + (centreline[i] - centreline[i - 1]).norm();
    // A lamella shorter than two windows (or a polyline whose vertices crowd at one end) has no
    // vertex a window from both ends: the window shrinks to what its most central vertex allows,
    // and the whole lamella is the window. Falling back to vertex by vertex there measured the
    // Lilium's base side (vertices 1 mm apart whose mesh normals differ by 0.09 rad) at 41 rad/m,
    // 197 times the shear strength.
    double central = 0.0;
    for (size_t i = 1; i + 1 < n; ++i)
      central = std::max(central, std::min(arc[i], arc[n - 1] - arc[i]));
    if (central > 0.0) windowM = std::min(windowM, central);
    bool measured = false;
    size_t j = 0, k = 0;
    for (size_t i = 1; i + 1 < n; ++i) {
      if (arc[i] < windowM || arc[n - 1] - arc[i] < windowM) continue;
      while (j + 1 < i && arc[i] - arc[j + 1] >= windowM) ++j;
      k = std::max(k, i + 1);
      while (k + 1 < n && arc[k] - arc[i] < windowM) ++k;
      const Eigen::Vector3d kappa =
          polylineCurvature({centreline[j], centreline[i], centreline[k]})[1];
      measured = true;
      double curvature = kappa.norm();
      if (useNormals) {
        curvature = std::abs(kappa.dot((*normals)[i].normalized()));
        // The turn of the normal from j to k about the chord, over the arc between them.
        const double rate =
            polylineTwistRate({centreline[j], centreline[k]}, {(*normals)[j], (*normals)[k]})[0];
        const double chord = (centreline[k] - centreline[j]).norm();
        const double twist = std::abs(rate) * chord / (arc[k] - arc[j]);
        s.maxTwistRateRadPerM = std::max(s.maxTwistRateRadPerM, twist);
        s.torsionArcM.push_back(arc[i]);
        s.torsionPa.push_back(material.shearModulusPa * twist * thicknessM);
      }
      s.maxCurvaturePerM = std::max(s.maxCurvaturePerM, curvature);
      s.bendingArcM.push_back(arc[i]);
      s.bendingPa.push_back(material.youngsModulusPa * curvature * thicknessM / 2.0);
    }
    if (measured) {
      finish(s, thicknessM, material);
      return s;
    }
  }
  const auto kappa = polylineCurvature(centreline);
  double along = 0.0;
  for (size_t i = 0; i < kappa.size(); ++i) {
    if (i > 0) along += (centreline[i] - centreline[i - 1]).norm();
    const double k =
        useNormals ? std::abs(kappa[i].dot((*normals)[i].normalized())) : kappa[i].norm();
    s.maxCurvaturePerM = std::max(s.maxCurvaturePerM, k);
    s.bendingArcM.push_back(along);
    s.bendingPa.push_back(material.youngsModulusPa * k * thicknessM / 2.0);
  }
  if (useNormals) {
    const auto rates = polylineTwistRate(centreline, *normals);
    along = 0.0;
    for (size_t i = 0; i < rates.size(); ++i) {
      const double length = (centreline[i + 1] - centreline[i]).norm();
      s.maxTwistRateRadPerM = std::max(s.maxTwistRateRadPerM, std::abs(rates[i]));
      s.torsionArcM.push_back(along + length / 2.0);
      s.torsionPa.push_back(material.shearModulusPa * std::abs(rates[i]) * thicknessM);
      along += length;
    }
  }
  finish(s, thicknessM, material);
  return s;
}

double maxStressOver(const std::vector<double>& arc, const std::vector<double>& values, double from,
                     double to) {
  double best = 0.0, nearest = 0.0, nearestGap = std::numeric_limits<double>::infinity();
  bool inside = false;
  const double middle = (from + to) / 2.0;
  for (size_t i = 0; i < arc.size() && i < values.size(); ++i) {
    if (arc[i] >= from && arc[i] <= to) best = std::max(best, values[i]), inside = true;
    if (std::abs(arc[i] - middle) < nearestGap)
      nearestGap = std::abs(arc[i] - middle), nearest = values[i];
  }
  return inside ? best : nearest;
}

}  // namespace egg::fabrication
