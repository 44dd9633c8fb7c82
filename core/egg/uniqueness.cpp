#include "core/egg/uniqueness.hpp"

#include "core/curvature/curvature.hpp"
#include "core/curvature/curvature_peaks.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace egg {

void UniquenessOptions::validate() const {
  if (!(etaMax >= 1.0)) throw InvalidInput("patching.eta_max must be >= 1");
  if (maxPeaks < 1) throw InvalidInput("uniqueness max_peaks must be >= 1");
  if (sideSamples < 3) throw InvalidInput("uniqueness side_samples must be >= 3");
  if (maxSmoothingRounds < 0) throw InvalidInput("uniqueness max_smoothing_rounds must be >= 0");
}

UniquenessReport checkUniqueness(const Patch& patch, const geodesic::DistanceSolver& solver,
                                 const UniquenessOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  UniquenessReport report;
  const auto curvature = computeCurvature(patch.mesh);
  PeakOptions peakOptions;
  peakOptions.include_boundary = false;  // a peak on the boundary is harmless (Section 2.3.3)
  auto peaks = findGaussianPeaks(patch.mesh, curvature.gaussian, curvature.mixed_area, peakOptions);
  peaks.erase(std::remove_if(peaks.begin(), peaks.end(), [](const CurvaturePeak& p) { return p.gaussian_max_nearby <= 0; }),
              peaks.end());
  if (static_cast<int>(peaks.size()) > options.maxPeaks) peaks.resize(options.maxPeaks);
  for (const auto& p : peaks) report.gaussianMax = std::max(report.gaussianMax, p.gaussian_max_nearby);
  report.injectivityBoundM = injectivityRadiusBound(report.gaussianMax);

  // Longest geodesic proxy: sides and diagonals.
  const auto c0 = geodesic::vertexPoint(patch.mesh, patch.cornerVertices[0]);
  const auto c1 = geodesic::vertexPoint(patch.mesh, patch.cornerVertices[1]);
  const double e = solver.distance(c0, geodesic::vertexPoint(patch.mesh, patch.cornerVertices[2]));
  const double f = solver.distance(c1, geodesic::vertexPoint(patch.mesh, patch.cornerVertices[3]));
  report.longestGeodesicM = std::max({e, f, patch.sideLengths[0], patch.sideLengths[1], patch.sideLengths[2], patch.sideLengths[3]});
  report.boundHolds = report.longestGeodesicM < report.injectivityBoundM;
  if (report.boundHolds) {
    report.passed = true;
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return report;
  }

  const int n = options.sideSamples;
  for (const auto& peak : peaks) {
    const auto source = geodesic::vertexPoint(patch.mesh, peak.vertex);
    for (Family family : {Family::U, Family::V}) {
      std::array<std::vector<SurfacePoint>, 2> side;
      std::vector<SurfacePoint> targets;
      for (bool end : {false, true})
        for (int k = 0; k < n; ++k) {
          side[end].push_back(familyBoundaryPoint(patch, family, end, static_cast<double>(k) / (n - 1)));
          targets.push_back(side[end].back());
        }
      const auto fromPeak = solver.distances(source, targets);
      int nearest = 0;
      for (int k = 1; k < 2 * n; ++k)
        if (fromPeak.targetDistances[k] < fromPeak.targetDistances[nearest]) nearest = k;
      const bool p1OnEnd = nearest >= n;
      const SurfacePoint p1 = targets[nearest];
      const double peakToP1 = fromPeak.targetDistances[nearest];
      const auto fromP1 = solver.distances(p1, side[!p1OnEnd]);
      EtaCheck check;
      check.family = family;
      check.peakVertex = peak.vertex;
      check.peak = peak.position;
      check.gaussian = peak.gaussian_max_nearby;
      check.p1 = position(patch.mesh, p1);
      double bestExcess = std::numeric_limits<double>::infinity();
      for (int k = 0; k < n; ++k) {
        const double viaPeak = peakToP1 + fromPeak.targetDistances[(p1OnEnd ? 0 : n) + k];
        const double direct = fromP1.targetDistances[k];
        if (!(direct > 0.0) || viaPeak - direct >= bestExcess) continue;
        bestExcess = viaPeak - direct;
        check.eta = viaPeak / direct;
        check.q1 = position(patch.mesh, side[!p1OnEnd][k]);
      }
      (family == Family::U ? report.etaU : report.etaV) =
          std::max(family == Family::U ? report.etaU : report.etaV, check.eta);
      report.checks.push_back(check);
    }
  }
  report.passed = report.etaU <= options.etaMax && report.etaV <= options.etaMax;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return report;
}

}  // namespace egg
