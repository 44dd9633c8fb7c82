#include "patching/injectivity.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace egg::patching {
namespace {

using Clock = std::chrono::steady_clock;

// Where the circle crosses one mesh edge: from the inside vertex (d < r) towards the outside one.
struct Crossing {
  int inside = -1, outside = -1;     // vertices
  int face = -1;                     // a face holding the edge, for the surface point
  double t = 0.0;                    // fraction from `inside` to `outside`
  double lo = 0.0, hi = 1.0;         // bracket of t
  double fLo = 0.0, fHi = 0.0;       // d - r at the bracket ends (fLo < 0 <= fHi)
  int lastSide = 0;                  // Illinois: which end moved last (-1 lo, +1 hi)
  double prevT = -1.0, prevF = 0.0;  // the evaluation before the last (secant)
  double bestT = 0.0;                // the evaluated t closest to the circle so far
  double error = std::numeric_limits<double>::infinity();  // its |d - r|
};

SurfacePoint edgePoint(const TriMesh& mesh, const Crossing& c, double t) {
  SurfacePoint point;
  point.face = c.face;
  const auto fv = faceVertices(mesh, c.face);
  for (int k = 0; k < 3; ++k) {
    if (fv[k] == c.inside) point.barycentric[k] = 1.0 - t;
    if (fv[k] == c.outside) point.barycentric[k] = t;
  }
  return point;
}

// Regula falsi with the Illinois modification (the end that stays put twice has its value halved),
// so the bracket shrinks from both sides even where d(t) is curved; the fallback of the secant
// step.
double nextGuess(const Crossing& c) {
  if (!std::isfinite(c.fHi)) return 0.5 * (c.lo + c.hi);
  const double t = c.lo - c.fLo * (c.hi - c.lo) / (c.fHi - c.fLo);
  return (t > c.lo && t < c.hi) ? t : 0.5 * (c.lo + c.hi);
}

}  // namespace

void SurfacePeakOptions::validate() const {
  curvature.validate();
  peaks.validate();
  if (!(std::isfinite(minGaussian) && minGaussian >= 0.0)) {
    std::ostringstream s;
    s << "SurfacePeakOptions.min_gaussian must be >= 0 (0 = automatic), got " << minGaussian;
    throw InvalidInput(s.str());
  }
}

std::vector<SurfacePeak> findSurfacePeaks(const TriMesh& surface,
                                          const SurfacePeakOptions& options) {
  options.validate();
  if (surface.n_vertices() == 0)
    throw InvalidInput("findSurfacePeaks: the surface has no vertices");
  const CurvatureField field = computeCurvature(surface, options.curvature);
  const double diagonal = boundingBox(surface).size().norm();
  // r = pi / sqrt(K) < diagonal  <=>  K > (pi / diagonal)^2.
  const double threshold =
      options.minGaussian > 0.0 ? options.minGaussian : std::pow(std::numbers::pi / diagonal, 2);
  PeakOptions peakOptions = options.peaks;
  // The raw search only needs averaged K > 0 and every candidate whose nearby maximum passes: the
  // averaged K is never above the nearby maximum, so filtering on the latter below loses nothing.
  peakOptions.minGaussian = std::max(peakOptions.minGaussian, 0.0);
  std::vector<CurvaturePeak> raw =
      findGaussianPeaks(surface, field.gaussian, field.mixedArea, peakOptions);
  std::stable_sort(raw.begin(), raw.end(), [](const CurvaturePeak& a, const CurvaturePeak& b) {
    if (a.gaussianAveraged != b.gaussianAveraged) return a.gaussianAveraged > b.gaussianAveraged;
    return a.vertex < b.vertex;
  });
  std::vector<SurfacePeak> kept;
  for (const CurvaturePeak& p : raw) {
    if (!(p.gaussianMaxNearby > threshold)) continue;
    const bool inside = std::any_of(kept.begin(), kept.end(), [&](const SurfacePeak& k) {
      return (k.position - p.position).norm() < k.radiusM;
    });
    if (inside) continue;
    SurfacePeak peak;
    peak.vertex = p.vertex;
    peak.position = p.position;
    peak.gaussianAveraged = p.gaussianAveraged;
    peak.gaussianMax = p.gaussianMaxNearby;
    peak.radiusM = injectivityRadiusBound(p.gaussianMaxNearby);
    peak.onBoundary = p.onBoundary;
    kept.push_back(peak);
  }
  return kept;
}

