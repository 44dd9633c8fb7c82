// Shortest connections along a non-convex boundary (Sections 4.5.3-4.5.4), on a distance map
// between samples of one closed boundary loop.
#include "core/geodesic/boundary_connections.hpp"

#include "core/errors.hpp"

#include <cmath>
#include <string>

namespace egg::geodesic {

void BoundaryConnectionOptions::validate() const {
  if (!std::isfinite(tolerance))
    throw InvalidInput("BoundaryConnectionOptions.tolerance must be finite");
}

std::vector<std::vector<int>> boundaryLoops(const TriMesh& mesh) {
  std::vector<std::vector<int>> loops;
  std::vector<char> visited(mesh.n_halfedges(), 0);
  for (auto start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || visited[start.idx()]) continue;
    std::vector<int> loop;
    auto h = start;
    do {
      visited[h.idx()] = 1;
      loop.push_back(mesh.from_vertex_handle(h).idx());
      h = mesh.next_halfedge_handle(h);
    } while (h != start && !visited[h.idx()] && loop.size() <= mesh.n_halfedges());
    loops.push_back(std::move(loop));
  }
  return loops;
}

BoundaryConnections findBoundaryConnections(const Eigen::MatrixXd& distanceMap,
                                            const std::vector<double>& arcLength, double loopLength,
                                            const std::vector<char>& bendsInward,
                                            const BoundaryConnectionOptions& options) {
  options.validate();
  const int n = static_cast<int>(arcLength.size());
  if (distanceMap.rows() != n || distanceMap.cols() != n) {
    throw InvalidInput("findBoundaryConnections: the distance map is " +
                       std::to_string(distanceMap.rows()) + " x " +
                       std::to_string(distanceMap.cols()) + " but there are " + std::to_string(n) +
                       " samples");
  }
  if (static_cast<int>(bendsInward.size()) != n) {
    throw InvalidInput("findBoundaryConnections: bendsInward has " +
                       std::to_string(bendsInward.size()) + " entries for " + std::to_string(n) +
                       " samples");
  }
  if (!(loopLength > 0.0))
    throw InvalidInput("findBoundaryConnections: the loop length must be positive");
  for (int i = 1; i < n; ++i) {
    if (!(arcLength[i] >= arcLength[i - 1]) || arcLength[i] > loopLength) {
      throw InvalidInput(
          "findBoundaryConnections: arc lengths must increase within [0, loop length]");
    }
  }
  const double tol = options.tolerance > 0.0 ? options.tolerance : 1e-9 * loopLength;
  BoundaryConnections result;
  result.alongBoundary.setConstant(n, n, false);
  result.invalid.setConstant(n, n, false);
  if (n < 3) return result;
  auto forward = [&](int x, int y) {  // boundary length from x to y in loop order
    const double d = arcLength[y] - arcLength[x];
    return d >= 0.0 ? d : d + loopLength;
  };
  // Eq. (4.6): D - B < eps, where B runs along the shorter way round. The boundary path must bend
  // towards the surface at an inner sample; along a straight (geodesic) stretch the connection is
  // a geodesic and a valid member, not a symptom of non-convexity.
  std::vector<char> marked(n, 0);
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      if (x == y) continue;
      const bool forwardShorter = forward(x, y) <= forward(y, x);
      const double along = forwardShorter ? forward(x, y) : forward(y, x);
      // D <= B always (the boundary path is a path on the surface), so Eq. (4.6) is |D - B| < eps.
      if (!(along - distanceMap(x, y) < tol)) continue;
      const int first = forwardShorter ? x : y, last = forwardShorter ? y : x;
      bool bends = false;
      for (int i = (first + 1) % n; i != last; i = (i + 1) % n) bends = bends || bendsInward[i];
      if (!bends) continue;
      result.alongBoundary(x, y) = true;
      for (int i = first;; i = (i + 1) % n) {
        marked[i] = 1;
        if (i == last) break;
      }
    }
  }
  // Non-convex segments: maximal runs of marked samples (cyclic), [t1, t2] of Section 4.5.3.
  int startOfRun = -1;
  for (int i = 0; i < n; ++i) {
    if (!marked[i] && marked[(i + 1) % n]) startOfRun = (i + 1) % n;
  }
  if (startOfRun < 0 && marked[0]) {
    result.nonConvexSegments.push_back({0, n - 1});  // the whole loop
  } else if (startOfRun >= 0) {
    for (int k = 0, i = startOfRun; k < n; ++k, i = (i + 1) % n) {
      if (marked[i] && !marked[(i + n - 1) % n]) result.nonConvexSegments.push_back({i, i});
      if (marked[i]) result.nonConvexSegments.back().second = i;
    }
  }
  // Connections running partly along a non-convex segment (Eq. 4.4-4.5). The thesis detects
  // them by the derivative of d(x,y) - d(Theta,y) in y vanishing, grown from the cores. With
  // exact distances on a mesh there is a sharper test of the same fact: a shortest connection can
  // touch the polyline boundary only at a vertex that bends inwards, and it passes through such a
  // vertex t exactly when d(x,t) + d(t,y) = d(x,y). (The derivative test also fires on collinear
  // samples along a straight side, whose connections are geodesics.)
  std::vector<int> contacts;
  for (const auto& [a, b] : result.nonConvexSegments) {
    for (int i = a;; i = (i + 1) % n) {
      if (bendsInward[i]) contacts.push_back(i);
      if (i == b) break;
    }
  }
  for (int x = 0; x < n; ++x) {
    for (int y = x + 1; y < n; ++y) {
      if (result.alongBoundary(x, y) || result.alongBoundary(y, x)) {
        result.invalid(x, y) = true;
        continue;
      }
      for (int t : contacts) {
        if (t == x || t == y) continue;
        if (distanceMap(x, t) + distanceMap(t, y) - distanceMap(x, y) < tol) {
          result.invalid(x, y) = true;
          break;
        }
      }
    }
  }
  // Connections are symmetric (Section 4.5.4: c(ix, iy) = c(iy, ix)).
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      if (result.invalid(x, y)) result.invalid(y, x) = true;
    }
  }
  return result;
}

BoundaryConnections findBoundaryConnections(const Eigen::MatrixXd& distanceMap,
                                            const std::vector<double>& arcLength, double loopLength,
                                            const BoundaryConnectionOptions& options) {
  return findBoundaryConnections(distanceMap, arcLength, loopLength,
                                 std::vector<char>(arcLength.size(), 1), options);
}

std::vector<char> boundaryBendsInward(const TriMesh& mesh, const std::vector<int>& loopVertices,
                                      double tolerance) {
  std::vector<char> result;
  result.reserve(loopVertices.size());
  for (int v : loopVertices) {
    if (v < 0 || v >= static_cast<int>(mesh.n_vertices())) {
      throw InvalidInput("boundaryBendsInward: vertex " + std::to_string(v) + " is out of range");
    }
    const auto vh = TriMesh::VertexHandle(v);
    double angle = 0.0;
    for (auto fh : mesh.vf_range(vh)) {
      const auto ids = faceVertices(mesh, fh.idx());
      int k = 0;
      while (ids[k] != v) ++k;
      const Eigen::Vector3d p = toEigen(mesh.point(vh));
      const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[(k + 1) % 3]))) - p;
      const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(ids[(k + 2) % 3]))) - p;
      angle += std::atan2(a.cross(b).norm(), a.dot(b));
    }
    result.push_back(angle > M_PI + tolerance ? 1 : 0);
  }
  return result;
}

}  // namespace egg::geodesic
