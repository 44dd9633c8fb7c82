#include "patching/layout.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::patching {
namespace {

// A 3 x 3 grid of corners over [-3, 3]^2 (indices row by row) and the four quads between them.
std::vector<Eigen::Vector3d> gridCorners(const TriMesh& surface) {
  std::vector<Eigen::Vector3d> corners;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d p(-3.0 + 3.0 * i, -3.0 + 3.0 * j, 0.0);
      corners.push_back(position(surface, geodesic::snapToSurface(surface, p)));
    }
  return corners;
}
const std::vector<std::array<int, 4>> kTwoByTwo{
    {0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}};

TriMesh bump() {
  return samples::generateSample("bump",
                                 {{"length", 8}, {"width", 8}, {"height", 1}, {"sigma", 1.5}}, 0.3);
}

TEST(Layout, TwoByTwoOnABumpSharesEverySideBitForBit) {
  const TriMesh surface = bump();
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout = makeLayout(surface, solver, gridCorners(surface), kTwoByTwo);
  EXPECT_EQ(layout.curves.size(), 12u);  // 12 distinct sides, none a T-junction
  EXPECT_EQ(layout.segments.size(), 12u);
  for (const auto& p : layout.curveProblems) EXPECT_EQ(p, "");
  std::vector<LayoutPatch> cut;
  for (int p = 0; p < 4; ++p) cut.push_back(cutLayoutPatch(layout, p));
  // Patch 0's side 1 (corner 1 -> 4) is patch 1's side 3 (corner 4 -> 1), the same polyline.
  const auto sidePoints = [&](int p, int k) {
    std::vector<Eigen::Vector3d> out;
    for (int v : cut[p].patch.sides[k])
      out.push_back(toEigen(cut[p].patch.mesh.point(TriMesh::VertexHandle(v))));
    return out;
  };
  auto a = sidePoints(0, 1), b = sidePoints(1, 3);
  std::reverse(b.begin(), b.end());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;  // bit-identical
  // The four patches tile the square: areas add up to the layout cell areas, no face twice.
  std::set<int> faces;
  double area = 0.0;
  for (const auto& c : cut) {
    area += c.patch.area;
    for (int f : c.layoutFace) EXPECT_TRUE(faces.insert(f).second);
    for (int k = 0; k < 4; ++k) EXPECT_LT(c.patch.innerAngles[k], M_PI);
  }
  EXPECT_GT(area, 36.0);
  // Every patch vertex maps back to a layout vertex at the same position.
  for (const auto& c : cut)
    for (auto vh : c.patch.mesh.vertices())
      EXPECT_EQ(c.patch.mesh.point(vh),
                layout.mesh.mesh.point(TriMesh::VertexHandle(c.layoutVertex[vh.idx()])));
}

TEST(Layout, TJunctionCornerLiesOnTheLongSide) {
  // One tall patch on the left (corners 0, 1, 4, 3 with 1 ... no: 0-1-7-6) and two on the right
  // sharing its right side, which corner 4 splits (a T-junction).
  const TriMesh surface = bump();
  const geodesic::DistanceSolver solver(surface);
  const std::vector<std::array<int, 4>> quads{{0, 1, 7, 6}, {1, 2, 5, 4}, {4, 5, 8, 7}};
  auto corners = gridCorners(surface);
  const PatchLayout layout = makeLayout(surface, solver, corners, quads);
  // Side 1 -> 7 is one curve carrying corner 4.
  int curve = -1;
  for (size_t c = 0; c < layout.curves.size(); ++c)
    if (layout.curves[c].corners.size() == 3) curve = static_cast<int>(c);
  ASSERT_GE(curve, 0);
  EXPECT_EQ(layout.curves[curve].corners[1], 4);
  EXPECT_EQ(layout.patchSides[0][1].size(), 2u);  // the tall patch's right side: two segments
  for (int p = 0; p < 3; ++p) EXPECT_NO_THROW(cutLayoutPatch(layout, p)) << p;
  // The T corner was moved onto the geodesic: on the bump's symmetry line x = 0 it stays put.
  EXPECT_LT(layout.cornerOffsets[4], 0.05);
}

TEST(Layout, BadIndicesNameThePatch) {
  const TriMesh surface = bump();
  const geodesic::DistanceSolver solver(surface);
  try {
    makeLayout(surface, solver, gridCorners(surface), {{0, 1, 4, 9}});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("patch 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(makeLayout(surface, solver, gridCorners(surface), {{0, 1, 1, 3}}), InvalidInput);
}

// Issue 40: four corners 1e-7 m apart ended as "solver failure" with no report; a patch whose
// corners the mesh cannot tell apart is bad input naming them.
TEST(Layout, CornersCloserThanTheMeshResolvesAreBadInput) {
  const TriMesh surface = bump();
  const geodesic::DistanceSolver solver(surface);
  const Eigen::Vector3d c = position(surface, geodesic::snapToSurface(surface, {0.3, 0.2, 0}));
  const std::vector<Eigen::Vector3d> corners{c, c + Eigen::Vector3d(1e-7, 0, 0),
                                             c + Eigen::Vector3d(1e-7, 1e-7, 0),
                                             c + Eigen::Vector3d(0, 1e-7, 0)};
  try {
    makeLayout(surface, solver, corners, {{0, 1, 2, 3}});
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("apart, less than half the mesh's mean edge length") !=
                    std::string::npos ||
                what.find("coincide") != std::string::npos)
        << what;
  }
  // Corners a tenth of an edge apart (distinct on the surface) say how far apart they are.
  const double h = 0.1 * meanEdgeLength(surface);
  try {
    makeLayout(surface, solver,
               {c, c + Eigen::Vector3d(h, 0, 0), c + Eigen::Vector3d(h, h, 0),
                c + Eigen::Vector3d(0, h, 0)},
               {{0, 1, 2, 3}});
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("patch 0: corners"), std::string::npos) << e.what();
  }
}

TEST(Layout, CrossingSidesMakeThePatchInfeasibleNotTheOthers) {
  const TriMesh surface = bump();
  const geodesic::DistanceSolver solver(surface);
  // Patch 1 is a bow tie (its sides cross); patch 0 is fine.
  const PatchLayout layout =
      makeLayout(surface, solver, gridCorners(surface), {{0, 1, 4, 3}, {1, 5, 2, 4}});
  EXPECT_NO_THROW(cutLayoutPatch(layout, 0));
  EXPECT_THROW(cutLayoutPatch(layout, 1), InfeasiblePatch);
}

}  // namespace
}  // namespace egg::patching
