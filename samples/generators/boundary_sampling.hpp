#pragma once
// Sampling of domain boundary curves at an even 3D spacing, and snapping of points that lie on the
// sampled chords back onto the exact curves.
#include "samples/generators/surface_spec.hpp"

#include <vector>

namespace egg::samples::detail {

struct BoundarySample {
  Vec2 domain;     // exact point of the curve
  int curve = 0;   // index of the curve within its loop
  double s = 0.0;  // curve parameter
};

// One closed loop as a polygon (no repeated first point).
struct SampledLoop {
  std::vector<BoundarySample> points;
};

// Samples every loop of `spec` with 3D chord spacing close to `spacing`: each curve gets
// round(length / spacing) pieces of equal 3D arc length (at least three points per loop).
std::vector<SampledLoop> sampleBoundary(const SurfaceSpec& spec, double spacing);

// 3D length of a domain curve (dense polyline, for spacing and area estimates).
double curveLength3d(const SurfaceSpec& spec, const DomainCurve& curve, int segments);

// If `point` lies on a chord of a sampled loop (within `tolerance` in the domain), returns the
// exact curve point at the same chord fraction; otherwise returns `point` and sets found = false.
Vec2 snapToBoundary(const SurfaceSpec& spec, const std::vector<SampledLoop>& loops,
                    const Vec2& point, double tolerance, bool& found);

}  // namespace egg::samples::detail
