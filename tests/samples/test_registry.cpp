#include "samples/generators/samples.hpp"

#include "core/errors.hpp"
#include "tests/samples/mesh_checks.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

namespace egg::samples {
namespace {

TEST(SamplesRegistry, Stats) {
  for (const auto& info : listSamples()) {
    const double h = info.name == "yas" ? 3.0 : info.name == "great_court" || info.name == "lilium" ? 1.5 : 0.4;
    const auto t0 = std::chrono::steady_clock::now();
    const TriMesh mesh = generateSample(info.name, {}, h);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto r = testing::inspect(mesh);
    const double area = surfaceArea(mesh);
    std::printf("%-12s h=%.2f V=%6zu F=%6zu comp=%d loops=%d cplx=%d minAng=%.1f mean/h=%.3f max/h=%.2f min/h=%.2f F/(A/0.433h2)=%.3f %.2fs\n",
                info.name.c_str(), h, mesh.n_vertices(), mesh.n_faces(), r.components, r.boundaryLoops,
                r.complexVertices, r.minAngleDeg, r.meanEdge / h, r.maxEdge / h, r.minEdge / h,
                mesh.n_faces() / (area / (0.4330127 * h * h)), seconds);
  }
}

}  // namespace
}  // namespace egg::samples
