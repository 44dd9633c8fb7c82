// Boundary sampling: the boundary vertices of every sample are placed once, exactly on the analytic
// boundary curves and at an even 3D spacing, and stay fixed while the interior is remeshed.
#include "samples/generators/boundary_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg::samples::detail {
namespace {

// Cumulative 3D arc length of a curve at `segments` + 1 equally spaced parameters.
std::vector<double> cumulativeLength(const SurfaceSpec& spec, const DomainCurve& curve,
                                     int segments) {
  std::vector<double> length(segments + 1, 0.0);
  Vec3 previous = spec.position(curve.at(0.0));
  for (int i = 1; i <= segments; ++i) {
    const Vec3 current = spec.position(curve.at(double(i) / segments));
    length[i] = length[i - 1] + (current - previous).norm();
    previous = current;
  }
  return length;
}

// Parameter at which the cumulative length reaches `target` (linear inside one table step).
double parameterAtLength(const std::vector<double>& length, double target) {
  const int segments = int(length.size()) - 1;
  const auto it = std::lower_bound(length.begin(), length.end(), target);
  if (it == length.begin()) return 0.0;
  if (it == length.end()) return 1.0;
  const int i = int(it - length.begin());
  const double span = length[i] - length[i - 1];
  const double fraction = span > 0.0 ? (target - length[i - 1]) / span : 0.0;
  return (i - 1 + fraction) / segments;
}

}  // namespace

double curveLength3d(const SurfaceSpec& spec, const DomainCurve& curve, int segments) {
  return cumulativeLength(spec, curve, segments).back();
}

std::vector<SampledLoop> sampleBoundary(const SurfaceSpec& spec, double spacing) {
  std::vector<SampledLoop> loops;
  for (const BoundaryLoop& loop : spec.boundary) {
    // Lengths first, so a loop of one short curve still gets three points.
    std::vector<std::vector<double>> tables;
    std::vector<int> pieces;
    int total = 0;
    for (const DomainCurve& curve : loop) {
      const double rough = curveLength3d(spec, curve, 256);
      // Table fine enough that one step is a small fraction of the spacing.
      const int segments = int(std::clamp(8.0 * rough / spacing, 512.0, 2.0e6));
      tables.push_back(cumulativeLength(spec, curve, segments));
      pieces.push_back(std::max(1, int(std::lround(tables.back().back() / spacing))));
      total += pieces.back();
    }
    if (total < 3) {
      for (int& p : pieces) p = std::max(p, 3 - total + p);
    }
    SampledLoop sampled;
    for (size_t c = 0; c < loop.size(); ++c) {
      const double length = tables[c].back();
      for (int k = 0; k < pieces[c]; ++k) {
        const double s = k == 0 ? 0.0 : parameterAtLength(tables[c], length * k / pieces[c]);
        sampled.points.push_back({loop[c].at(s), int(c), s});
      }
    }
    loops.push_back(std::move(sampled));
  }
  return loops;
}

Vec2 snapToBoundary(const SurfaceSpec& spec, const std::vector<SampledLoop>& loops,
                    const Vec2& point, double tolerance, bool& found) {
  found = false;
  double best = std::numeric_limits<double>::infinity();
  Vec2 snapped = point;
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& pts = loops[l].points;
    const BoundaryLoop& curves = spec.boundary[l];
    for (size_t i = 0; i < pts.size(); ++i) {
      const BoundarySample& a = pts[i];
      const BoundarySample& b = pts[(i + 1) % pts.size()];
      const Vec2 chord = b.domain - a.domain;
      const double chord2 = chord.squaredNorm();
      if (chord2 == 0.0) continue;
      const double t = std::clamp((point - a.domain).dot(chord) / chord2, 0.0, 1.0);
      const double distance = (a.domain + t * chord - point).norm();
      if (distance > tolerance || distance >= best) continue;
      best = distance;
      found = true;
      // The chord's end may be the start of the next curve (parameter 1 of this one).
      const double sEnd = b.curve == a.curve && b.s > a.s ? b.s : 1.0;
      snapped = curves[a.curve].at(a.s + t * (sEnd - a.s));
    }
  }
  return snapped;
}

}  // namespace egg::samples::detail
