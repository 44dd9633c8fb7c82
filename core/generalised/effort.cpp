// Effort energy of grid members (Sections 4.6.1, 4.6.3): see effort.hpp.
#include "core/generalised/effort.hpp"

#include "core/errors.hpp"

#include <cmath>
#include <string>

namespace egg::generalised {

double normalCurvature(const PrincipalCurvature& curvature, const Eigen::Vector3d& tangent) {
  const Eigen::Vector3d v1 = curvature.direction1.normalized();
  // The tangent is taken as given, normalised: it must lie in the tangent plane
  // (normalCurvatureAt projects it there; a polyline's on the surface does to its discretisation).
  const double length = tangent.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw InvalidInput("normalCurvature: the tangent must be a finite, non-zero vector");
  const double c = v1.dot(tangent) / length;
  return (curvature.kappa1 - curvature.kappa2) * c * c + curvature.kappa2;
}

double normalCurvatureAt(const TriMesh& mesh, const CurvatureField& field,
                         const SurfacePoint& point, const Eigen::Vector3d& tangent) {
  if (point.face < 0 || point.face >= static_cast<int>(mesh.n_faces()))
    throw InvalidInput("normalCurvatureAt: face " + std::to_string(point.face) +
                       " is not a face of the mesh");
  if (field.kappaMax.size() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidInput("normalCurvatureAt: the curvature field is not the mesh's");
  int k = 0;
  double value = 0.0;
  for (auto v : mesh.fv_range(mesh.face_handle(point.face))) {
    if (k == 3) break;
    const int i = v.idx();
    // The tangent in this vertex's tangent plane, so that <t, v1>^2 + <t, v2>^2 = 1 there.
    const Eigen::Vector3d n = field.normals[i];
    const Eigen::Vector3d t = tangent - tangent.dot(n) * n;
    if (!(t.norm() > 1e-12 * tangent.norm()))
      throw InvalidInput("normalCurvatureAt: the tangent is along the surface normal at vertex " +
                         std::to_string(i));
    value += point.barycentric[k] *
             normalCurvature({field.kappaMax[i], field.kappaMin[i], field.directionMax[i]}, t);
    ++k;
  }
  return value;
}

std::vector<Eigen::Vector3d> memberTangents(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 2) throw InvalidInput("memberTangents: a member needs at least two points");
  std::vector<Eigen::Vector3d> unit(points.size() - 1);
  for (size_t j = 0; j + 1 < points.size(); ++j) {
    const Eigen::Vector3d e = points[j + 1] - points[j];
    if (!(e.norm() > 0.0))
      throw InvalidInput("memberTangents: points " + std::to_string(j) + " and " +
                         std::to_string(j + 1) + " coincide");
    unit[j] = e.normalized();
  }
  std::vector<Eigen::Vector3d> tangents(points.size());
  tangents.front() = unit.front();
  tangents.back() = unit.back();
  for (size_t j = 1; j + 1 < points.size(); ++j) tangents[j] = (unit[j - 1] + unit[j]).normalized();
  return tangents;
}

double memberEffort(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& kappaN) {
  if (points.size() < 2 || kappaN.size() != points.size())
    throw InvalidInput("memberEffort: " + std::to_string(kappaN.size()) + " curvatures for " +
                       std::to_string(points.size()) + " points (at least two)");
  double length = 0.0, sum = 0.0;
  for (size_t j = 0; j + 1 < points.size(); ++j) {
    const double h = (points[j + 1] - points[j]).norm();
    length += h;
    sum += 0.5 * h * (kappaN[j] * kappaN[j] + kappaN[j + 1] * kappaN[j + 1]);
  }
  if (!(length > 0.0)) throw InvalidInput("memberEffort: the member has no length");
  return sum / length;
}

double gridEffortEnergy(const std::vector<double>& memberEfforts) {
  if (memberEfforts.size() < 2) return 0.0;
  double mean = 0.0;
  for (double e : memberEfforts) mean += e;
  mean /= static_cast<double>(memberEfforts.size());
  double energy = 0.0;
  for (double e : memberEfforts) energy -= (e - mean) * (e - mean);
  return energy;
}

}  // namespace egg::generalised
