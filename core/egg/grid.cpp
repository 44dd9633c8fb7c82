#include "core/egg/grid.hpp"

#include "core/egg/member_trace.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"
#include "core/geodesic/geodesic_intersection.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <set>

namespace egg {

void GridOptions::validate() const {
  if (!(lengthTolerance > 0.0)) throw InvalidInput("grid.length_tolerance must be > 0");
  if (bracketSamples < 3) throw InvalidInput("grid.bracket_samples must be >= 3");
  if (maxSecantSteps < 1) throw InvalidInput("grid.max_secant_steps must be >= 1");
  if (maxStripTraces < 1) throw InvalidInput("grid.max_strip_traces must be >= 1");
  if (!(anchorCurvatureFraction >= 0.0 && anchorCurvatureFraction <= 1.0))
    throw InvalidInput("grid.anchor_curvature_fraction must lie in [0, 1]");
}

int countNotches(const EggGrid& grid, double minimumM) {
  int count = 0;
  for (const auto& c : grid.connections)
    count += (std::abs(c.notchU) > minimumM) + (std::abs(c.notchV) > minimumM);
  return count;
}

bool intersectSegments(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1, double& t, double& s,
                       double slack) {
  const Eigen::Vector2d r = a1 - a0, q = b1 - b0, w = b0 - a0;
  const double denom = r.x() * q.y() - r.y() * q.x();
  if (std::abs(denom) <= 1e-300) return false;
  t = (w.x() * q.y() - w.y() * q.x()) / denom;
  s = (w.x() * r.y() - w.y() * r.x()) / denom;
  return t >= -slack && t <= 1 + slack && s >= -slack && s <= 1 + slack;
}

namespace {

double polylineLength(const std::vector<Eigen::Vector3d>& line) {
  double length = 0.0;
  for (size_t k = 1; k < line.size(); ++k) length += (line[k] - line[k - 1]).norm();
  return length;
}

std::vector<Eigen::Vector3d> sidePolyline(const Patch& patch, int side, bool reversed) {
  std::vector<Eigen::Vector3d> line;
  for (int v : patch.sides[side])
    line.push_back(toEigen(patch.mesh.point(TriMesh::VertexHandle(v))));
  if (reversed) std::reverse(line.begin(), line.end());
  return line;
}

// Area-weighted vertex normal (the faces around a boundary vertex are all inside the patch).
Eigen::Vector3d vertexNormal(const TriMesh& mesh, int vertex) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto fh : mesh.vf_range(TriMesh::VertexHandle(vertex))) {
    const auto ids = faceVertices(mesh, fh.idx());
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[0])));
    sum += (toEigen(mesh.point(TriMesh::VertexHandle(ids[1]))) - a)
               .cross(toEigen(mesh.point(TriMesh::VertexHandle(ids[2]))) - a);
  }
  return sum.normalized();
}

std::vector<Eigen::Vector3d> sideNormals(const Patch& patch, int side, bool reversed) {
  std::vector<Eigen::Vector3d> normals;
  for (int v : patch.sides[side]) normals.push_back(vertexNormal(patch.mesh, v));
  if (reversed) std::reverse(normals.begin(), normals.end());
  return normals;
}

// Normal at the polyline point nearest to `p`.
Eigen::Vector3d nearestNormal(const GridMember& m, const Eigen::Vector3d& p) {
  size_t best = 0;
  for (size_t k = 1; k < m.spatial.size(); ++k)
    if ((m.spatial[k] - p).squaredNorm() < (m.spatial[best] - p).squaredNorm()) best = k;
  return m.normals[best];
}

