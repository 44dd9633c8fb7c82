// Height-field grids written as OBJ text: counts, holes, offsets and heights known by hand, and the
// text reads back through the mesh importer.
#include "samples/generators/obj_grid.hpp"

#include "core/io/mesh_io.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace egg::samples {
namespace {

int count(const std::string& text, const std::string& prefix) {
  int n = 0;
  for (size_t at = 0; (at = text.find("\n" + prefix, at)) != std::string::npos; ++at) ++n;
  return n + (text.rfind(prefix, 0) == 0 ? 1 : 0);
}

TEST(ObjGrid, AGridOfNxByNyCellsHasItsVerticesAndTwoTrianglesPerCell) {
  ObjText obj;
  addHeightFieldGrid(obj, 4, 3, 8.0, 6.0, gaussianBump(2.0, 1.0));
  EXPECT_EQ(obj.vertices, 5 * 4);
  EXPECT_EQ(count(obj.text, "v "), 20);
  EXPECT_EQ(count(obj.text, "f "), 2 * 4 * 3);
  // The first vertex is the corner (-4, -3), the bump's height there h exp(-25 / 2).
  EXPECT_EQ(obj.text.rfind(fmt::format("v -4 -3 {:.9g}\n", 2.0 * std::exp(-12.5)), 0), 0u)
      << obj.text.substr(0, 40);
  EXPECT_DOUBLE_EQ(gaussianBump(2.0, 1.0)(0.0, 0.0), 2.0);
}

TEST(ObjGrid, SkippedCellsLoseTheirTrianglesAndASecondGridNumbersOn) {
  ObjText obj;
  addHeightFieldGrid(obj, 4, 4, 4.0, 4.0, gaussianBump(1.0, 1.0),
                     [](double x, double y) { return x > 0 && y > 0; });  // 4 of 16 cells
  EXPECT_EQ(count(obj.text, "f "), 2 * 12);
  addHeightFieldGrid(obj, 1, 1, 1.0, 1.0, gaussianBump(1.0, 1.0), {}, 10.0);
  EXPECT_EQ(obj.vertices, 25 + 4);
  EXPECT_NE(obj.text.find("f 26 27 29\n"), std::string::npos);  // its ids follow the first grid's
  EXPECT_NE(obj.text.find("v 9.5 -0.5 "), std::string::npos);
}

TEST(ObjGrid, TheTextReadsBackAsAMesh) {
  ObjText obj;
  addHeightFieldGrid(obj, 6, 5, 6.0, 5.0, gaussianBump(1.0, 2.0));
  const auto file = std::filesystem::temp_directory_path() /
                    ("egg_obj_grid_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(file) << obj.text;
  const TriangleSoup soup = readMeshFile(file);
  std::filesystem::remove(file);
  EXPECT_EQ(soup.triangles.size(), 60u);
}

TEST(SizedSample, ABumpMeshedToAVertexCountHasItWithinFifteenPercent) {
  for (int vertices : {1000, 4000}) {
    const TriMesh mesh = generateSampleWithVertices("bump", vertices);
    EXPECT_NEAR(double(mesh.n_vertices()) / vertices, 1.0, 0.15) << vertices;
  }
}

}  // namespace
}  // namespace egg::samples
