#include "core/egg/uniqueness.hpp"

#include "core/curvature/curvature.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

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
}

namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Offsets of the family's start and end side samples in uniquenessPeakTargets.
int sideOffset(Family family, bool end, int n) { return (family == Family::U ? 0 : 2 * n) + (end ? n : 0); }

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

// eta for one family and peak: q1 on the side opposite p1 minimises d(p1,p_max) + d(p_max,q) - d(p1,q).
// `fromP1(k)` is d(p1, sample k of the opposite side).
EtaCheck etaCheck(const Patch& patch, Family family, const CurvaturePeak& peak, const std::vector<double>& fromPeak,
                  const NearestBoundary& p1, int n, const std::function<double(int)>& fromP1) {
  EtaCheck check;
  check.family = family;
  check.peakVertex = peak.vertex;
  check.peak = peak.position;
  check.gaussian = peak.gaussian_max_nearby;
  const double x1 = static_cast<double>(p1.index) / (n - 1);
  check.p1 = position(patch.mesh, familyBoundaryPoint(patch, family, p1.onEnd, x1));
  double bestExcess = std::numeric_limits<double>::infinity();
  const int opposite = sideOffset(family, !p1.onEnd, n);
  for (int k = 0; k < n; ++k) {
    const double viaPeak = p1.distance + fromPeak[opposite + k];
    const double direct = fromP1(k);
    if (!(direct > 0.0) || viaPeak - direct >= bestExcess) continue;
    bestExcess = viaPeak - direct;
    check.eta = viaPeak / direct;
    check.q1 = position(patch.mesh, familyBoundaryPoint(patch, family, !p1.onEnd, static_cast<double>(k) / (n - 1)));
  }
  return check;
}

void addCheck(UniquenessReport& report, const EtaCheck& check) {
  double& worst = check.family == Family::U ? report.etaU : report.etaV;
  worst = std::max(worst, check.eta);
  report.checks.push_back(check);
}

}  // namespace

PatchPeaks findPatchPeaks(const Patch& patch, const UniquenessOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  PatchPeaks result;
  const auto curvature = computeCurvature(patch.mesh);
  PeakOptions peakOptions;
  peakOptions.include_boundary = false;  // a peak on the boundary is harmless (Section 2.3.3)
  auto peaks = findGaussianPeaks(patch.mesh, curvature.gaussian, curvature.mixed_area, peakOptions);
  peaks.erase(std::remove_if(peaks.begin(), peaks.end(), [](const CurvaturePeak& p) { return p.gaussian_max_nearby <= 0; }),
              peaks.end());
  if (static_cast<int>(peaks.size()) > options.maxPeaks) peaks.resize(options.maxPeaks);
  for (const auto& p : peaks) result.gaussianMax = std::max(result.gaussianMax, p.gaussian_max_nearby);
  result.peaks = std::move(peaks);
  result.seconds = secondsSince(started);
  return result;
}

bool boundCertainlyHolds(const Patch& patch, const PatchPeaks& peaks) {
  const auto& s = patch.sideLengths;
  // e = d(c0, c2) <= min(s0 + s1, s3 + s2) and f = d(c1, c3) <= min(s1 + s2, s0 + s3) (triangle inequality).
  const double upper = std::max({s[0], s[1], s[2], s[3], std::min(s[0] + s[1], s[3] + s[2]), std::min(s[1] + s[2], s[0] + s[3])});
  return upper < injectivityRadiusBound(peaks.gaussianMax);
}

std::vector<SurfacePoint> uniquenessPeakTargets(const Patch& patch, int n) {
  std::vector<SurfacePoint> targets;
  targets.reserve(4 * static_cast<size_t>(n));
  for (Family family : {Family::U, Family::V})
    for (bool end : {false, true})
      for (int k = 0; k < n; ++k) targets.push_back(familyBoundaryPoint(patch, family, end, static_cast<double>(k) / (n - 1)));
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
    for (const auto& p : peaks.peaks) sources.push_back(geodesic::vertexPoint(patch.mesh, p.vertex));
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

  // Second batch: the fields from every p1 (one per peak and family).
  std::vector<NearestBoundary> nearest;
  std::vector<SurfacePoint> p1Sources;
  for (size_t p = 0; p < peaks.peaks.size(); ++p)
    for (Family family : {Family::U, Family::V}) {
      nearest.push_back(nearestBoundary(fields[2 + p].targetDistances, family, n));
      p1Sources.push_back(targets[sideOffset(family, nearest.back().onEnd, n) + nearest.back().index]);
    }
  const auto fromP1 = solver.distances(p1Sources, targets);
  report.propagations += static_cast<int>(p1Sources.size());
  size_t q = 0;
  for (size_t p = 0; p < peaks.peaks.size(); ++p)
    for (Family family : {Family::U, Family::V}) {
      const size_t at = q++;
      const int opposite = sideOffset(family, !nearest[at].onEnd, n);
      const auto& d = fromP1[at].targetDistances;
      addCheck(report, etaCheck(patch, family, peaks.peaks[p], fields[2 + p].targetDistances, nearest[at], n,
                                [&](int k) { return d[opposite + k]; }));
    }
  report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
  report.seconds = secondsSince(started);
  return report;
}

UniquenessReport checkUniqueness(const Patch& patch, const PatchPeaks& peaks,
                                 const std::vector<geodesic::DistanceField>& peakFields, const PatchDistanceMaps& maps,
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
  const int n = maps.u.n1;
  if (maps.u.n2 != n || maps.v.n1 != n || maps.v.n2 != n)
    throw InvalidInput("checkUniqueness: the distance maps must be square and of one size");
  if (peakFields.size() != peaks.peaks.size())
    throw InvalidInput("checkUniqueness: one peak field per peak is needed when the injectivity bound fails");
  for (size_t p = 0; p < peaks.peaks.size(); ++p) {
    const auto& fromPeak = peakFields[p].targetDistances;
    if (fromPeak.size() != 4 * static_cast<size_t>(n))
      throw InvalidInput("checkUniqueness: peak fields must target uniquenessPeakTargets(patch, map resolution)");
    for (Family family : {Family::U, Family::V}) {
      const DistanceMap& map = maps.map(family);
      const NearestBoundary p1 = nearestBoundary(fromPeak, family, n);
      // map.at(i, j) = d(start_i, end_j): a row is the field of a start sample, a column that of an end sample.
      addCheck(report, etaCheck(patch, family, peaks.peaks[p], fromPeak, p1, n, [&](int k) {
                 return p1.onEnd ? map.at(k, p1.index) : map.at(p1.index, k);
               }));
    }
  }
  report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
  report.seconds = secondsSince(started) + peaks.seconds;
  return report;
}

}  // namespace egg
