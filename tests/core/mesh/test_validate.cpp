#include "core/mesh/validate.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace egg {
namespace {

// (n+1) x (n+1) vertices on the unit square, two triangles per cell, consistently oriented.
TriangleSoup grid(int n) {
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) soup.vertices.push_back({double(i) / n, double(j) / n, 0.0});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return soup;
}

std::string messageOf(const TriangleSoup& soup, const MeshCheckOptions& options = {}) {
  MeshRepairDiagnostics diagnostics;
  try {
    prepareMesh(soup, options, diagnostics);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  ADD_FAILURE() << "prepareMesh accepted the mesh";
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Validate, CleanGridHasNoIssues) {
  const MeshCheckResult result = checkMesh(grid(4));
  EXPECT_TRUE(result.issues.empty()) << result.summary();
  EXPECT_TRUE(result.acceptable());
  EXPECT_EQ(result.components, 1);
  EXPECT_EQ(result.boundaryEdges, 16);
  EXPECT_NEAR(result.minAngleRad, M_PI / 4.0, 1e-12);
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(grid(4), {}, diagnostics);
  EXPECT_EQ(mesh.n_vertices(), 25u);
  EXPECT_EQ(mesh.n_faces(), 32u);
  EXPECT_TRUE(diagnostics.warnings.empty());
}

TEST(Validate, NanCoordinateNamesTheVertex) {
  TriangleSoup soup = grid(3);
  soup.vertices[6].y() = std::numeric_limits<double>::quiet_NaN();
  const MeshCheckResult result = checkMesh(soup);
  ASSERT_TRUE(result.has(MeshIssueKind::NonFiniteVertex));
  EXPECT_FALSE(result.acceptable());
  const std::string message = messageOf(soup);
  EXPECT_TRUE(contains(message, "vertex 6 at")) << message;
  EXPECT_TRUE(contains(message, "NaN")) << message;
  // Issue 17: a NaN with its sign bit set was printed as "-nan"; an infinity is printed as inf.
  soup.vertices[6].y() = -std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(contains(messageOf(soup), "-nan")) << messageOf(soup);
  soup.vertices[6].y() = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(messageOf(soup), ", inf, ")) << messageOf(soup);
}

TEST(Validate, InfiniteUnusedVertexIsSimplyDropped) {
  TriangleSoup soup = grid(2);
  soup.vertices.push_back({std::numeric_limits<double>::infinity(), 0, 0});
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(soup, {}, diagnostics);
  EXPECT_EQ(mesh.n_vertices(), 9u);
  EXPECT_EQ(diagnostics.droppedUnreferencedVertices, 1);
}

TEST(Validate, ZeroAreaTriangleIsNamed) {
  TriangleSoup soup = grid(2);
  // A triangle whose third corner lies on the segment between the other two.
  const int a = static_cast<int>(soup.vertices.size());
  soup.vertices.push_back({2, 0, 0});
  soup.vertices.push_back({3, 0, 0});
  soup.vertices.push_back({2.5, 0, 0});
  soup.triangles.push_back({a, a + 1, a + 2});
  const MeshCheckResult result = checkMesh(soup);
  const MeshIssue* issue = result.find(MeshIssueKind::DegenerateFaces);
  ASSERT_NE(issue, nullptr) << result.summary();
  EXPECT_EQ(issue->count, 1);
  EXPECT_TRUE(contains(issue->message, "triangle 8 (vertices 9, 10, 11)")) << issue->message;
  EXPECT_TRUE(contains(issue->message, "area below 1e-12 x mean edge length squared"))
      << issue->message;
}

