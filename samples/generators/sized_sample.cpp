#include "samples/generators/samples.hpp"

#include <cmath>

namespace egg::samples {

TriMesh generateSampleWithVertices(const std::string& name, int vertices) {
  Params params;
  for (const auto& info : listSamples())
    if (info.name == name) params = info.defaults;
  const double area =
      params.count("length") && params.count("width") ? params["length"] * params["width"] : 100.0;
  // An equilateral mesh of edge e has about 2 area / (sqrt(3) e^2) vertices.
  double edge = std::sqrt(2.0 * area / (std::sqrt(3.0) * vertices));
  TriMesh mesh = generateSample(name, {}, edge);
  const double ratio = double(mesh.n_vertices()) / vertices;
  if (ratio < 0.85 || ratio > 1.15) {
    edge *= std::sqrt(ratio);
    mesh = generateSample(name, {}, edge);
  }
  return mesh;
}

}  // namespace egg::samples
