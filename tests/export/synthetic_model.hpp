#pragma once
// A small two-patch structure model with known numbers for the export tests: patch p (0, 1) sits
// 3 m apart along x, holds `uCount` u lamellas along x and `vCount` v lamellas along y on the
// paraboloid z = 0.1 (x^2 + y^2) seen locally, deviations rising along each lamella up to
// 1 mm x (index + 1), one bolt per crossing and one support block (a 0.2 m cube) per patch.
#include "export/model.hpp"

#include <fmt/core.h>

namespace egg::exporter::testing {

inline ModelMesh cube(const Eigen::Vector3d& centre, double side) {
  ModelMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(
        centre + 0.5 * side * Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) m.triangles.emplace_back(f[0], f[1], f[2]);
  return m;
}

inline StructureModel syntheticModel(int uCount = 3, int vCount = 2) {
  StructureModel model;
  model.name = "synthetic";
  model.widthM = 0.1;
  model.thicknessM = 0.02;
  model.boltDiameterM = 0.01;
  model.source = CentrelineSource::PatchSimulation;
  auto height = [](double x, double y) { return 0.1 * (x * x + y * y); };
  auto normal = [](double x, double y) {
    return Eigen::Vector3d(-0.2 * x, -0.2 * y, 1).normalized();
  };
  model.surface.vertices = {{-1, -1, 0}, {6, -1, 0}, {6, 2, 0}, {-1, 2, 0}};
  model.surface.triangles = {{0, 1, 2}, {0, 2, 3}};
  for (int p = 0; p < 2; ++p) {
    model.patches.push_back(p);
    const double x0 = 3.0 * p;
    for (int family = 0; family < 2; ++family) {
      const int count = family == 0 ? uCount : vCount;
      for (int i = 0; i < count; ++i) {
        ModelLamella l;
        l.family = family == 0 ? 'U' : 'V';
        l.patch = p;
        l.index = i;
        l.id = fmt::format("P{}-{}{}", p, l.family, i);
        l.layer = family;
        l.sheet = fmt::format("sheet_{:02d}", i + 1);
        for (int k = 0; k <= 10; ++k) {
          const double t = k / 10.0;
          const double x = family == 0 ? x0 + 2.0 * t : x0 + 0.5 * i;
          const double y = family == 0 ? 0.5 * i : 1.5 * t;
          l.centreline.emplace_back(x, y, height(x - x0, y));
          l.normals.push_back(normal(x - x0, y));
          l.deviationM.push_back(1e-3 * (i + 1) * t);
        }
        l.lengthM = l.spatialLengthM = family == 0 ? 2.0 : 1.5;
        model.lamellas.push_back(l);
      }
    }
    for (int i = 0; i < uCount; ++i)
      for (int j = 0; j < vCount; ++j) {
        const double x = 0.5 * j, y = 0.5 * i;
        model.bolts.push_back({fmt::format("P{}-C{}-{}", p, i, j), p,
                               Eigen::Vector3d(x0 + x, y, height(x, y)), normal(x, y)});
      }
    ModelSupport s;
    s.id = fmt::format("S{:03d}", p + 1);
    s.patch = p;
    s.connection = fmt::format("P{}-C0-0", p);
    s.kind = "block";
    s.position = {x0, 0, 0};
    s.solid = cube({x0, 0, -0.1}, 0.2);
    model.supports.push_back(s);
  }
  return model;
}

}  // namespace egg::exporter::testing