TEST(Validate, SliversReportCountAndWorst) {
  TriangleSoup soup = grid(2);
  // Pull the centre vertex down to just above the bottom edge: triangle 0 becomes a needle
  // (angle atan(2e-5) at vertex 0) and triangle 3 a cap (angle atan2(5e-6, 0.499995) at vertex 5,
  // the worst); the rest stays a valid mesh.
  soup.vertices[4] = {0.5, 1e-5, 0.0};
  const MeshCheckResult result = checkMesh(soup);
  const MeshIssue* issue = result.find(MeshIssueKind::SliverFaces);
  ASSERT_NE(issue, nullptr) << result.summary();
  EXPECT_EQ(issue->count, 2);
  EXPECT_TRUE(contains(issue->message, "the worst is triangle 3 (vertices 1, 5, 4)"))
      << issue->message;
  EXPECT_EQ(result.worstFace, 3);
  EXPECT_NEAR(result.minAngleRad, std::atan2(5e-6, 0.499995), 1e-12);
  EXPECT_FALSE(result.acceptable());
  // Tolerated (reported, not refused) when the option says so.
  MeshCheckOptions options;
  options.rejectSlivers = false;
  const MeshCheckResult tolerated = checkMesh(soup, options);
  EXPECT_TRUE(tolerated.has(MeshIssueKind::SliverFaces));
  EXPECT_TRUE(tolerated.acceptable()) << tolerated.summary();
  MeshRepairDiagnostics diagnostics;
  EXPECT_EQ(prepareMesh(soup, options, diagnostics).n_faces(), 8u);
  EXPECT_EQ(diagnostics.warnings.size(), 1u);
}

TEST(Validate, NonManifoldEdgeNamesEdgeAndTriangles) {
  TriangleSoup soup = grid(1);  // vertices 0..3, triangles (0,1,3) (0,3,2)
  soup.vertices.push_back({0.5, 0.5, 1.0});
  soup.triangles.push_back({0, 4, 3});  // a fin on the diagonal 0-3
  const std::string message = messageOf(soup);
  EXPECT_TRUE(contains(message, "edge (0, 3) is shared by 3 triangles (0, 1, 2)")) << message;
}

TEST(Validate, BowTieVertexIsNonManifold) {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 3, 4}};  // two triangles touching only at vertex 0
  const MeshCheckResult result = checkMesh(soup);
  const MeshIssue* issue = result.find(MeshIssueKind::NonManifoldVertices);
  ASSERT_NE(issue, nullptr) << result.summary();
  EXPECT_TRUE(contains(issue->message, "vertex 0 at (0, 0, 0) joins 2 separate fans"))
      << issue->message;
  EXPECT_EQ(result.components, 1);  // connected through the vertex
}

TEST(Validate, IsolatedVerticesAreAnErrorWhenNotDropped) {
  TriangleSoup soup = grid(1);
  soup.vertices.push_back({7, 7, 7});
  MeshCheckOptions options;
  options.dropUnreferencedVertices = false;
  const std::string message = messageOf(soup, options);
  EXPECT_TRUE(contains(message, "vertex 4 at (7, 7, 7)")) << message;
}

TEST(Validate, SeveralComponentsRejectedOrLargestKept) {
  TriangleSoup soup = grid(3);
  const int a = static_cast<int>(soup.vertices.size());
  soup.vertices.push_back({5, 5, 0});
  soup.vertices.push_back({5.1, 5, 0});
  soup.vertices.push_back({5, 5.1, 0});
  soup.triangles.push_back({a, a + 1, a + 2});
  const std::string message = messageOf(soup);
  EXPECT_TRUE(contains(message, "2 connected components")) << message;
  EXPECT_TRUE(contains(message, "component 1: 1 triangles from triangle 18")) << message;
  // Issue 17: the advice named a non-existent option ("keep the largest by option").
  EXPECT_FALSE(contains(message, "by option")) << message;
  EXPECT_TRUE(contains(message, "surface.keep_largest_component")) << message;

  MeshCheckOptions options;
  options.components = ComponentPolicy::KeepLargest;
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(soup, options, diagnostics);
  EXPECT_EQ(mesh.n_faces(), 18u);
  EXPECT_EQ(mesh.n_vertices(), 16u);
  EXPECT_EQ(diagnostics.removedComponents, 1);
  ASSERT_EQ(diagnostics.warnings.size(), 1u);
  EXPECT_TRUE(contains(diagnostics.warnings[0], "kept the largest")) << diagnostics.warnings[0];
}

