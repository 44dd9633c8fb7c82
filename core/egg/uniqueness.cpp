#include "core/egg/uniqueness.hpp"
#include "core/timing.hpp"

#include "core/curvature/curvature.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

namespace egg {

void UniquenessOptions::validate() const {
  if (!(etaMax >= 1.0)) throw InvalidInput("patching.eta_max must be >= 1");
  if (maxPeaks < 1) throw InvalidInput("uniqueness max_peaks must be >= 1");
  if (sideSamples < 3) throw InvalidInput("uniqueness side_samples must be >= 3");
  if (maxSmoothingRounds < 0) throw InvalidInput("uniqueness max_smoothing_rounds must be >= 0");
  if (!(boundaryMarginRelative >= 0.0 && boundaryMarginRelative < 0.5))
    throw InvalidInput("uniqueness boundary_margin_relative must lie in [0, 0.5)");
}

namespace {

// Offsets of the family's start and end side samples in uniquenessPeakTargets.
int sideOffset(Family family, bool end, int n) {
  return (family == Family::U ? 0 : 2 * n) + (end ? n : 0);
}

// Boundary sample index of p1: which side of the family (end or start) and where on it.
struct NearestBoundary {
  bool onEnd = false;
  int index = 0;
  double distance = 0.0;
};

// p1 = the sample of the family's two sides closest to the peak (Section 2.3.3).
NearestBoundary nearestBoundary(const std::vector<double>& fromPeak, Family family, int n) {
  NearestBoundary best;
  best.distance = std::numeric_limits<double>::infinity();
  for (bool end : {false, true})
    for (int k = 0; k < n; ++k) {
      const double d = fromPeak[sideOffset(family, end, n) + k];
      if (d < best.distance) best = {end, k, d};
    }
  return best;
}

// q1 (Section 2.3.3): the index i < count with the smallest excess viaPeak(i) - direct(i) among
// those with direct(i) > 0; -1 if there is none.
int leastExcess(int count, const std::function<double(int)>& viaPeak,
                const std::function<double(int)>& direct) {
  int best = -1;
  double bestExcess = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double d = direct(i), excess = viaPeak(i) - d;
    if (!(d > 0.0) || excess >= bestExcess) continue;
    bestExcess = excess;
    best = i;
  }
  return best;
}

// The check of one family and peak with p1 and q1 = sample q of the side opposite p1 (eta =
// viaPeak / direct there; q < 0: no sample qualified, eta stays 1).
EtaCheck makeCheck(const Patch& patch, Family family, const CurvaturePeak& peak,
                   const NearestBoundary& p1, int n, int q, double viaPeak, double direct) {
  EtaCheck check;
  check.family = family;
  check.peakVertex = peak.vertex;
  check.peak = peak.position;
  check.gaussian = peak.gaussianMaxNearby;
  check.p1 = position(patch.mesh, familyBoundaryPoint(patch, family, p1.onEnd,
                                                      static_cast<double>(p1.index) / (n - 1)));
  if (q >= 0) {
    check.eta = viaPeak / direct;
    check.q1 = position(patch.mesh, familyBoundaryPoint(patch, family, !p1.onEnd,
                                                        static_cast<double>(q) / (n - 1)));
  }
  return check;
}

// eta for one family and peak: q1 on the side opposite p1 minimises d(p1,p_max) + d(p_max,q) -
// d(p1,q). `fromP1(k)` is d(p1, sample k of the opposite side).
EtaCheck etaCheck(const Patch& patch, Family family, const CurvaturePeak& peak,
                  const std::vector<double>& fromPeak, const NearestBoundary& p1, int n,
                  const std::function<double(int)>& fromP1) {
  const int opposite = sideOffset(family, !p1.onEnd, n);
  const auto viaPeak = [&](int k) { return p1.distance + fromPeak[opposite + k]; };
  const int q = leastExcess(n, viaPeak, fromP1);
  return makeCheck(patch, family, peak, p1, n, q, q >= 0 ? viaPeak(q) : 0.0,
                   q >= 0 ? fromP1(q) : 1.0);
}

void addCheck(UniquenessReport& report, const EtaCheck& check) {
  double& worst = check.family == Family::U ? report.etaU : report.etaV;
  worst = std::max(worst, check.eta);
  report.checks.push_back(check);
}

// p1 per peak and family (u, then v) from the peak fields (their first 4n targets are
// uniquenessPeakTargets), and the boundary points the p1 fields start from.
std::vector<NearestBoundary> nearestBoundaries(
    const std::vector<const std::vector<double>*>& fromPeaks, int n) {
  std::vector<NearestBoundary> nearest;
  for (const auto* d : fromPeaks)
    for (Family family : {Family::U, Family::V}) nearest.push_back(nearestBoundary(*d, family, n));
  return nearest;
}
std::vector<SurfacePoint> p1Points(const Patch& patch, const std::vector<NearestBoundary>& nearest,
                                   int n) {
  std::vector<SurfacePoint> points;
  for (size_t k = 0; k < nearest.size(); ++k) {
    const Family family = k % 2 == 0 ? Family::U : Family::V;
    points.push_back(familyBoundaryPoint(patch, family, nearest[k].onEnd,
                                         static_cast<double>(nearest[k].index) / (n - 1)));
  }
  return points;
}

// One eta check per peak and family from exact fields: d(p_max, .) and d(p1, .) to the targets.
void addEtaChecks(UniquenessReport& report, const Patch& patch, const PatchPeaks& peaks,
                  const std::vector<const std::vector<double>*>& fromPeaks,
                  const std::vector<NearestBoundary>& nearest,
                  const std::vector<geodesic::DistanceField>& fromP1, int n) {
  size_t q = 0;
  for (size_t p = 0; p < peaks.peaks.size(); ++p)
    for (Family family : {Family::U, Family::V}) {
      const size_t at = q++;
      const int opposite = sideOffset(family, !nearest[at].onEnd, n);
      const auto& d = fromP1[at].targetDistances;
      addCheck(report, etaCheck(patch, family, peaks.peaks[p], *fromPeaks[p], nearest[at], n,
                                [&](int k) { return d[opposite + k]; }));
    }
}

}  // namespace

