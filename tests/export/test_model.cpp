#include "export/model.hpp"

#include "core/errors.hpp"
#include "tests/export/synthetic_model.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <map>

namespace egg::exporter {
namespace {

// Signed volume of a closed mesh (divergence theorem): positive when the triangles face outward.
double volume(const ModelMesh& m) {
  double v = 0.0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

// Every edge used once in each direction: the mesh is closed and consistently oriented.
bool closedAndOriented(const ModelMesh& m) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  // Vertices are duplicated per side: compare edges by position.
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> byPosition;
  auto key = [&](int i) {
    const auto& p = m.vertices[i];
    return std::array<double, 3>{std::round(p.x() * 1e9), std::round(p.y() * 1e9),
                                 std::round(p.z() * 1e9)};
  };
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++byPosition[{key(t[k]), key(t[(k + 1) % 3])}];
  for (const auto& [edge, count] : byPosition) {
    const auto reverse = byPosition.find({edge.second, edge.first});
    if (count != 1 || reverse == byPosition.end() || reverse->second != 1) return false;
  }
  return true;
}

TEST(ExportModel, StraightRibbonIsTheClosedBoxOfTheSection) {
  ModelLamella l;
  l.id = "P0-U0";
  for (int k = 0; k <= 4; ++k) {
    l.centreline.emplace_back(0.5 * k, 0.0, 1.0);
    l.normals.emplace_back(0.0, 0.0, 1.0);
    l.deviationM.push_back(0.0);
  }
  const Ribbon r = ribbonOf(l, 0.25, 0.04);
  EXPECT_EQ(r.mesh.vertices.size(), 8u * 5 + 8);
  EXPECT_EQ(r.mesh.triangles.size(), 8u * 4 + 4);
  EXPECT_NEAR(volume(r.mesh), 2.0 * 0.25 * 0.04, 1e-12);  // L w t, outward
  EXPECT_TRUE(closedAndOriented(r.mesh));
  // Width across (y), thickness along the normal (z).
  double yMax = -1, zMax = -1;
  for (const auto& p : r.mesh.vertices) yMax = std::max(yMax, p.y()), zMax = std::max(zMax, p.z());
  EXPECT_NEAR(yMax, 0.125, 1e-12);
  EXPECT_NEAR(zMax, 1.02, 1e-12);
  for (size_t i = 0; i < r.normals.size(); ++i) EXPECT_NEAR(r.normals[i].norm(), 1.0, 1e-12);
}

TEST(ExportModel, CurvedRibbonVolumeFollowsTheCentreline) {
  // A quarter circle of radius 2 bent about the width axis (normal towards the centre): the
  // polygonal sweep's volume is w t times its centreline length, to the corner's second order.
  ModelLamella l;
  l.id = "P1-V3";
  const int n = 200;
  for (int k = 0; k <= n; ++k) {
    const double a = 0.5 * M_PI * k / n;
    l.centreline.emplace_back(2 * std::cos(a), 0.0, 2 * std::sin(a));
    l.normals.emplace_back(-std::cos(a), 0.0, -std::sin(a));
    l.deviationM.push_back(0.0);
  }
  const Ribbon r = ribbonOf(l, 0.1, 0.01);
  EXPECT_TRUE(closedAndOriented(r.mesh));
  EXPECT_NEAR(volume(r.mesh), 0.1 * 0.01 * M_PI, 1e-6);
}

TEST(ExportModel, BoltIsAClosedHexagonalPrism) {
  const ModelBolt bolt{"P0-C0-0", 0, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 1, 0)};
  const ModelMesh m = boltSolid(bolt, 0.02, 0.08);
  EXPECT_TRUE(closedAndOriented(m));
  const double hexagon = 1.5 * std::sqrt(3.0) * 0.01 * 0.01;
  EXPECT_NEAR(volume(m), hexagon * 0.08, 1e-12);
}

TEST(ExportModel, DeviationColoursRunFromViridisStartToEnd) {
  const Eigen::Vector3d low = deviationColour(0.0, 0.01), high = deviationColour(0.01, 0.01);
  EXPECT_GT(low.z(), low.y());                                           // dark blue-violet
  EXPECT_GT(high.x(), high.z());                                         // yellow
  EXPECT_NEAR(high.x(), std::pow((0.993 + 0.055) / 1.055, 2.4), 1e-12);  // sRGB -> linear
  EXPECT_EQ(deviationColour(0.5, 0.0), low);  // no deviation at all: one colour
}

TEST(ExportModel, ValidateNamesTheBadLamella) {
  StructureModel model = testing::syntheticModel();
  model.validate();
  model.lamellas[4].normals.pop_back();
  try {
    model.validate();
    FAIL() << "accepted a lamella with a missing normal";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(model.lamellas[4].id), std::string::npos) << e.what();
  }
  model = testing::syntheticModel();
  model.lamellas[0].centreline[3].x() = std::nan("");
  EXPECT_THROW(model.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg::exporter