TEST(Validate, InconsistentOrientationIsNamedOrFixed) {
  TriangleSoup soup = grid(2);
  std::swap(soup.triangles[3][1], soup.triangles[3][2]);
  const std::string message = messageOf(soup);
  EXPECT_TRUE(contains(message, "inconsistent orientation at 3 edge(s)")) << message;
  EXPECT_TRUE(contains(message, "triangles 2 and 3")) << message;
  EXPECT_FALSE(contains(message, "by option")) << message;  // issue 17: there is no such option

  MeshCheckOptions options;
  options.fixOrientation = true;
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(soup, options, diagnostics);
  EXPECT_EQ(diagnostics.flippedTriangles, 1);
  EXPECT_EQ(mesh.n_faces(), 8u);
  // All face normals now point the same way (+z, like the majority).
  for (auto fh : mesh.faces()) EXPECT_GT(mesh.calc_face_normal(fh)[2], 0.99);
}

TEST(Validate, StlStyleSoupIsMergedIntoOneSurface) {
  // Every triangle with its own three corners, as an STL file stores them.
  const TriangleSoup shared = grid(3);
  TriangleSoup stl;
  for (const auto& tri : shared.triangles) {
    const int base = static_cast<int>(stl.vertices.size());
    for (int v : tri) stl.vertices.push_back(shared.vertices[v] + Eigen::Vector3d::Constant(1e-9));
    stl.triangles.push_back({base, base + 1, base + 2});
  }
  stl.triangles.push_back(stl.triangles[4]);  // and one repeated triangle
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(stl, {}, diagnostics);
  EXPECT_EQ(mesh.n_vertices(), 16u);
  EXPECT_EQ(mesh.n_faces(), 18u);
  EXPECT_EQ(diagnostics.mergedVertices, 54 - 16);
  EXPECT_EQ(diagnostics.droppedDuplicateTriangles, 1);

  MeshCheckOptions noMerge;
  noMerge.mergeDuplicateVertices = false;
  const std::string message = messageOf(stl, noMerge);
  EXPECT_TRUE(contains(message, "38 duplicate vertices")) << message;
}

// Exact copies of a vertex are how OBJ and STL store shared corners: merged without a warning.
// Copies that differ by less than the tolerance are a real defect of the model: merged and
// reported.
TEST(Validate, ExactCopiesMergeSilentlyNearCopiesAreReported) {
  const TriangleSoup shared = grid(3);
  auto split = [&](double offset) {
    TriangleSoup soup;
    for (const auto& tri : shared.triangles) {
      const int base = static_cast<int>(soup.vertices.size());
      for (int v : tri) soup.vertices.push_back(shared.vertices[v]);
      soup.triangles.push_back({base, base + 1, base + 2});
    }
    soup.vertices[0] += Eigen::Vector3d(offset, 0.0, 0.0);  // one corner a little off
    return soup;
  };
  MeshRepairDiagnostics exact;
  const TriMesh a = prepareMesh(split(0.0), {}, exact);
  EXPECT_EQ(a.n_vertices(), 16u);
  EXPECT_EQ(exact.mergedVertices, 54 - 16);
  EXPECT_TRUE(exact.warnings.empty()) << exact.warnings.front();
  MeshRepairDiagnostics near;
  const TriMesh b = prepareMesh(split(1e-9), {}, near);
  EXPECT_EQ(b.n_vertices(), 16u);
  EXPECT_EQ(near.mergedVertices, 54 - 16);
  ASSERT_EQ(near.warnings.size(), 1u);
  EXPECT_TRUE(contains(near.warnings[0], "merged 1 duplicate vertices")) << near.warnings[0];
}

TEST(Validate, IndexOutOfRangeAndEmptyAreRejected) {
  TriangleSoup soup = grid(1);
  soup.triangles.push_back({0, 2, 9});
  EXPECT_TRUE(contains(messageOf(soup), "triangle 2 (0, 2, 9)"));
  EXPECT_TRUE(contains(messageOf(TriangleSoup{}), "empty"));
}

TEST(Validate, BadOptionsNameTheField) {
  MeshCheckOptions options;
  options.sliverMinAngleRad = -1.0;
  try {
    checkMesh(grid(1), options);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_TRUE(contains(e.what(), "sliver_min_angle_rad"));
  }
}

}  // namespace
}  // namespace egg