PatchPeaks findPatchPeaks(const Patch& patch, const UniquenessOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  PatchPeaks result;
  const auto curvature = computeCurvature(patch.mesh);
  PeakOptions peakOptions;
  peakOptions.includeBoundary = false;  // a peak on the boundary is harmless (Section 2.3.3)
  auto peaks = findGaussianPeaks(patch.mesh, curvature.gaussian, curvature.mixedArea, peakOptions);
  const double longest = *std::max_element(patch.sideLengths.begin(), patch.sideLengths.end());
  const double margin =
      std::max(options.boundaryMarginRelative * longest, 2.0 * meanEdgeLength(patch.mesh));
  const auto nearBoundary = [&](const CurvaturePeak& p) {
    for (const auto& side : patch.sides)
      for (int v : side)
        if ((toEigen(patch.mesh.point(TriMesh::VertexHandle(v))) - p.position).norm() < margin)
          return true;
    return false;
  };
  peaks.erase(std::remove_if(peaks.begin(), peaks.end(),
                             [&](const CurvaturePeak& p) {
                               return p.gaussianMaxNearby <= 0 || nearBoundary(p);
                             }),
              peaks.end());
  if (static_cast<int>(peaks.size()) > options.maxPeaks) peaks.resize(options.maxPeaks);
  for (const auto& p : peaks)
    result.gaussianMax = std::max(result.gaussianMax, p.gaussianMaxNearby);
  result.peaks = std::move(peaks);
  result.seconds = secondsSince(started);
  return result;
}

bool boundCertainlyHolds(const Patch& patch, const PatchPeaks& peaks) {
  const auto& s = patch.sideLengths;
  // e = d(c0, c2) <= min(s0 + s1, s3 + s2) and f = d(c1, c3) <= min(s1 + s2, s0 + s3) (triangle
  // inequality).
  const double upper = std::max({s[0], s[1], s[2], s[3], std::min(s[0] + s[1], s[3] + s[2]),
                                 std::min(s[1] + s[2], s[0] + s[3])});
  return upper < injectivityRadiusBound(peaks.gaussianMax);
}

