#include "core/mesh/laplacian.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace egg {
namespace {

Eigen::SparseMatrix<double> assemble(const TriMesh& mesh, bool cotangent) {
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(12 * mesh.n_faces());
  const double uniformHalf = 0.5 / std::sqrt(3.0);  // per face corner: half of 1/sqrt(3)
  for (auto fh : mesh.faces()) {
    const auto v = faceVertices(mesh, fh.idx());
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = toEigen(mesh.point(TriMesh::VertexHandle(v[k])));
    for (int k = 0; k < 3; ++k) {
      // The corner at k weights the opposite edge (k+1, k+2).
      const int i = v[(k + 1) % 3], j = v[(k + 2) % 3];
      double weight = uniformHalf;
      if (cotangent) {
        const Eigen::Vector3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
        const double sine = a.cross(b).norm();
        const double cosine = a.dot(b);
        weight =
            0.5 * std::clamp(sine > 0.0 ? cosine / sine : (cosine >= 0.0 ? 1e8 : -1e8), -1e8, 1e8);
      }
      entries.emplace_back(i, j, -weight);
      entries.emplace_back(j, i, -weight);
      entries.emplace_back(i, i, weight);
      entries.emplace_back(j, j, weight);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

}  // namespace

Eigen::SparseMatrix<double> cotanLaplacian(const TriMesh& mesh) { return assemble(mesh, true); }

Eigen::SparseMatrix<double> uniformLaplacian(const TriMesh& mesh) { return assemble(mesh, false); }

Eigen::VectorXd barycentricVertexAreas(const TriMesh& mesh) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto fh : mesh.faces()) {
    const auto v = faceVertices(mesh, fh.idx());
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(v[0])));
    const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(v[1])));
    const Eigen::Vector3d c = toEigen(mesh.point(TriMesh::VertexHandle(v[2])));
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (int k : v) area(k) += third;
  }
  return area;
}

Eigen::VectorXd mixedVoronoiAreas(const TriMesh& mesh) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto fh : mesh.faces()) {
    const auto v = faceVertices(mesh, fh.idx());
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = toEigen(mesh.point(TriMesh::VertexHandle(v[k])));
    double angle[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
      angle[k] = std::atan2(a.cross(b).norm(), a.dot(b));
    }
    const double faceArea = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    int obtuse = -1;
    for (int k = 0; k < 3; ++k)
      if (angle[k] > 0.5 * std::numbers::pi) obtuse = k;
    if (obtuse >= 0) {
      // The circumcentre lies outside: Voronoi regions would overlap neighbours (Meyer Fig. 4).
      for (int k = 0; k < 3; ++k) area(v[k]) += (k == obtuse ? 0.5 : 0.25) * faceArea;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const int q = (k + 1) % 3, r = (k + 2) % 3;
      const double cotQ = 1.0 / std::tan(angle[q]), cotR = 1.0 / std::tan(angle[r]);
      area(v[k]) += ((p[r] - p[k]).squaredNorm() * cotQ + (p[q] - p[k]).squaredNorm() * cotR) / 8.0;
    }
  }
  return area;
}

}  // namespace egg
