#include "core/egg/cladding.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg {

void CladdingOptions::validate() const {
  if (!(degenerateTolerance >= 0.0))
    throw InvalidInput("cladding.degenerate_tolerance must be >= 0");
  if (!(infiniteSlopeFactor > 0.0))
    throw InvalidInput("cladding.infinite_slope_factor must be > 0");
}

namespace {

// The grid edges of the triangulated map: cells split along the anti-diagonal (i+1,j)-(i,j+1).
struct MapGrid {
  int n1, n2, horizontal, vertical;
  MapGrid(int a, int b) : n1(a), n2(b), horizontal((a - 1) * b), vertical(a * (b - 1)) {}
  int edgeCount() const { return horizontal + vertical + (n1 - 1) * (n2 - 1); }
  int hEdge(int i, int j) const { return i * n2 + j; }                     // (i,j)-(i+1,j)
  int vEdge(int i, int j) const { return horizontal + i * (n2 - 1) + j; }  // (i,j)-(i,j+1)
  int aEdge(int i, int j) const {
    return horizontal + vertical + i * (n2 - 1) + j;
  }  // (i+1,j)-(i,j+1)
  // Endpoints of an edge as grid indices.
  std::array<std::array<int, 2>, 2> ends(int e) const {
    if (e < horizontal) return {{{e / n2, e % n2}, {e / n2 + 1, e % n2}}};
    e -= horizontal;
    if (e < vertical) return {{{e / (n2 - 1), e % (n2 - 1)}, {e / (n2 - 1), e % (n2 - 1) + 1}}};
    e -= vertical;
    const int i = e / (n2 - 1), j = e % (n2 - 1);
    return {{{i + 1, j}, {i, j + 1}}};
  }
  // Triangles: 2*(i*(n2-1)+j) is the lower one of cell (i,j), +1 the upper one.
  std::array<int, 3> triangleEdges(int t) const {
    const int cell = t / 2, i = cell / (n2 - 1), j = cell % (n2 - 1);
    if (t % 2 == 0) return {hEdge(i, j), vEdge(i, j), aEdge(i, j)};
    return {vEdge(i + 1, j), hEdge(i, j + 1), aEdge(i, j)};
  }
  // The (one or two) triangles sharing an edge; -1 where the edge is on the domain boundary.
  std::array<int, 2> edgeTriangles(int e) const {
    const auto tri = [&](int i, int j, int upper) { return 2 * (i * (n2 - 1) + j) + upper; };
    const auto end = ends(e);
    const int i = end[0][0], j = end[0][1];
    if (e < horizontal) return {j < n2 - 1 ? tri(i, j, 0) : -1, j > 0 ? tri(i, j - 1, 1) : -1};
    if (e < horizontal + vertical)
      return {i < n1 - 1 ? tri(i, j, 0) : -1, i > 0 ? tri(i - 1, j, 1) : -1};
    const int ci = end[1][0], cj = end[0][1];
    return {tri(ci, cj, 0), tri(ci, cj, 1)};
  }
};

// Position of a point on the domain boundary walked counter-clockwise from (0,0): bottom, right,
// then (from the other side) left and top are measured from (0,0) as well.
double boundaryDistanceFromOrigin(const Eigen::Vector2d& p) {
  constexpr double eps = 1e-12;
  if (p.y() <= eps) return p.x();
  if (p.x() <= eps) return p.y();
  if (p.y() >= 1 - eps) return 1.0 + p.x();
  return 1.0 + p.y();
}

bool near(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - b).lpNorm<Eigen::Infinity>() <= 1e-12;
}

// Curve points closer than this (parameter units) are merged: where the zero set runs through grid
// vertices, round-off places crossings a few ulps apart in arbitrary directions, and those
// zero-length zigzags must not count as slopes.
constexpr double kMergeDistance = 1e-9;

}  // namespace

