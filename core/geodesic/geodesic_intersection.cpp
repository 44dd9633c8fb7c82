// Intersections of shortest geodesics from summed distance fields (Section 4.5.2), and of traced
// polylines (the exact check).
#include "core/geodesic/geodesic_intersection.hpp"

#include "core/errors.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace egg::geodesic {

void GeodesicIntersectionOptions::validate() const {
  if (!std::isfinite(maxExcess))
    throw InvalidInput("GeodesicIntersectionOptions.maxExcess must be finite");
  if (fitRings < 1 || fitRings > 4)
    throw InvalidInput("GeodesicIntersectionOptions.fitRings must be in [1, 4]");
}

GeodesicIntersection intersectGeodesics(const TriMesh& mesh, const std::vector<double>& dA,
                                        const std::vector<double>& dB,
                                        const std::vector<double>& dC,
                                        const std::vector<double>& dD, double lengthAB,
                                        double lengthCD,
                                        const GeodesicIntersectionOptions& options) {
  options.validate();
  const size_t n = mesh.n_vertices();
  for (const auto* field : {&dA, &dB, &dC, &dD}) {
    if (field->size() != n) {
      throw InvalidInput("intersectGeodesics: a distance field has " +
                         std::to_string(field->size()) + " values, the mesh has " +
                         std::to_string(n) + " vertices");
    }
  }
  if (!(lengthAB > 0.0) || !(lengthCD > 0.0) || !std::isfinite(lengthAB) ||
      !std::isfinite(lengthCD)) {
    throw InvalidInput("intersectGeodesics: the geodesic lengths must be positive and finite");
  }
  GeodesicIntersection result;
  const double target = lengthAB + lengthCD;
  auto excess = [&](int v) { return dA[v] + dB[v] + dC[v] + dD[v] - target; };
  // Eq. (4.1)+(4.2): the summed field is >= d(A,B) + d(C,D), with equality only on both geodesics.
  double best = std::numeric_limits<double>::infinity();
  for (size_t v = 0; v < n; ++v) {
    const double e = excess(static_cast<int>(v));
    if (e < best) {
      best = e;
      result.nearestVertex = static_cast<int>(v);
    }
  }
  if (result.nearestVertex < 0) return result;  // all infinite: different components
  const int v0 = result.nearestVertex;
  result.vertexExcess = best;
  const auto vh0 = TriMesh::VertexHandle(v0);
  const Eigen::Vector3d p0 = toEigen(mesh.point(vh0));

  double meanEdge = 0.0;
  int edgeCount = 0;
  for (auto w : mesh.vv_range(vh0)) {
    meanEdge += (toEigen(mesh.point(w)) - p0).norm();
    ++edgeCount;
  }
  meanEdge = edgeCount > 0 ? meanEdge / edgeCount : 0.0;
  const double maxExcess = options.maxExcess > 0.0
                               ? options.maxExcess
                               : 2.0 * meanEdge * meanEdge / std::min(lengthAB, lengthCD);

  // Local (u, v) coordinates: the tangent plane of the area-weighted vertex normal.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (auto f : mesh.vf_range(vh0)) {
    const auto ids = faceVertices(mesh, f.idx());
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[0])));
    const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(ids[1])));
    const Eigen::Vector3d c = toEigen(mesh.point(TriMesh::VertexHandle(ids[2])));
    normal += (b - a).cross(c - a);
  }
  Eigen::Vector3d refined = p0;
  result.refinedExcess = best;
  std::set<int> ring = {v0};
  std::set<int> faces;
  // Second-order refinement: least-squares paraboloid s(u,v) = a u^2 + b uv + c v^2 + d u + e v + f
  // over the vertex rings, minimised in closed form (Section 4.5.2). The thesis fits one ring; a
  // ring of 6-7 vertices barely determines 6 coefficients, so when that fit is not convex or its
  // minimum leaves the ring we widen it by a ring (at most twice).
  bool refinedOk = false;
  for (int rings = 1; rings <= options.fitRings + 2 && !refinedOk; ++rings) {
    std::set<int> grown = ring;
    for (int v : ring) {
      for (auto w : mesh.vv_range(TriMesh::VertexHandle(v))) grown.insert(w.idx());
    }
    ring.swap(grown);
    if (rings < options.fitRings || normal.norm() == 0.0 || ring.size() < 6) continue;
    const Eigen::Vector3d nrm = normal.normalized();
    const Eigen::Vector3d u = nrm.unitOrthogonal();
    const Eigen::Vector3d w = nrm.cross(u);
    Eigen::MatrixXd design(ring.size(), 6);
    Eigen::VectorXd values(ring.size());
    double radius = 0.0;
    int row = 0;
    bool finite = true;
    for (int v : ring) {
      const Eigen::Vector3d d = toEigen(mesh.point(TriMesh::VertexHandle(v))) - p0;
      const double x = d.dot(u) / meanEdge, y = d.dot(w) / meanEdge;  // scaled for conditioning
      radius = std::max(radius, std::hypot(x, y));
      design.row(row) << x * x, x * y, y * y, x, y, 1.0;
      values[row] = excess(v);
      finite = finite && std::isfinite(values[row]);
      ++row;
    }
    if (!finite) break;
    const Eigen::VectorXd c = design.colPivHouseholderQr().solve(values);
    Eigen::Matrix2d hessian;
    hessian << 2 * c[0], c[1], c[1], 2 * c[2];
    const Eigen::Vector2d gradient(c[3], c[4]);
    if (!(hessian.determinant() > 0.0 && hessian(0, 0) > 0.0)) continue;
    const Eigen::Vector2d minimum = hessian.ldlt().solve(-gradient);
    if (!(minimum.norm() <= 0.75 * radius)) continue;
    const double predicted = c[0] * minimum.x() * minimum.x() + c[1] * minimum.x() * minimum.y() +
                             c[2] * minimum.y() * minimum.y() + c[3] * minimum.x() +
                             c[4] * minimum.y() + c[5];
    refined = p0 + meanEdge * (minimum.x() * u + minimum.y() * w);
    result.refinedExcess = std::max(0.0, predicted);
    refinedOk = true;
  }
  for (int v : ring) {
    for (auto f : mesh.vf_range(TriMesh::VertexHandle(v))) faces.insert(f.idx());
  }
  // Back onto the surface: the closest point on the neighbourhood's faces.
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int f : faces) {
    const auto ids = faceVertices(mesh, f);
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[0])));
    const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(ids[1])));
    const Eigen::Vector3d c = toEigen(mesh.point(TriMesh::VertexHandle(ids[2])));
    const Eigen::Vector3d bc = closestPointBarycentric(refined, a, b, c);
    const double d = (bc[0] * a + bc[1] * b + bc[2] * c - refined).squaredNorm();
    if (d < bestDistance) {
      bestDistance = d;
      result.point.face = f;
      result.point.barycentric = bc;
    }
  }
  result.position = position(mesh, result.point);
  result.found = result.refinedExcess <= maxExcess;
  return result;
}

