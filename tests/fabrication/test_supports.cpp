#include "fabrication/supports.hpp"

#include "core/errors.hpp"
#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>

namespace egg::fabrication {
namespace {

// Every directed edge once, its reverse once: a closed, consistently oriented 2-manifold.
void expectClosedManifold(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1) << e.first << "->" << e.second;
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << "open edge " << e.first << "-" << e.second;
  }
}

double signedVolume(const TriangleMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.triangles) {
    v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return v;
}

// admesh's report of a binary STL: fails the test unless 0 open edges and nothing to fix.
void expectAdmeshClosed(const std::filesystem::path& stl) {
  ASSERT_TRUE(testing::haveTool("admesh")) << "admesh missing: run scripts/install-deps.sh";
  const auto run = testing::runTool("admesh " + stl.string());
  ASSERT_EQ(run.status, 0) << run.output;
  auto field = [&](const std::string& name) {
    std::smatch m;
    const std::regex re(name + R"(\s*:\s*(-?[0-9]+))");
    if (!std::regex_search(run.output, m, re)) {
      ADD_FAILURE() << "admesh printed no \"" << name << "\":\n" << run.output;
      return -1;
    }
    return std::stoi(m[1]);
  };
  EXPECT_EQ(field("Number of parts"), 1) << run.output;
  EXPECT_EQ(field("Facets with 1 disconnected edge"), 0) << run.output;
  EXPECT_EQ(field("Facets with 2 disconnected edges"), 0) << run.output;
  EXPECT_EQ(field("Facets with 3 disconnected edges"), 0) << run.output;
  EXPECT_EQ(field("Edges fixed"), 0) << run.output;
  EXPECT_EQ(field("Facets reversed"), 0) << run.output;
  EXPECT_EQ(field("Backwards edges"), 0) << run.output;
  EXPECT_EQ(field("Normals fixed"), 0) << run.output;  // no flipped facets
  EXPECT_EQ(field("Degenerate facets"), 0) << run.output;
}

TEST(Supports, AtTheAnchorsWithTheTangentPlane) {
  const EggGrid grid = testing::handGrid();
  double ground = 0.0;
  const auto supports = planSupports({{0, &grid, std::nullopt}}, testing::handOptions(), &ground);
  ASSERT_EQ(supports.size(), 4u);   // the four corner anchors
  EXPECT_NEAR(ground, 0.4, 1e-12);  // 0.1 m below the lowest support
  EXPECT_EQ(supports[0].id, "S001");
  EXPECT_EQ(supports[3].connectionId, "P0-C2-2");
  EXPECT_EQ(supports[1].reason, "anchor: corner");
  for (const auto& s : supports) {
    EXPECT_NEAR(s.heightM, 0.1, 1e-12);
    EXPECT_NEAR(s.inclinationDeg, 0.0, 1e-12);
  }
  auto options = testing::handOptions();
  options.supportsAtBoundaryConnections = true;
  options.groundHeightM = 0.0;
  const auto all = planSupports({{0, &grid, std::nullopt}}, options);
  EXPECT_EQ(all.size(), 8u);  // every connection but the inner one
  EXPECT_NEAR(all[0].heightM, 0.5, 1e-12);
}

TEST(Supports, InclinedBlockIsAClosedSolidWithItsContactFaceThroughThePoint) {
  Support s;
  s.id = "S001";
  s.position = {1.0, 2.0, 0.6};
  s.normal = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  s.heightM = 0.25;
  const TriangleMesh mesh = supportSolid(s, 40.0, 6.0, 18.0);
  expectClosedManifold(mesh);
  const double hole = M_PI * 9.0 * 18.0;
  EXPECT_LT(signedVolume(mesh),
            40.0 * 40.0 * 250.0 - 0.8 * hole);  // the plane through the centre at 250 mm
  EXPECT_GT(signedVolume(mesh), 40.0 * 40.0 * 250.0 - 1.05 * hole);
  // Every top vertex on the contact plane through (0, 0, 250).
  for (const auto& v : mesh.vertices) {
    const double off = s.normal.dot(v - Eigen::Vector3d(0, 0, 250.0));
    EXPECT_TRUE(std::abs(off) < 1e-9 || off < -1.0) << v.transpose();  // on the plane or below it
  }
  const auto dir = testing::scratchDir("supports");
  std::ofstream(dir / "inclined.stl", std::ios::binary) << toBinaryStl(mesh, "test");
  expectAdmeshClosed(dir / "inclined.stl");
}

TEST(Supports, FlatLowSupportDropsItsBottomAndStaysClosed) {
  Support s;
  s.normal = Eigen::Vector3d(0.0, 0.8, 0.6);  // 53 deg
  s.heightM = 0.004;                          // the plane would cut the ground inside the footprint
  double drop = 0.0;
  const TriangleMesh mesh = supportSolid(s, 30.0, 4.0, 12.0, &drop);
  EXPECT_GT(drop, 0.0);
  expectClosedManifold(mesh);
  EXPECT_GT(signedVolume(mesh), 0.0);
  const auto dir = testing::scratchDir("supports_low");
  std::ofstream(dir / "low.stl", std::ios::binary) << toBinaryStl(mesh, "test");
  expectAdmeshClosed(dir / "low.stl");
}