std::vector<SurfacePoint> uniquenessPeakTargets(const Patch& patch, int n) {
  std::vector<SurfacePoint> targets;
  targets.reserve(4 * static_cast<size_t>(n));
  for (Family family : {Family::U, Family::V})
    for (bool end : {false, true})
      for (int k = 0; k < n; ++k)
        targets.push_back(
            familyBoundaryPoint(patch, family, end, static_cast<double>(k) / (n - 1)));
  return targets;
}

UniquenessReport checkUniqueness(const Patch& patch, const geodesic::DistanceSolver& solver,
                                 const UniquenessOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  UniquenessReport report;
  const PatchPeaks peaks = findPatchPeaks(patch, options);
  report.gaussianMax = peaks.gaussianMax;
  report.injectivityBoundM = injectivityRadiusBound(report.gaussianMax);

  // One batch: the diagonals e = d(c0, c2), f = d(c1, c3) (longest-geodesic proxy together with the
  // sides) and the fields from the peaks, which are only used when the bound fails.
  const int n = options.sideSamples;
  std::vector<SurfacePoint> targets = uniquenessPeakTargets(patch, n);
  const size_t cornerTargets = targets.size();
  targets.push_back(geodesic::vertexPoint(patch.mesh, patch.cornerVertices[2]));
  targets.push_back(geodesic::vertexPoint(patch.mesh, patch.cornerVertices[3]));
  std::vector<SurfacePoint> sources{geodesic::vertexPoint(patch.mesh, patch.cornerVertices[0]),
                                    geodesic::vertexPoint(patch.mesh, patch.cornerVertices[1])};
  const bool needPeaks = !peaks.peaks.empty() && !boundCertainlyHolds(patch, peaks);
  if (needPeaks)
    for (const auto& p : peaks.peaks)
      sources.push_back(geodesic::vertexPoint(patch.mesh, p.vertex));
  const auto fields = solver.distances(sources, targets);
  report.propagations += static_cast<int>(sources.size());
  const double e = fields[0].targetDistances[cornerTargets];
  const double f = fields[1].targetDistances[cornerTargets + 1];
  const auto& s = patch.sideLengths;
  report.longestGeodesicM = std::max({e, f, s[0], s[1], s[2], s[3]});
  report.boundHolds = report.longestGeodesicM < report.injectivityBoundM;
  if (report.boundHolds) {
    report.passed = true;
    report.seconds = secondsSince(started);
    return report;
  }

  // Second batch: the fields from every p1 (one per peak and family), to the same targets.
  std::vector<const std::vector<double>*> fromPeaks;
  for (size_t p = 0; p < peaks.peaks.size(); ++p)
    fromPeaks.push_back(&fields[2 + p].targetDistances);
  const auto nearest = nearestBoundaries(fromPeaks, n);
  const auto fromP1 = solver.distances(p1Points(patch, nearest, n), targets);
  report.propagations += static_cast<int>(fromP1.size());
  addEtaChecks(report, patch, peaks, fromPeaks, nearest, fromP1, n);
  report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
  report.seconds = secondsSince(started);
  return report;
}

UniquenessFields uniquenessFields(const Patch& patch, const PatchPeaks& peaks,
                                  const geodesic::DistanceSolver& solver, int n) {
  if (n < 3) throw InvalidInput("uniquenessFields: at least 3 samples per side are needed");
  UniquenessFields fields;
  fields.samples = n;
  if (peaks.peaks.empty()) return fields;
  const auto targets = uniquenessPeakTargets(patch, n);
  std::vector<SurfacePoint> sources;
  for (const auto& p : peaks.peaks) sources.push_back(geodesic::vertexPoint(patch.mesh, p.vertex));
  fields.fromPeaks = solver.distances(sources, targets);
  std::vector<const std::vector<double>*> fromPeaks;
  for (const auto& f : fields.fromPeaks) fromPeaks.push_back(&f.targetDistances);
  fields.fromP1 = solver.distances(p1Points(patch, nearestBoundaries(fromPeaks, n), n), targets);
  return fields;
}