PolylineCrossing intersectPolylines(const std::vector<Eigen::Vector3d>& first,
                                    const std::vector<Eigen::Vector3d>& second, double tolerance) {
  PolylineCrossing crossing;
  double arcFirst = 0.0;
  for (size_t i = 0; i + 1 < first.size(); ++i) {
    const Eigen::Vector3d p = first[i], d1 = first[i + 1] - first[i];
    double arcSecond = 0.0;
    for (size_t j = 0; j + 1 < second.size(); ++j) {
      const Eigen::Vector3d q = second[j], d2 = second[j + 1] - second[j];
      // Closest points of two segments (Ericson 5.1.9).
      const Eigen::Vector3d r = p - q;
      const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
      double s = 0.0, t = 0.0;
      if (a > 0.0 && e > 0.0) {
        const double b = d1.dot(d2), c = d1.dot(r), denom = a * e - b * b;
        s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
        t = (b * s + f) / e;
        if (t < 0.0) {
          t = 0.0;
          s = std::clamp(-c / a, 0.0, 1.0);
        } else if (t > 1.0) {
          t = 1.0;
          s = std::clamp((b - c) / a, 0.0, 1.0);
        }
      }
      const Eigen::Vector3d c1 = p + s * d1, c2 = q + t * d2;
      if ((c1 - c2).norm() <= tolerance) {
        crossing.found = true;
        crossing.position = 0.5 * (c1 + c2);
        crossing.arcLengthFirst = arcFirst + s * std::sqrt(a);
        crossing.arcLengthSecond = arcSecond + t * std::sqrt(e);
        return crossing;
      }
      arcSecond += std::sqrt(e);
    }
    arcFirst += std::sqrt(d1.squaredNorm());
  }
  return crossing;
}

}  // namespace egg::geodesic