namespace {

// The intersection for a planar map given node by node (planarAt(i, j)). Only the nodes next to
// the zero set are visited: the arcs start at sign changes on the domain boundary and are walked
// triangle by triangle, so an evaluation costs O(n) rather than O(n^2) (Problem 2.3 evaluates it
// a few hundred times).
template <class PlanarAt>
CladdingFunction intersectMaps(const DistanceMap& surface, const PlanarAt& planarAt, Family family,
                               double scale, const CladdingOptions& options) {
  const int n1 = surface.n1, n2 = surface.n2;
  CladdingFunction result;
  result.family = family;

  const auto rawGap = [&](int i, int j) {
    const double g = surface.at(i, j) - planarAt(i, j);
    if (!std::isfinite(g))
      throw SolverFailure("claddingFunction: distance maps hold non-finite values");
    return g;
  };
  // Maps that agree everywhere: stop at the first node that tells them apart.
  bool degenerate = true;
  for (int i = 0; i < n1 && degenerate; ++i)
    for (int j = 0; j < n2; ++j)
      if (std::abs(rawGap(i, j)) > options.degenerateTolerance * scale) {
        degenerate = false;
        break;
      }
  if (degenerate) {
    // Developable patch at its unrolled angle: every pairing has equal lengths; the identity
    // pairs boundary points at equal parameters and gives the unrolled grid.
    result.degenerate = true;
    result.connectsCorners = true;
    const int n = std::max(n1, n2);
    for (int k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / (n - 1);
      result.points.emplace_back(t, t);
      result.lengths.push_back(surface.interpolate(t, t));
    }
    return result;
  }

  // D(0,0) and D(1,1) are side lengths, equal in both maps by construction of the planar quad.
  // Round-off zeros (a parallelogram's maps agree exactly on the diagonal) are snapped to zero so
  // that the sign rule below treats them consistently.
  const auto gapAt = [&](const std::array<int, 2>& v) {
    if ((v[0] == 0 && v[1] == 0) || (v[0] == n1 - 1 && v[1] == n2 - 1)) return 0.0;
    const double g = rawGap(v[0], v[1]);
    return std::abs(g) <= 1e-12 * scale ? 0.0 : g;
  };

  // Zero set of the piecewise-linear gap; a zero value counts as positive (symbolic perturbation),
  // so every triangle holds zero or one segment and arcs never branch.
  const MapGrid grid(n1, n2);
  const auto positive = [&](const std::array<int, 2>& v) { return gapAt(v) >= 0.0; };
  const auto crosses = [&](int e) {
    const auto end = grid.ends(e);
    return positive(end[0]) != positive(end[1]);
  };
  // Where the zero set crosses edge e, and the member length there.
  const auto crossingOf = [&](int e, double* length) {
    const auto end = grid.ends(e);
    const double ga = gapAt(end[0]), gb = gapAt(end[1]);
    const double t = ga / (ga - gb);
    const Eigen::Vector2d a(static_cast<double>(end[0][0]) / (n1 - 1),
                            static_cast<double>(end[0][1]) / (n2 - 1));
    const Eigen::Vector2d b(static_cast<double>(end[1][0]) / (n1 - 1),
                            static_cast<double>(end[1][1]) / (n2 - 1));
    if (length) {
      const double da = surface.at(end[0][0], end[0][1]), db = surface.at(end[1][0], end[1][1]);
      *length = da + t * (db - da);
    }
    return Eigen::Vector2d(a + t * (b - a));
  };
  const auto otherCrossingEdge = [&](int triangle, int edge) {
    for (int e : grid.triangleEdges(triangle))
      if (e != edge && crosses(e)) return e;
    return -1;
  };

  // Boundary edges in increasing id order: bottom/top rows of horizontal edges, then the left and
  // right columns of vertical ones (anti-diagonals are interior).
  std::vector<int> boundaryEdges;
  for (int i = 0; i + 1 < n1; ++i)
    boundaryEdges.push_back(grid.hEdge(i, 0)), boundaryEdges.push_back(grid.hEdge(i, n2 - 1));
  for (int j = 0; j + 1 < n2; ++j) boundaryEdges.push_back(grid.vEdge(0, j));
  for (int j = 0; j + 1 < n2; ++j) boundaryEdges.push_back(grid.vEdge(n1 - 1, j));
  std::sort(boundaryEdges.begin(), boundaryEdges.end());

  // Arcs start and end on the domain boundary; closed loops inside are irrelevant here.
  std::vector<std::vector<int>> arcs;
  std::vector<char> used(grid.edgeCount(), 0);
  for (int e : boundaryEdges) {
    if (used[e] || !crosses(e)) continue;
    std::vector<int> arc{e};
    used[e] = 1;
    int current = e;
    const auto firstTriangles = grid.edgeTriangles(e);
    int triangle = firstTriangles[0] >= 0 ? firstTriangles[0] : firstTriangles[1];
    while (triangle >= 0) {
      const int next = otherCrossingEdge(triangle, current);
      if (next < 0) break;  // cannot happen with the perturbation rule; stop defensively
      arc.push_back(next);
      used[next] = 1;
      const auto tris = grid.edgeTriangles(next);
      triangle = tris[0] == triangle ? tris[1] : tris[0];
      current = next;
    }
    arcs.push_back(std::move(arc));
  }

  const Eigen::Vector2d origin(0, 0), far(1, 1);
  int chosen = -1;
  bool reversed = false;
  for (size_t a = 0; a < arcs.size() && chosen < 0; ++a) {
    const Eigen::Vector2d first = crossingOf(arcs[a].front(), nullptr),
                          last = crossingOf(arcs[a].back(), nullptr);
    if (near(first, origin) && near(last, far)) chosen = static_cast<int>(a);
    if (near(last, origin) && near(first, far)) chosen = static_cast<int>(a), reversed = true;
  }
  result.connectsCorners = chosen >= 0;
  if (chosen < 0) {
    // The intersection does not link the corners (Figure 2.6, centre): take the arc that starts
    // closest to (0,0) along the boundary and complete it along the domain boundary.
    double best = std::numeric_limits<double>::infinity();
    for (size_t a = 0; a < arcs.size(); ++a)
      for (bool rev : {false, true}) {
        const double d =
            boundaryDistanceFromOrigin(crossingOf(rev ? arcs[a].back() : arcs[a].front(), nullptr));
        if (d < best) best = d, chosen = static_cast<int>(a), reversed = rev;
      }
  }

  const auto push = [&](const Eigen::Vector2d& p, double length) {
    if (!result.points.empty() &&
        (result.points.back() - p).lpNorm<Eigen::Infinity>() <= kMergeDistance) {
      if (near(p, Eigen::Vector2d(1, 1))) result.points.back() = p, result.lengths.back() = length;
      return;
    }
    result.points.push_back(p);
    result.lengths.push_back(length);
  };
  const auto pushCorner = [&](double x1, double x2) {
    push(Eigen::Vector2d(x1, x2), surface.interpolate(x1, x2));
  };
  push(origin, surface.at(0, 0));
  if (chosen < 0) {
    pushCorner(1, 0);  // no intersection arc at all: the boundary path, every slope 0 or infinite
  } else {
    std::vector<int> arc = arcs[chosen];
    if (reversed) std::reverse(arc.begin(), arc.end());
    const Eigen::Vector2d start = crossingOf(arc.front(), nullptr),
                          end = crossingOf(arc.back(), nullptr);
    if (start.y() > 1e-12 && start.x() > 1e-12) {  // start on the top or right side
      if (start.y() >= 1 - 1e-12)
        pushCorner(0, 1);
      else
        pushCorner(1, 0);
    }
    for (int e : arc) {
      double length = 0.0;
      const Eigen::Vector2d p = crossingOf(e, &length);
      push(p, length);
    }
    if (end.x() < 1 - 1e-12 && end.y() < 1 - 1e-12) {  // end on the bottom or left side
      if (end.y() <= 1e-12)
        pushCorner(1, 0);
      else
        pushCorner(0, 1);
    }
  }
  push(far, surface.at(n1 - 1, n2 - 1));
  return result;
}

}  // namespace