UniquenessFields uniquenessFieldsViaProxy(const Patch& patch,
                                          const geodesic::DistanceSolver& solver,
                                          const MapProxy& proxy,
                                          const geodesic::DistanceSolver& proxySolver,
                                          const PatchPeaks& peaks, int n) {
  if (n < 3) throw InvalidInput("uniquenessFieldsViaProxy: at least 3 samples per side are needed");
  UniquenessFields fields;
  fields.samples = n;
  if (peaks.peaks.empty()) return fields;
  // Each peak on the proxy: its vertex nearest to the peak (proxy vertices are patch vertices).
  const TriMesh& coarse = proxy.patch.mesh;
  std::vector<SurfacePoint> proxyPeaks;
  for (const auto& peak : peaks.peaks) {
    int best = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (auto vh : coarse.vertices()) {
      const double d = (toEigen(coarse.point(vh)) - peak.position).squaredNorm();
      if (d < bestDistance) bestDistance = d, best = vh.idx();
    }
    proxyPeaks.push_back(geodesic::vertexPoint(coarse, best));
  }
  const auto proxyTargets = uniquenessPeakTargets(proxy.patch, n);
  fields.fromPeaks = proxySolver.distances(proxyPeaks, proxyTargets);
  std::vector<const std::vector<double>*> fromPeaks;
  for (const auto& f : fields.fromPeaks) fromPeaks.push_back(&f.targetDistances);
  const auto nearest = nearestBoundaries(fromPeaks, n);
  fields.fromP1 = proxySolver.distances(p1Points(proxy.patch, nearest, n), proxyTargets);

  // Per check (peak, family): q1 on the proxy, then the candidates q1 - 1, q1, q1 + 1 measured.
  struct Located {
    size_t peak;
    Family family;
    std::vector<int> candidates;  // sample indices on the side opposite p1
  };
  std::vector<Located> located;
  for (size_t p = 0, at = 0; p < peaks.peaks.size(); ++p)
    for (Family family : {Family::U, Family::V}) {
      const NearestBoundary& p1 = nearest[at];
      const auto& direct = fields.fromP1[at++].targetDistances;
      const int opposite = sideOffset(family, !p1.onEnd, n);
      const int q1 =
          std::max(0, leastExcess(
                          n, [&](int k) { return p1.distance + (*fromPeaks[p])[opposite + k]; },
                          [&](int k) { return direct[opposite + k]; }));
      Located l{p, family, {}};
      for (int k = std::max(0, q1 - 1); k <= std::min(n - 1, q1 + 1); ++k)
        l.candidates.push_back(k);
      located.push_back(l);
    }
  // Three directed propagations per check on the patch: p1 to the peak, p1 to the candidates, the
  // peak to the candidates. (p1 to the peak and the candidates at once would sweep every point
  // with d(p1, p) + |p p_max| up to d(p1, q): most of the patch.)
  std::vector<std::vector<double>> fromP1Fine(located.size()), fromPeakFine(located.size());
  std::vector<double> p1ToPeak(located.size());
  tbb::parallel_for(0, static_cast<int>(3 * located.size()), [&](int job) {
    const size_t c = job / 3;
    const Located& l = located[c];
    const NearestBoundary& p1 = nearest[c];
    const SurfacePoint start =
        familyBoundaryPoint(patch, l.family, p1.onEnd, static_cast<double>(p1.index) / (n - 1));
    const SurfacePoint peak = geodesic::vertexPoint(patch.mesh, peaks.peaks[l.peak].vertex);
    std::vector<SurfacePoint> candidates;
    for (int k : l.candidates)
      candidates.push_back(
          familyBoundaryPoint(patch, l.family, !p1.onEnd, static_cast<double>(k) / (n - 1)));
    if (job % 3 == 0)
      p1ToPeak[c] = solver.distance(start, peak);
    else if (job % 3 == 1)
      fromP1Fine[c] = solver.directedDistances(start, candidates).targetDistances;
    else
      fromPeakFine[c] = solver.directedDistances(peak, candidates).targetDistances;
  });
  fields.directed = static_cast<int>(3 * located.size());
  for (size_t c = 0; c < located.size(); ++c) {
    const Located& l = located[c];
    const NearestBoundary& p1 = nearest[c];
    const auto viaPeak = [&](int i) { return p1ToPeak[c] + fromPeakFine[c][i]; };
    const auto direct = [&](int i) { return fromP1Fine[c][i]; };
    for (size_t i = 0; i < l.candidates.size(); ++i)
      if (!std::isfinite(viaPeak(i)) || !std::isfinite(direct(i)))
        throw SolverFailure(
            "eta check: a boundary sample is unreachable from p1 or the peak inside the patch");
    const int i = leastExcess(static_cast<int>(l.candidates.size()), viaPeak, direct);
    const EtaCheck check =
        makeCheck(patch, l.family, peaks.peaks[l.peak], p1, n, i >= 0 ? l.candidates[i] : -1,
                  i >= 0 ? viaPeak(i) : 0.0, i >= 0 ? direct(i) : 1.0);
    fields.measured.push_back(check);
  }
  return fields;
}