InjectivityCircle injectivityCircle(const TriMesh& surface, const geodesic::DistanceSolver& solver,
                                    const SurfacePeak& peak) {
  const auto start = Clock::now();
  const int nv = static_cast<int>(surface.n_vertices());
  if (peak.vertex < 0 || peak.vertex >= nv)
    throw InvalidInput("injectivityCircle: peak vertex " + std::to_string(peak.vertex) +
                       " is not a vertex of the surface (" + std::to_string(nv) + " vertices)");
  if (solver.vertexCount() != nv)
    throw InvalidInput("injectivityCircle: the distance solver was built on another mesh");
  if (!(peak.radiusM > 0.0))
    throw InvalidInput("injectivityCircle: the peak's radius must be positive");
  InjectivityCircle circle;
  circle.peakVertex = peak.vertex;
  circle.centre = toEigen(surface.point(TriMesh::VertexHandle(peak.vertex)));
  circle.radiusM = peak.radiusM;
  const double r = peak.radiusM;

  const std::vector<double> d = solver.distancesFromVertex(peak.vertex).vertexDistances;
  circle.propagations = 1;
  const auto inside = [&](int v) { return d[v] < r; };
  circle.coversSurface = std::all_of(d.begin(), d.end(), [&](double x) { return x < r; });

  // Marching triangles: one crossing per edge with its ends on both sides; in each face the segment
  // runs from the crossing of the halfedge leaving the disc to that of the halfedge entering it, so
  // the disc is on the segment's left (faces are counter-clockwise).
  const int ne = static_cast<int>(surface.n_edges());
  std::vector<int> crossingOfEdge(ne, -1);
  std::vector<Crossing> crossings;
  std::vector<int> next, prev;  // crossing -> following / preceding crossing along the circle
  for (auto fh : surface.faces()) {
    int leaving = -1, entering = -1;
    for (auto h : surface.fh_range(fh)) {
      const int from = surface.from_vertex_handle(h).idx(), to = surface.to_vertex_handle(h).idx();
      if (inside(from) == inside(to)) continue;
      const int e = surface.edge_handle(h).idx();
      if (crossingOfEdge[e] < 0) {
        Crossing c;
        c.inside = inside(from) ? from : to;
        c.outside = inside(from) ? to : from;
        c.face = fh.idx();
        c.fLo = d[c.inside] - r;
        c.fHi = d[c.outside] - r;
        c.t = nextGuess(c);
        crossingOfEdge[e] = static_cast<int>(crossings.size());
        crossings.push_back(c);
        next.push_back(-1), prev.push_back(-1);
      }
      (inside(from) ? leaving : entering) = crossingOfEdge[e];
    }
    if (leaving >= 0 && entering >= 0) next[leaving] = entering, prev[entering] = leaving;
  }

  // Move every crossing along its edge until its own distance is r; all unconverged crossings are
  // targets of one propagation per round.
  const double tolerance = 1e-10 * r;
  std::vector<int> active(crossings.size());
  for (size_t i = 0; i < active.size(); ++i) active[i] = static_cast<int>(i);
  for (int round = 0; round < 8 && !active.empty(); ++round) {
    std::vector<SurfacePoint> targets;
    targets.reserve(active.size());
    for (int i : active) targets.push_back(edgePoint(surface, crossings[i], crossings[i].t));
    const std::vector<double> dt = solver.distancesFromVertex(peak.vertex, targets).targetDistances;
    ++circle.propagations;
    std::vector<int> still;
    for (size_t k = 0; k < active.size(); ++k) {
      Crossing& c = crossings[active[k]];
      const double f = dt[k] - r;
      if (std::abs(f) < c.error) c.error = std::abs(f), c.bestT = c.t;
      if (c.error <= tolerance) continue;
      if (f < 0.0) {
        c.lo = c.t, c.fLo = f;
        if (c.lastSide == -1) c.fHi *= 0.5;
        c.lastSide = -1;
      } else {
        c.hi = c.t, c.fHi = f;
        if (c.lastSide == 1) c.fLo *= 0.5;
        c.lastSide = 1;
      }
      const double previous = c.t;
      c.t = nextGuess(c);
      // Secant through the last two evaluations where it stays inside the bracket: superlinear once
      // both lie in the same window of the field, where the vertex values at the edge's ends (often
      // reached through other windows) slow regula falsi down.
      if (c.prevT >= 0.0 && f != c.prevF) {
        const double secant = previous - f * (previous - c.prevT) / (f - c.prevF);
        if (secant > c.lo && secant < c.hi) c.t = secant;
      }
      c.prevT = previous, c.prevF = f;
      // A bracket at rounding: the best point stays (its error is reported).
      if (c.t != previous && c.hi - c.lo > 1e-15) still.push_back(active[k]);
    }
    active = std::move(still);
  }
  for (const Crossing& c : crossings)
    circle.maxDistanceErrorM = std::max(circle.maxDistanceErrorM, c.error);

  // Chain the segments: open pieces start at a crossing nothing precedes (its edge is on the
  // surface boundary); what remains are loops, each started at its lowest edge.
  std::vector<char> used(crossings.size(), 0);
  std::vector<CirclePolyline> loops, pieces;
  const auto walk = [&](int first, bool loop) {
    CirclePolyline line;
    line.closed = loop;
    for (int c = first; c >= 0 && !used[c]; c = next[c]) {
      used[c] = 1;
      line.points.push_back(edgePoint(surface, crossings[c], crossings[c].bestT));
      line.positions.push_back(position(surface, line.points.back()));
    }
    for (size_t i = 1; i < line.positions.size(); ++i)
      line.lengthM += (line.positions[i] - line.positions[i - 1]).norm();
    if (loop && line.positions.size() > 1)
      line.lengthM += (line.positions.front() - line.positions.back()).norm();
    return line;
  };
  for (int e = 0; e < ne; ++e) {
    const int c = crossingOfEdge[e];
    if (c >= 0 && !used[c] && prev[c] < 0) pieces.push_back(walk(c, false));
  }
  for (int e = 0; e < ne; ++e) {
    const int c = crossingOfEdge[e];
    if (c >= 0 && !used[c]) loops.push_back(walk(c, true));
  }
  circle.polylines = std::move(loops);
  circle.complete = !circle.polylines.empty() && pieces.empty();
  for (auto& p : pieces) circle.polylines.push_back(std::move(p));
  for (const auto& p : circle.polylines) circle.lengthM += p.lengthM;
  circle.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return circle;
}

std::vector<InjectivityCircle> injectivityCircles(const TriMesh& surface,
                                                  const geodesic::DistanceSolver& solver,
                                                  const std::vector<SurfacePeak>& peaks) {
  std::vector<InjectivityCircle> circles(peaks.size());
  tbb::parallel_for(size_t(0), peaks.size(),
                    [&](size_t i) { circles[i] = injectivityCircle(surface, solver, peaks[i]); });
  return circles;
}

}  // namespace egg::patching
