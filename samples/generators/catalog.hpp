#pragma once
// Internal: the samples known to the registry, grouped by topic (architectural, test surfaces,
// Chapter 4 patches).
#include "samples/generators/samples.hpp"
#include "samples/generators/surface_spec.hpp"

#include <functional>
#include <string>
#include <vector>

namespace egg::samples::detail {

struct SampleEntry {
  SampleInfo info;
  // Builds the surface from a complete parameter set (defaults already merged); throws
  // InvalidInput naming the sample and parameter when a value is out of range.
  std::function<SurfaceSpec(const Params&)> build;
};

std::vector<SampleEntry> architecturalSamples();
std::vector<SampleEntry> testSurfaceSamples();
std::vector<SampleEntry> chapter4Samples();  // Table 4.1 analogues (desktop size)

// Shared helpers for the builders.
// A counter-clockwise axis-aligned rectangle [x0, x1] x [y0, y1] as four straight curves.
BoundaryLoop rectangleLoop(double x0, double x1, double y0, double y1);
// A closed ellipse centred at `centre` with semi-axes (rx, ry), one curve.
BoundaryLoop ellipseLoop(const Vec2& centre, double rx, double ry);
// Throws InvalidInput "sample 'name': parameter 'key' <requirement> (got value)" unless ok.
void require(bool ok, const std::string& sample, const std::string& key, double value,
             const std::string& requirement);

}  // namespace egg::samples::detail