bool measureDiagonalsNearTheBound(PatchDistanceMaps& maps, const Patch& patch,
                                  const geodesic::DistanceSolver& solver, const PatchPeaks& peaks,
                                  double band) {
  const double bound = injectivityRadiusBound(peaks.gaussianMax);
  const double diagonal = std::max(maps.diagonalE, maps.diagonalF);
  if (!std::isfinite(bound) || std::abs(diagonal - bound) > band * bound) return false;
  const auto corner = [&](int k) {
    return geodesic::vertexPoint(patch.mesh, patch.cornerVertices[k]);
  };
  double e = 0.0, f = 0.0;
  tbb::parallel_invoke([&] { e = solver.distance(corner(0), corner(2)); },
                       [&] { f = solver.distance(corner(3), corner(1)); });
  if (!std::isfinite(e) || !std::isfinite(f))
    throw SolverFailure("uniqueness: opposite corners are unreachable inside the patch");
  maps.diagonalE = e;
  maps.diagonalF = f;
  return true;
}

UniquenessReport checkUniqueness(const Patch& patch, const PatchPeaks& peaks,
                                 const UniquenessFields& fields, const PatchDistanceMaps& maps,
                                 const UniquenessOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  UniquenessReport report;
  report.gaussianMax = peaks.gaussianMax;
  report.injectivityBoundM = injectivityRadiusBound(report.gaussianMax);
  const auto& s = patch.sideLengths;
  report.longestGeodesicM = std::max({maps.diagonalE, maps.diagonalF, s[0], s[1], s[2], s[3]});
  report.boundHolds = report.longestGeodesicM < report.injectivityBoundM;
  if (report.boundHolds) {
    report.passed = true;
    report.seconds = secondsSince(started) + peaks.seconds;
    return report;
  }
  if (!fields.measured
           .empty()) {  // uniquenessFieldsViaProxy measured the checks on the patch already
    for (const auto& check : fields.measured) addCheck(report, check);
    report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
    report.seconds = secondsSince(started) + peaks.seconds;
    return report;
  }
  const int n = fields.samples;
  if (n != maps.u.n1)
    throw InvalidInput(
        "checkUniqueness: the fields must target uniquenessPeakTargets(patch, map resolution)");
  if (fields.fromPeaks.size() != peaks.peaks.size() ||
      fields.fromP1.size() != 2 * peaks.peaks.size())
    throw InvalidInput(
        "checkUniqueness: one peak field per peak and one p1 field per peak and family are needed "
        "when the injectivity bound fails (uniquenessFields)");
  std::vector<const std::vector<double>*> fromPeaks;
  for (const auto& f : fields.fromPeaks) fromPeaks.push_back(&f.targetDistances);
  for (const auto* d : fromPeaks)
    if (d->size() != 4 * static_cast<size_t>(n))
      throw InvalidInput(
          "checkUniqueness: peak fields must target uniquenessPeakTargets(patch, n)");
  for (const auto& f : fields.fromP1)
    if (f.targetDistances.size() != 4 * static_cast<size_t>(n))
      throw InvalidInput("checkUniqueness: p1 fields must target uniquenessPeakTargets(patch, n)");
  addEtaChecks(report, patch, peaks, fromPeaks, nearestBoundaries(fromPeaks, n), fields.fromP1, n);
  report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
  report.seconds = secondsSince(started) + peaks.seconds;
  return report;
}

}  // namespace egg
