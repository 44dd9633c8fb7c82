#pragma once
// Procedural design surfaces (docs/architecture.md "Samples"): the three architectural scenes of
// Chapter 3 and the parametric test surfaces whose geodesics and curvatures are known in closed
// form.
#include "core/mesh/mesh.hpp"

#include <map>
#include <string>
#include <vector>

namespace egg::samples {

// Named numeric parameters of a sample (metres, radians, or dimensionless; 0/1 for switches).
using Params = std::map<std::string, double>;

struct SampleInfo {
  std::string name;
  std::string description;
  Params defaults;  // every accepted parameter with its default value
  std::map<std::string, std::string> parameterHelp;  // per parameter: meaning and unit, one line
};

// All samples, in a stable order.
std::vector<SampleInfo> listSamples();

// True if `name` is a sample (so the CLI can tell a sample name from a file path).
bool isSample(const std::string& name);

// Triangulates sample `name` with edges of about `edgeLengthM` metres: the mean 3D edge length is
// within a few per cent of it, triangles are near-equilateral on the surface (smallest angle above
// 20 degrees once the edge is below a tenth of the surface's size), every vertex lies on the
// analytic surface to rounding, footprint corners and spot heights (Great Court) or the tip
// (Lilium) are vertices, and normals point up / outward. The mesh is one connected, manifold,
// consistently oriented component with about area / (0.433 h^2) triangles. Throws InvalidInput
// naming the sample or parameter when the name is unknown, a parameter is unknown or out of range,
// or the edge length is not positive / would give an absurd number of triangles.
TriMesh generateSample(const std::string& name, const Params& params, double edgeLengthM);

// The sample with its default parameters meshed to about `vertices` vertices (within 15 %): the
// edge length from its footprint (length x width, 100 m^2 without them), corrected once by the
// count it gave. Benchmarks size their surfaces by this.
TriMesh generateSampleWithVertices(const std::string& name, int vertices);

}  // namespace egg::samples
