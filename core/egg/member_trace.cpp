#include "core/egg/member_trace.hpp"
#include "core/egg/illinois_bracket.hpp"

#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace egg {

namespace {

Eigen::Vector3d vertexPosition(const TriMesh& mesh, int v) {
  return toEigen(mesh.point(TriMesh::VertexHandle(v)));
}

Eigen::Vector3d faceNormal(const TriMesh& mesh, int face) {
  const auto ids = faceVertices(mesh, face);
  const Eigen::Vector3d a = vertexPosition(mesh, ids[0]);
  return (vertexPosition(mesh, ids[1]) - a).cross(vertexPosition(mesh, ids[2]) - a).normalized();
}

void setPath(const Patch& patch, GridMember& m, double x2, const std::vector<SurfacePoint>& points,
             std::vector<Eigen::Vector3d> positions) {
  m.x2 = x2;
  m.spatial = std::move(positions);
  m.normals.clear();
  for (const auto& point : points) m.normals.push_back(faceNormal(patch.mesh, point.face));
}

// ---------------------------------------------------------------------------------------------
// The unfolded strip of a traced geodesic.

// Where a path point lies: on an edge (a, b) at fraction t from a, or inside a face. Vertices are
// not supported (a path through a vertex may bend there; the strip does not apply).
struct Support {
  bool onEdge = false;
  int a = -1, b = -1;
  double t = 0.0;
  int face = -1;  // the face for a point inside a face
};

std::optional<Support> supportOf(const TriMesh& mesh, const SurfacePoint& p) {
  const auto ids = faceVertices(mesh, p.face);
  const Eigen::Vector3d& w = p.barycentric;
  int zeros = 0, zero = -1;
  for (int i = 0; i < 3; ++i)
    // 1e-11, not 1e-14: the tracer's point at a bend vertex carries ~1e-13 of rounding in its
    // other weights; read as a crossing that close to the vertex it shares no face with the next
    // step and the strip failed (a member of the 2k bench bump fell back to full fields).
    if (std::abs(w[i]) <= 1e-11) ++zeros, zero = i;
  Support s;
  if (zeros >= 2) return std::nullopt;
  if (zeros == 0) {
    s.face = p.face;
    return s;
  }
  const int i = (zero + 1) % 3, j = (zero + 2) % 3;
  s.onEdge = true;
  s.a = ids[i], s.b = ids[j];
  s.t = w[j] / (w[i] + w[j]);
  return s;
}

// Faces a support point touches.
std::vector<int> facesOf(const TriMesh& mesh, const Support& s) {
  if (s.face == -2) {
    std::vector<int> faces;
    for (auto fh : mesh.vf_range(TriMesh::VertexHandle(s.a))) faces.push_back(fh.idx());
    return faces;
  }
  if (!s.onEdge) return {s.face};
  std::vector<int> faces;
  const auto h = mesh.find_halfedge(TriMesh::VertexHandle(s.a), TriMesh::VertexHandle(s.b));
  if (!h.is_valid()) return faces;
  for (auto hh : {h, mesh.opposite_halfedge_handle(h)})
    if (!mesh.is_boundary(hh)) faces.push_back(mesh.face_handle(hh).idx());
  return faces;
}

struct Strip {
  // A path that bends around a saddle (or reflex boundary) vertex is unfolded from its last bend:
  // the part before it is kept, and its length is added.
  int first = 0;                            // index of the strip's first path point
  double prefixLength = 0.0;                // path length up to that point
  std::vector<int> faces;                   // faces the geodesic runs through, in order
  std::vector<std::array<int, 3>> faceIds;  // their vertices
  std::vector<std::array<Eigen::Vector2d, 3>> unfolded;  // and their unfolded positions
  std::vector<Support> crossings;  // the edges crossed between consecutive faces
  std::vector<std::array<Eigen::Vector2d, 2>> crossings2d;  // those edges (a, b) unfolded
  Eigen::Vector2d source = Eigen::Vector2d::Zero();
  // The boundary edge holding the end point: chain vertices lo, lo + 1 of the end side.
  int chainLo = -1;
  Eigen::Vector2d endLo = Eigen::Vector2d::Zero(), endHi = Eigen::Vector2d::Zero();
};

Eigen::Vector2d unfoldedVertex(const Strip& strip, size_t face, int vertex) {
  for (int i = 0; i < 3; ++i)
    if (strip.faceIds[face][i] == vertex) return strip.unfolded[face][i];
  throw SolverFailure("member strip: vertex not in face");
}

// Unfolds the faces of `points` into the plane, isometrically face by face. nullopt when the path
// touches a vertex, runs along an edge, or does not end on the family's end side.
std::optional<Strip> unfoldStrip(const Patch& patch, Family family,
                                 const std::vector<SurfacePoint>& points) {
  const TriMesh& mesh = patch.mesh;
  if (points.size() < 2) return std::nullopt;
  Strip strip;
  // The last bend: the last point before the end that is a mesh vertex.
  for (size_t k = 1; k + 1 < points.size(); ++k)
    if (!supportOf(mesh, points[k])) strip.first = static_cast<int>(k);
  for (int k = 1; k <= strip.first; ++k)
    strip.prefixLength += (position(mesh, points[k]) - position(mesh, points[k - 1])).norm();
  std::vector<Support> supports;
  for (size_t k = strip.first; k < points.size(); ++k) {
    auto s = supportOf(mesh, points[k]);
    if (!s && static_cast<int>(k) == strip.first) {  // the bend vertex: every face around it
      const auto ids = faceVertices(mesh, points[k].face);
      int corner = 0;
      for (int i = 1; i < 3; ++i)
        if (points[k].barycentric[i] > points[k].barycentric[corner]) corner = i;
      s = Support{};
      s->a = ids[corner];
      s->face = -2;  // marks a vertex
    }
    if (!s) return std::nullopt;
    supports.push_back(*s);
  }
  for (size_t k = 0; k + 1 < supports.size(); ++k) {
    const auto fa = facesOf(mesh, supports[k]), fb = facesOf(mesh, supports[k + 1]);
    std::vector<int> common;
    for (int f : fa)
      if (std::find(fb.begin(), fb.end(), f) != fb.end()) common.push_back(f);
    if (common.size() != 1) return std::nullopt;
    if (!strip.faces.empty() && strip.faces.back() == common[0]) return std::nullopt;
    strip.faces.push_back(common[0]);
  }
  for (size_t k = 1; k + 1 < supports.size(); ++k) {
    if (!supports[k].onEdge) return std::nullopt;
    strip.crossings.push_back(supports[k]);
  }
  if (!supports.back().onEdge) return std::nullopt;

  // First face: v0 at the origin, v1 on +x, v2 above.
  const size_t count = strip.faces.size();
  strip.faceIds.resize(count);
  strip.unfolded.resize(count);
  {
    const auto ids = faceVertices(mesh, strip.faces[0]);
    const Eigen::Vector3d p0 = vertexPosition(mesh, ids[0]), p1 = vertexPosition(mesh, ids[1]),
                          p2 = vertexPosition(mesh, ids[2]);
    const double d01 = (p1 - p0).norm(), d02 = (p2 - p0).norm(), d12 = (p2 - p1).norm();
    const double x = (d02 * d02 - d12 * d12 + d01 * d01) / (2 * d01);
    strip.faceIds[0] = ids;
    strip.unfolded[0] = {Eigen::Vector2d(0, 0), Eigen::Vector2d(d01, 0),
                         Eigen::Vector2d(x, std::sqrt(std::max(0.0, d02 * d02 - x * x)))};
  }
  // Each next face across the crossed edge, its third vertex on the far side of that edge.
  for (size_t k = 1; k < count; ++k) {
    const Support& e = strip.crossings[k - 1];
    const auto ids = faceVertices(mesh, strip.faces[k]);
    int third = -1, previousThird = -1;
    for (int v : ids)
      if (v != e.a && v != e.b) third = v;
    for (int v : strip.faceIds[k - 1])
      if (v != e.a && v != e.b) previousThird = v;
    if (third < 0 || previousThird < 0) return std::nullopt;
    const Eigen::Vector2d A = unfoldedVertex(strip, k - 1, e.a),
                          B = unfoldedVertex(strip, k - 1, e.b);
    const Eigen::Vector2d P = unfoldedVertex(strip, k - 1, previousThird);
    const double ab = (B - A).norm();
    const double ac = (vertexPosition(mesh, third) - vertexPosition(mesh, e.a)).norm();
    const double bc = (vertexPosition(mesh, third) - vertexPosition(mesh, e.b)).norm();
    const Eigen::Vector2d u = (B - A) / ab;
    Eigen::Vector2d normal(-u.y(), u.x());
    if (normal.dot(P - A) > 0) normal = -normal;
    const double x = (ac * ac - bc * bc + ab * ab) / (2 * ab);
    const Eigen::Vector2d C = A + x * u + std::sqrt(std::max(0.0, ac * ac - x * x)) * normal;
    strip.faceIds[k] = ids;
    for (int i = 0; i < 3; ++i) strip.unfolded[k][i] = ids[i] == e.a ? A : ids[i] == e.b ? B : C;
  }
  for (const auto& e : strip.crossings) {
    const size_t k = &e - strip.crossings.data() + 1;
    strip.crossings2d.push_back({unfoldedVertex(strip, k, e.a), unfoldedVertex(strip, k, e.b)});
  }
  const Support& s0 = supports.front();
  if (s0.face == -2) {
    strip.source = unfoldedVertex(strip, 0, s0.a);
  } else if (s0.onEdge) {
    strip.source =
        (1 - s0.t) * unfoldedVertex(strip, 0, s0.a) + s0.t * unfoldedVertex(strip, 0, s0.b);
  } else {
    for (int i = 0; i < 3; ++i)
      strip.source += points[strip.first].barycentric[i] *
                      unfoldedVertex(strip, 0, faceVertices(mesh, s0.face)[i]);
  }
  // The end point's edge on the end side's vertex chain.
  const Support& last = supports.back();
  const auto& chain = patch.sides[familySide(family, true).first];
  for (size_t i = 0; i + 1 < chain.size(); ++i)
    if ((chain[i] == last.a && chain[i + 1] == last.b) ||
        (chain[i] == last.b && chain[i + 1] == last.a))
      strip.chainLo = static_cast<int>(i);
  if (strip.chainLo < 0) return std::nullopt;
  strip.endLo = unfoldedVertex(strip, count - 1, chain[strip.chainLo]);
  strip.endHi = unfoldedVertex(strip, count - 1, chain[strip.chainLo + 1]);
  return strip;
}

// The result of solving the length equation in a strip.
struct StripSolution {
  bool matched =
      false;        // x2 found on the strip's end edge and the straight line stays in the strip
  double x2 = 0.0;  // matched x2, or the next x2 to trace from
  std::vector<SurfacePoint> points;
  std::vector<Eigen::Vector3d> positions;
};

StripSolution solveInStrip(const Patch& patch, const Strip& strip, const PlanarQuad& quad,
                           const GridMember& m, double x2Traced,
                           const std::vector<SurfacePoint>& traced, double tolerance) {
  // Plain variables, not a structured binding: clang before 16 cannot capture one in a lambda
  // (the fuzz build, scripts/fuzz.sh).
  const auto familyEnd = familySide(m.family, true);
  const int side = familyEnd.first;
  const bool reversed = familyEnd.second;
  const double length = patch.sideLengths[side];
  const auto& arc = patch.sideArcLength[side];
  const double sLo = arc[strip.chainLo], sHi = arc[strip.chainLo + 1];
  const auto xOf = [&](double s) { return reversed ? 1.0 - s / length : s / length; };
  const auto endAt = [&](double x2) {
    const double s = (reversed ? 1.0 - x2 : x2) * length;
    return Eigen::Vector2d(strip.endLo + (s - sLo) / (sHi - sLo) * (strip.endHi - strip.endLo));
  };
  // Exact in the strip: geodesic length minus planar length.
  const auto g = [&](double x2) {
    return strip.prefixLength + (endAt(x2) - strip.source).norm() -
           planarDistance(quad, m.family, m.x1, x2);
  };
  double a = std::min(xOf(sLo), xOf(sHi)), b = std::max(xOf(sLo), xOf(sHi));
  double ga = g(a), gb = g(b);
  StripSolution solution;
  if ((ga > 0) == (gb > 0) && ga != 0.0 && gb != 0.0) {
    // The root lies beyond this boundary edge: a Newton step with the strip's slope (the straight
    // line extended) says where to trace next.
    const double slope = (gb - ga) / (b - a);
    solution.x2 = std::clamp(x2Traced - g(x2Traced) / slope, 0.0, 1.0);
    return solution;
  }
  // Bracketed: Illinois regula falsi to the last bits.
  IllinoisBracket r{a, b, ga, gb};
  double x = a;
  for (int step = 0; step < 200; ++step) {
    x = r.gb != r.ga ? r.falsePosition() : 0.5 * (r.a + r.b);
    if (!(x > r.a && x < r.b)) x = 0.5 * (r.a + r.b);
    const double gx = g(x);
    if (std::abs(gx) <= 1e-3 * tolerance || r.b - r.a <= 4e-16) break;
    r.replace(x, gx, (gx > 0) == (r.gb > 0));
  }
  solution.x2 = x;
  // The straight line to the matched end point must cross every strip edge inside it, in order.
  const Eigen::Vector2d S = strip.source, E = endAt(x);
  const Eigen::Vector2d d = E - S;
  double previous = 0.0;
  for (int k = 0; k <= strip.first; ++k) {
    solution.points.push_back(traced[k]);
    solution.positions.push_back(position(patch.mesh, traced[k]));
  }
  for (size_t k = 0; k < strip.crossings.size(); ++k) {
    const Eigen::Vector2d A = strip.crossings2d[k][0], B = strip.crossings2d[k][1];
    const Eigen::Vector2d q = B - A, w = A - S;
    const double denom = d.x() * q.y() - d.y() * q.x();
    if (std::abs(denom) <= 1e-300) return solution;
    const double lambda = (w.x() * q.y() - w.y() * q.x()) / denom;
    const double u = (w.x() * d.y() - w.y() * d.x()) / denom;
    if (!(u > 1e-12 && u < 1 - 1e-12 && lambda > previous && lambda < 1.0)) return solution;
    previous = lambda;
    const Support& e = strip.crossings[k];
    SurfacePoint p =
        traced[strip.first + k + 1];  // same edge, same face: only the position along it changes
    const auto ids = faceVertices(patch.mesh, p.face);
    for (int i = 0; i < 3; ++i)
      p.barycentric[i] = ids[i] == e.a ? 1.0 - u : ids[i] == e.b ? u : 0.0;
    solution.points.push_back(p);
    solution.positions.push_back((1 - u) * vertexPosition(patch.mesh, e.a) +
                                 u * vertexPosition(patch.mesh, e.b));
  }
  const SurfacePoint end = familyBoundaryPoint(patch, m.family, true, x);
  solution.points.push_back(end);
  solution.positions.push_back(position(patch.mesh, end));
  solution.matched = true;
  return solution;
}

double traceLength(const std::vector<Eigen::Vector3d>& line) {
  double total = 0.0;
  for (size_t k = 1; k < line.size(); ++k) total += (line[k] - line[k - 1]).norm();
  return total;
}

// ---------------------------------------------------------------------------------------------
// Fallback: bracket the root with exact fields (one propagation per step).

void matchByFields(const Patch& patch, const geodesic::DistanceSolver& solver,
                   const PlanarQuad& quad, GridMember& m, const GridOptions& options,
                   std::atomic<int>& propagations) {
  const SurfacePoint start = familyBoundaryPoint(patch, m.family, false, m.x1);
  const auto endPoint = [&](double x2) { return familyBoundaryPoint(patch, m.family, true, x2); };
  const auto mismatch = [&](double x2, double distance) {
    return distance - planarDistance(quad, m.family, m.x1, x2);
  };
  const double guess = m.x2;
  const int count = options.bracketSamples;
  const double halfWidth = 0.05;
  std::vector<double> xs{guess};
  std::vector<SurfacePoint> targets{endPoint(guess)};
  for (int k = 0; k < count; ++k) {
    const double x = std::clamp(guess - halfWidth + 2 * halfWidth * k / (count - 1), 0.0, 1.0);
    xs.push_back(x);
    targets.push_back(endPoint(x));
  }
  // Coarse samples of the whole side as well: on a nearly developable patch the mismatch is tiny
  // everywhere and its root may lie outside the window around the guess.
  std::vector<double> coarse;
  for (int k = 0; k < count; ++k) coarse.push_back(static_cast<double>(k) / (count - 1));
  for (double x : coarse) targets.push_back(endPoint(x));
  const auto field = solver.distances(start, targets);
  ++propagations;
  const double scale = planarDistance(quad, m.family, m.x1, guess);
  const double tolerance = options.lengthTolerance * scale;
  double bestX = guess, bestG = mismatch(guess, field.targetDistances[0]);
  if (std::abs(bestG) > tolerance) {
    // Bracket nearest the guess, in the window first, else on the coarse samples.
    int bracket = -1;
    double a = 0, b = 0, ga = 0, gb = 0;
    for (int k = 1; k < count; ++k) {
      const double g0 = mismatch(xs[k], field.targetDistances[k]),
                   g1 = mismatch(xs[k + 1], field.targetDistances[k + 1]);
      if (std::abs(g0) < std::abs(bestG)) bestG = g0, bestX = xs[k];
      if ((g0 <= 0) != (g1 <= 0) &&
          (bracket < 0 || std::abs(xs[k] - guess) < std::abs(xs[bracket] - guess)))
        bracket = k, a = xs[k], b = xs[k + 1], ga = g0, gb = g1;
    }
    if (bracket < 0) {
      const size_t offset = xs.size();
      for (int k = 0; k + 1 < count; ++k) {
        const double g0 = mismatch(coarse[k], field.targetDistances[offset + k]);
        const double g1 = mismatch(coarse[k + 1], field.targetDistances[offset + k + 1]);
        if ((g0 <= 0) == (g1 <= 0)) continue;
        const double middle = 0.5 * (coarse[k] + coarse[k + 1]);
        if (bracket < 0 || std::abs(middle - guess) < std::abs(0.5 * (a + b) - guess))
          bracket = k, a = coarse[k], b = coarse[k + 1], ga = g0, gb = g1;
      }
    }
    if (bracket >= 0) {
      IllinoisBracket r{a, b, ga, gb};
      for (int step = 0; step < options.maxSecantSteps; ++step) {
        const double x = r.falsePosition();
        const double g = mismatch(x, solver.distance(start, endPoint(x)));
        ++propagations;
        if (std::abs(g) < std::abs(bestG)) bestG = g, bestX = x;
        if (std::abs(g) <= tolerance) break;
        r.replace(x, g, (g <= 0) == (r.gb <= 0));
      }
    }
  }
  const auto path = solver.path(start, endPoint(bestX));
  ++propagations;
  if (!std::isfinite(path.length) || path.positions.size() < 2)
    throw SolverFailure("grid: member " + std::to_string(m.index) +
                        " could not be traced inside the patch");
  setPath(patch, m, bestX, path.points, path.positions);
  m.bracketed = true;
}

}  // namespace