CladdingFunction claddingFunction(const DistanceMap& surface, const DistanceMap& planar,
                                  Family family, double scale, const CladdingOptions& options) {
  if (surface.n1 != planar.n1 || surface.n2 != planar.n2 || surface.n1 < 2 || surface.n2 < 2)
    throw InvalidInput(
        "claddingFunction: surface and planar distance maps must share a grid of at least 2x2");
  return intersectMaps(
      surface, [&](int i, int j) { return planar.at(i, j); }, family, scale, options);
}

CladdingFunction claddingFunction(const DistanceMap& surface, const PlanarQuad& quad, Family family,
                                  double scale, const CladdingOptions& options) {
  if (surface.n1 < 2 || surface.n2 < 2)
    throw InvalidInput("claddingFunction: the distance map needs at least 2x2 samples");
  // The closed-form planar map node by node, with the arithmetic of planarDistanceMap.
  const auto k = familyCorners(family);
  const auto& c = quad.corners;
  const Eigen::Vector2d start = c[k[0]], startDir = c[k[1]] - c[k[0]];
  const Eigen::Vector2d end = c[k[2]], endDir = c[k[3]] - c[k[2]];
  const int n1 = surface.n1, n2 = surface.n2;
  return intersectMaps(
      surface,
      [&](int i, int j) {
        const Eigen::Vector2d p = start + (static_cast<double>(i) / (n1 - 1)) * startDir;
        return (end + (static_cast<double>(j) / (n2 - 1)) * endDir - p).norm();
      },
      family, scale, options);
}