TEST(Supports, TooSteepIsABracketAndBelowGroundAnError) {
  // A contact plane 87 degrees steep (a wall): no block can carry it; it is listed as a bracket,
  // and fabricate() draws no solid for it.
  EggGrid grid = testing::handGrid();
  grid.connections[0].normal = Eigen::Vector3d(1.0, 0.0, 0.05).normalized();
  const auto supports = planSupports({{0, &grid, std::nullopt}}, testing::handOptions());
  ASSERT_FALSE(supports.empty());
  EXPECT_FALSE(supports[0].block);
  EXPECT_NEAR(supports[0].inclinationDeg, 87.14, 0.01);
  EXPECT_TRUE(supports[1].block);
  EXPECT_NE(supportsCsv(supports).find(",bracket,,\n"), std::string::npos);
  auto options = testing::handOptions();
  options.groundHeightM = 0.6;
  const EggGrid flat = testing::handGrid();
  EXPECT_THROW(planSupports({{0, &flat, std::nullopt}}, options), InvalidInput);
}

TEST(Supports, CsvHasOneRowPerSupport) {
  const EggGrid grid = testing::handGrid();
  const auto csv = supportsCsv(planSupports({{0, &grid, std::nullopt}}, testing::handOptions()));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_EQ(csv.rfind("id,connection,reason,x_m,y_m,z_m,nx,ny,nz,inclination_deg,direction_deg,"
                      "height_m,kind,block_mm,below_ground_mm\n",
                      0),
            0u);
  EXPECT_NE(csv.find("S001,P0-C0-0,anchor: "
                     "corner,0.000000,0.000000,0.500000,0.000000,0.000000,1.000000,0.000,0.000,0."
                     "100000,block"),
            std::string::npos)
      << csv;
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

TEST(Supports, OnlyOnFreeSides) {
  // The hand grid's anchors are its four corners 0, 2, 6, 8 (connection i * 3 + j). With only side
  // 0 (u member 0: connections 0, 1, 2) on the design boundary, the corners 6 and 8 lie on sides
  // shared with other patches: their lamellas hold them, no block stands under them (the Lilium's
  // apex anchors got 37 m blocks).
  const EggGrid grid = testing::handGrid();
  FabricationPatch patch{0, &grid, std::nullopt};
  patch.freeSides = {true, false, false, false};
  int inner = -1;
  const auto supports = planSupports({patch}, testing::handOptions(), nullptr, &inner);
  ASSERT_EQ(supports.size(), 2u);
  EXPECT_EQ(supports[0].connectionId, "P0-C0-0");
  EXPECT_EQ(supports[1].connectionId, "P0-C0-2");
  EXPECT_EQ(inner, 2);
  // Side 3 (v member 0: connections 0, 3, 6) free, every boundary connection there supported.
  patch.freeSides = {false, false, false, true};
  auto options = testing::handOptions();
  options.supportsAtBoundaryConnections = true;
  const auto column = planSupports({patch}, options, nullptr, &inner);
  ASSERT_EQ(column.size(), 3u);
  EXPECT_EQ(column[0].connectionId, "P0-C0-0");
  EXPECT_EQ(column[1].connectionId, "P0-C1-0");
  EXPECT_EQ(column[2].connectionId, "P0-C2-0");
  EXPECT_EQ(inner, 2);  // anchors 2 and 8
  // No free side: no support at all.
  patch.freeSides = {false, false, false, false};
  EXPECT_TRUE(planSupports({patch}, testing::handOptions()).empty());
}

TEST(Supports, GeneralisedMemberEndsStandOnSupportsOncePerPoint) {
  // A generalised patch (issue 41) holds its members at their ends: those on the design boundary
  // get supports like anchors, with the tangent plane there; an end where a quad's anchor already
  // stands shares its support.
  const EggGrid quad = testing::handGrid();
  FabricationPatch corner{0, &quad, std::nullopt};
  corner.freeSides = {true, false, false, false};
  const EggGrid sparse = testing::handGrid(1.0);
  FabricationPatch generalised{5, &sparse, std::nullopt};
  generalised.freeSides = {false, false, false, false};
  const Eigen::Vector3d tilted = Eigen::Vector3d(0.0, -1.0, 1.0).normalized();
  generalised.endSupports = {{"P5-U0-start", {1.5, 0.3, 0.5}, -tilted},         // normal flipped up
                             {"P5-V1-end", {0.0, 0.0, 0.5}, {0.0, 0.0, 1.0}}};  // quad's corner
  const auto supports = planSupports({corner, generalised}, testing::handOptions());
  ASSERT_EQ(supports.size(), 3u);
  EXPECT_EQ(supports[0].connectionId, "P0-C0-0");
  EXPECT_EQ(supports[1].connectionId, "P0-C0-2");
  EXPECT_EQ(supports[2].connectionId, "P5-U0-start");
  EXPECT_EQ(supports[2].patchId, 5);
  EXPECT_EQ(supports[2].connection, -1);
  EXPECT_EQ(supports[2].reason, "anchor: generalised member end");
  EXPECT_NEAR(supports[2].normal.dot(tilted), 1.0, 1e-12);
  EXPECT_NEAR(supports[2].inclinationDeg, 45.0, 1e-9);
  EXPECT_NEAR(supports[2].directionDeg, -90.0, 1e-9);
}

}  // namespace
}  // namespace egg::fabrication