// Curvature maxima along a side (resampled, three-point circles), as arc lengths from its start.
std::vector<double> boundaryCurvatureMaxima(const std::vector<Eigen::Vector3d>& line,
                                            double fraction) {
  const double total = polylineLength(line);
  constexpr int samples = 65;
  std::vector<Eigen::Vector3d> points;
  size_t seg = 1;
  double before = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double s = total * k / (samples - 1);
    while (seg + 1 < line.size() && before + (line[seg] - line[seg - 1]).norm() < s)
      before += (line[seg] - line[seg - 1]).norm(), ++seg;
    const double length = (line[seg] - line[seg - 1]).norm();
    const double t = length > 0 ? std::clamp((s - before) / length, 0.0, 1.0) : 0.0;
    points.push_back(line[seg - 1] + t * (line[seg] - line[seg - 1]));
  }
  std::vector<double> curvature(samples, 0.0);
  for (int k = 1; k + 1 < samples; ++k) {
    const Eigen::Vector3d a = points[k - 1], b = points[k], c = points[k + 1];
    const double area2 = (b - a).cross(c - a).norm();
    const double denom = (b - a).norm() * (c - b).norm() * (c - a).norm();
    curvature[k] = denom > 0 ? 2.0 * area2 / denom : 0.0;
  }
  std::vector<double> smooth(curvature);
  for (int k = 2; k + 2 < samples; ++k)
    smooth[k] = (curvature[k - 2] + 2 * curvature[k - 1] + 3 * curvature[k] + 2 * curvature[k + 1] +
                 curvature[k + 2]) /
                9.0;
  const double largest = *std::max_element(smooth.begin() + 3, smooth.end() - 3);
  std::vector<double> maxima;
  if (largest <= 1e-12) return maxima;  // a straight side: nothing to anchor
  for (int k = 6; k + 6 < samples; ++k)
    if (smooth[k] > smooth[k - 1] && smooth[k] >= smooth[k + 1] && smooth[k] >= fraction * largest)
      maxima.push_back(total * k / (samples - 1));
  return maxima;
}

}  // namespace

