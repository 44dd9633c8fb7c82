#pragma once
// Mesh invariants shared by the samples tests: connectivity, manifoldness, orientation, quality.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

namespace egg::samples::testing {

struct MeshReport {
  int components = 0;       // face-connected components
  int complexVertices = 0;  // vertices with more than one boundary fan
  int boundaryLoops = 0;
  double minAngleDeg = 180.0;
  double meanEdge = 0.0;
  double maxEdge = 0.0;
  double minEdge = 1e300;
};

inline MeshReport inspect(const TriMesh& mesh) {
  MeshReport report;
  // Components by breadth-first search over faces.
  std::vector<int> seen(mesh.n_faces(), 0);
  for (auto start : mesh.faces()) {
    if (seen[start.idx()]) continue;
    ++report.components;
    std::queue<TriMesh::FaceHandle> queue;
    queue.push(start);
    seen[start.idx()] = 1;
    while (!queue.empty()) {
      const auto f = queue.front();
      queue.pop();
      for (auto g : mesh.ff_range(f)) {
        if (!seen[g.idx()]) {
          seen[g.idx()] = 1;
          queue.push(g);
        }
      }
    }
  }
  for (auto v : mesh.vertices()) {
    int boundaryOut = 0;
    for (auto h : mesh.voh_range(v)) boundaryOut += mesh.is_boundary(h) ? 1 : 0;
    if (boundaryOut > 1) ++report.complexVertices;
  }
  std::vector<int> visited(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || visited[h.idx()]) continue;
    ++report.boundaryLoops;
    auto g = h;
    do {
      visited[g.idx()] = 1;
      g = mesh.next_halfedge_handle(g);
    } while (g != h);
  }
  double sum = 0.0;
  for (auto e : mesh.edges()) {
    const double l = mesh.calc_edge_length(e);
    sum += l;
    report.maxEdge = std::max(report.maxEdge, l);
    report.minEdge = std::min(report.minEdge, l);
  }
  report.meanEdge = sum / double(mesh.n_edges());
  for (auto f : mesh.faces()) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) p[k++] = toEigen(mesh.point(v));
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi;
      report.minAngleDeg = std::min(report.minAngleDeg, angle);
    }
  }
  return report;
}

// Unit normal of face f from its circulator order (the orientation the mesh stores).
inline Eigen::Vector3d faceNormal(const TriMesh& mesh, TriMesh::FaceHandle f) {
  Eigen::Vector3d p[3];
  int k = 0;
  for (auto v : mesh.fv_range(f)) p[k++] = toEigen(mesh.point(v));
  return (p[1] - p[0]).cross(p[2] - p[0]).normalized();
}

inline Eigen::Vector3d faceCentroid(const TriMesh& mesh, TriMesh::FaceHandle f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (auto v : mesh.fv_range(f)) c += toEigen(mesh.point(v));
  return c / 3.0;
}

}  // namespace egg::samples::testing