void traceInnerMember(const Patch& patch, const geodesic::DistanceSolver& solver,
                      const PlanarQuad& quad, GridMember& m, const GridOptions& options,
                      std::atomic<int>& propagations) {
  const SurfacePoint start = familyBoundaryPoint(patch, m.family, false, m.x1);
  const double tolerance = options.lengthTolerance * planarDistance(quad, m.family, m.x1, m.x2);
  const double guess = m.x2;
  double x2 = guess;
  for (int attempt = 0; attempt < options.maxStripTraces; ++attempt) {
    const auto path = solver.path(start, familyBoundaryPoint(patch, m.family, true, x2));
    ++propagations;
    if (!std::isfinite(path.length) || path.positions.size() < 2) break;
    if (std::abs(path.length - planarDistance(quad, m.family, m.x1, x2)) <= tolerance) {
      setPath(patch, m, x2, path.points, path.positions);  // already matched (a retrace lands here)
      return;
    }
    const auto strip = unfoldStrip(patch, m.family, path.points);
    if (!strip) break;
    const auto solution = solveInStrip(patch, *strip, quad, m, x2, path.points, tolerance);
    if (solution.matched && strip->first > 0 && !(attempt > 0 && solution.x2 == x2)) {
      // Bent at a vertex: the path to the matched end bends there too unless the end left the
      // vertex's shadow, which only a new trace can tell; it is exact and usually matches.
      x2 = solution.x2;
      continue;
    }
    // Retraced at the strip's end and bent at the same place, the strip gives the same end again:
    // the trace went round a vertex the straight segment from a skipped near-flat saddle passes
    // (distance_solver.hpp, path()), a few 1e-5 m longer. The strip's own polyline (straight
    // after the bend, length equal to the planar segment) is then the member; without this the
    // member fell back to bracketing with full fields (~20 ms on the 3.4k bench patch).
    if (solution.matched) {
      const double mismatch =
          traceLength(solution.positions) - planarDistance(quad, m.family, m.x1, solution.x2);
      if (std::abs(mismatch) <= tolerance) {
        setPath(patch, m, solution.x2, solution.points, solution.positions);
        return;
      }
      break;
    }
    x2 = solution.x2;
  }
  m.x2 = guess;
  matchByFields(patch, solver, quad, m, options, propagations);
}

}  // namespace egg
