#include "export/mesh_writers.hpp"

#include "tests/export/synthetic_model.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

namespace egg::exporter {
namespace {

TEST(ExportMeshWriters, ObjHasAnObjectAndGroupPerLamellaNamedById) {
  const StructureModel model = testing::syntheticModel(3, 2);
  const std::string obj = modelObj(model);
  std::istringstream in(obj);
  std::string line;
  std::vector<std::string> groups;
  int vertices = 0, faces = 0;
  while (std::getline(in, line)) {
    if (line.rfind("g ", 0) == 0) groups.push_back(line.substr(2));
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("f ", 0) == 0) ++faces;
  }
  for (const auto& l : model.lamellas)
    EXPECT_EQ(std::count(groups.begin(), groups.end(), l.id), 1) << l.id;
  EXPECT_EQ(groups.size(), 1u + 10 + 2 + 2);  // surface, lamellas, bolts per patch, supports
  // Ribbons 8 n + 8 vertices, bolts 12, cubes 8, the surface 4.
  EXPECT_EQ(vertices, 4 + 10 * (8 * 11 + 8) + 12 * 12 + 2 * 8);
  EXPECT_EQ(faces, 2 + 10 * (8 * 10 + 4) + 12 * 20 + 2 * 12);
}

TEST(ExportMeshWriters, SupportsStlHoldsEveryBlockAtItsSitePosition) {
  const StructureModel model = testing::syntheticModel();
  const std::string stl = supportsStl(model);
  uint32_t triangles = 0;
  std::memcpy(&triangles, stl.data() + 80, 4);
  EXPECT_EQ(triangles, 24u);
  EXPECT_EQ(stl.size(), 84u + 50u * 24);
  float xMax = -1e9f;
  for (uint32_t t = 0; t < triangles; ++t)
    for (int v = 0; v < 3; ++v) {
      float x = 0;
      std::memcpy(&x, stl.data() + 84 + 50 * t + 12 + 12 * v, 4);
      xMax = std::max(xMax, x);
    }
  EXPECT_NEAR(xMax, 3.1f, 1e-6);  // the second patch's block, centred at x = 3
}

}  // namespace
}  // namespace egg::exporter