EggGrid buildGrid(const Patch& patch, const geodesic::DistanceSolver& solver,
                  const PlanarQuad& quad, const FamilyMembers& u, const FamilyMembers& v,
                  const GridOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (u.x1.size() < 2 || v.x1.size() < 2)
    throw InvalidInput("grid: each family needs at least its two boundary members");
  EggGrid grid;
  grid.quad = quad;
  std::atomic<int> propagations{0};
  for (const FamilyMembers* family : {&u, &v}) {
    auto& members = family->family == Family::U ? grid.u : grid.v;
    const int count = static_cast<int>(family->x1.size());
    members.resize(count);
    for (int i = 0; i < count; ++i) {
      GridMember& m = members[i];
      m.family = family->family;
      m.index = i;
      m.boundary = i == 0 || i == count - 1;
      m.x1 = m.boundary ? (i == 0 ? 0.0 : 1.0) : family->x1[i];
      m.x2 = m.boundary ? m.x1 : family->x2[i];
    }
    // Boundary members are the sides themselves (u: c0c1 and c3c2; v: c0c3 and c1c2).
    const bool isU = family->family == Family::U;
    members.front().spatial = isU ? sidePolyline(patch, 0, false) : sidePolyline(patch, 3, true);
    members.back().spatial = isU ? sidePolyline(patch, 2, true) : sidePolyline(patch, 1, false);
    members.front().normals = isU ? sideNormals(patch, 0, false) : sideNormals(patch, 3, true);
    members.back().normals = isU ? sideNormals(patch, 2, true) : sideNormals(patch, 1, false);
  }
  // Inner members of both families in one parallel loop (one or two propagations each).
  std::vector<GridMember*> inner;
  for (auto* members : {&grid.u, &grid.v})
    for (auto& m : *members)
      if (!m.boundary) inner.push_back(&m);
  tbb::parallel_for(0, static_cast<int>(inner.size()), [&](int k) {
    traceInnerMember(patch, solver, quad, *inner[k], options, propagations);
  });
  for (auto* members : {&grid.u, &grid.v})
    for (auto& m : *members) {
      const auto ends = planarMember(quad, m.family, m.x1, m.x2);
      m.planarStart = ends[0];
      m.planarEnd = ends[1];
      m.planarLength = (ends[1] - ends[0]).norm();
      m.spatialLength = polylineLength(m.spatial);
      grid.maxLengthMismatch = std::max(
          grid.maxLengthMismatch, std::abs(m.spatialLength - m.planarLength) / m.planarLength);
    }
  grid.propagations = propagations;

  // Connections: every u member meets every v member once.
  const int nu = static_cast<int>(grid.u.size()), nv = static_cast<int>(grid.v.size());
  grid.connections.resize(static_cast<size_t>(nu) * nv);
  tbb::parallel_for(0, nu, [&](int i) {
    const GridMember& mu = grid.u[i];
    for (int j = 0; j < nv; ++j) {
      const GridMember& mv = grid.v[j];
      GridConnection& c = grid.connections[static_cast<size_t>(i) * nv + j];
      c.memberU = i, c.memberV = j;
      c.onBoundary = mu.boundary || mv.boundary;
      double t = 0, s = 0;
      if (!intersectSegments(mu.planarStart, mu.planarEnd, mv.planarStart, mv.planarEnd, t, s,
                             1e-6))
        throw SolverFailure("grid: planar members u" + std::to_string(i) + " and v" +
                            std::to_string(j) + " do not cross");
      t = std::clamp(t, 0.0, 1.0), s = std::clamp(s, 0.0, 1.0);
      c.planar = mu.planarStart + t * (mu.planarEnd - mu.planarStart);
      c.sBarU = t * mu.planarLength;
      c.sBarV = s * mv.planarLength;
      if (c.onBoundary) {
        // Boundary correspondence (criterion ii): the connection sits at the inner member's end,
        // at the same boundary parameter on the surface and in the plane.
        if (mu.boundary && mv.boundary) {
          c.sU = i == 0 ? (j == 0 ? 0.0 : mu.spatialLength) : (j == 0 ? 0.0 : mu.spatialLength);
          c.sV = j == 0 ? (i == 0 ? 0.0 : mv.spatialLength) : (i == 0 ? 0.0 : mv.spatialLength);
          c.spatial = i == 0 ? (j == 0 ? mu.spatial.front() : mu.spatial.back())
                             : (j == 0 ? mu.spatial.front() : mu.spatial.back());
        } else if (mu.boundary) {  // v member ends on side c0c1 (i = 0) or c3c2
          c.sV = i == 0 ? 0.0 : mv.spatialLength;
          c.sU = (i == 0 ? mv.x1 : mv.x2) * mu.spatialLength;
          c.spatial = i == 0 ? mv.spatial.front() : mv.spatial.back();
        } else {  // u member ends on side c0c3 (j = 0) or c1c2
          c.sU = j == 0 ? 0.0 : mu.spatialLength;
          c.sV = (j == 0 ? mu.x1 : mu.x2) * mv.spatialLength;
          c.spatial = j == 0 ? mu.spatial.front() : mu.spatial.back();
        }
        // Boundary members carry no notches; the inner member's end is exact by construction.
        c.notchU = mu.boundary ? 0.0 : c.sU - c.sBarU;
        c.notchV = mv.boundary ? 0.0 : c.sV - c.sBarV;
        continue;
      }
      const auto crossing =
          geodesic::intersectPolylines(mu.spatial, mv.spatial, 1e-9 * mu.spatialLength);
      if (!crossing.found)
        throw SolverFailure("grid: geodesic members u" + std::to_string(i) + " and v" +
                            std::to_string(j) + " do not cross");
      c.spatial = crossing.position;
      c.sU = crossing.arcLengthFirst;
      c.sV = crossing.arcLengthSecond;
      c.notchU = c.sU - c.sBarU;
      c.notchV = c.sV - c.sBarV;
    }
  });
  for (auto& c : grid.connections) c.normal = nearestNormal(grid.u[c.memberU], c.spatial);
  for (const auto& c : grid.connections)
    grid.maxNotch = std::max({grid.maxNotch, std::abs(c.notchU), std::abs(c.notchV)});

  // Anchors (2.4.6): the corners, and the boundary connections nearest to curvature maxima of the
  // boundary geodesics.
  std::set<int> anchored;
  const auto addAnchor = [&](int i, int j, const std::string& reason) {
    const int index = i * nv + j;
    if (anchored.insert(index).second) grid.anchors.push_back({index, reason});
  };
  addAnchor(0, 0, "corner");
  addAnchor(0, nv - 1, "corner");
  addAnchor(nu - 1, nv - 1, "corner");
  addAnchor(nu - 1, 0, "corner");
  for (int side = 0; side < 4; ++side) {
    const auto line = sidePolyline(patch, side, false);
    for (double s : boundaryCurvatureMaxima(line, options.anchorCurvatureFraction)) {
      int bestI = -1, bestJ = -1;
      double bestGap = 1e300;
      const auto consider = [&](int i, int j, double along) {
        if (std::abs(along - s) < bestGap) bestGap = std::abs(along - s), bestI = i, bestJ = j;
      };
      const double length = patch.sideLengths[side];
      if (side == 0)
        for (int j = 1; j + 1 < nv; ++j) consider(0, j, grid.at(0, j).sU);
      if (side == 1)
        for (int i = 1; i + 1 < nu; ++i) consider(i, nv - 1, grid.at(i, nv - 1).sV);
      if (side == 2)
        for (int j = 1; j + 1 < nv; ++j) consider(nu - 1, j, length - grid.at(nu - 1, j).sU);
      if (side == 3)
        for (int i = 1; i + 1 < nu; ++i) consider(i, 0, length - grid.at(i, 0).sV);
      if (bestI >= 0) addAnchor(bestI, bestJ, "boundary curvature extremum");
    }
  }
  grid.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return grid;
}

}  // namespace egg