bool CladdingFunction::bijective() const {
  if (!connectsCorners || points.size() < 2) return false;
  for (size_t k = 1; k < points.size(); ++k)
    if (!(points[k].x() > points[k - 1].x() && points[k].y() > points[k - 1].y())) return false;
  return true;
}

namespace {

double interpolateAlong(const std::vector<Eigen::Vector2d>& points,
                        const std::vector<double>* values, int from, double key) {
  key = std::clamp(key, 0.0, 1.0);
  const auto coordinate = [&](size_t k) { return points[k][from]; };
  size_t hi = 1;
  {
    size_t lo = 0, top = points.size() - 1;
    while (top - lo > 1) {
      const size_t mid = (lo + top) / 2;
      (coordinate(mid) <= key ? lo : top) = mid;
    }
    hi = top;
  }
  const size_t lo = hi - 1;
  const double span = coordinate(hi) - coordinate(lo);
  const double t = span > 0.0 ? (key - coordinate(lo)) / span : 0.0;
  if (values) return (*values)[lo] + t * ((*values)[hi] - (*values)[lo]);
  return points[lo][1 - from] + t * (points[hi][1 - from] - points[lo][1 - from]);
}

}  // namespace

double CladdingFunction::evaluate(double x1) const {
  return interpolateAlong(points, nullptr, 0, x1);
}
double CladdingFunction::inverse(double x2) const {
  return interpolateAlong(points, nullptr, 1, x2);
}
double CladdingFunction::lengthAt(double x1) const {
  return interpolateAlong(points, &lengths, 0, x1);
}

std::vector<double> segmentSlopes(const CladdingFunction& cladding, double infiniteSlopeFactor) {
  std::vector<double> slopes;
  for (size_t k = 1; k < cladding.points.size(); ++k) {
    const Eigen::Vector2d d = cladding.points[k] - cladding.points[k - 1];
    if (d.x() == 0.0 && d.y() == 0.0) continue;
    slopes.push_back(d.x() == 0.0 ? infiniteSlopeFactor * d.y() : d.y() / d.x());
  }
  return slopes;
}

double slopeViolation(const CladdingFunction& cladding, double slopeMin, double slopeMax) {
  double worst = -std::numeric_limits<double>::infinity();
  for (size_t k = 1; k < cladding.points.size(); ++k) {
    const Eigen::Vector2d d = cladding.points[k] - cladding.points[k - 1];
    const double length = d.norm();
    if (length == 0.0) continue;
    worst = std::max(worst, std::max(slopeMin * d.x() - d.y(), d.y() - slopeMax * d.x()) / length);
  }
  return worst;
}

}  // namespace egg
