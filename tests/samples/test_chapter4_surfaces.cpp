// The Table 4.1 analogues (Chapter 4): single disk-topology meshes of the requested size, with the
// curvature sign of their kind and, for the Moon, a boundary that bends inwards along its bay only.
#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"
#include "core/geodesic/boundary_connections.hpp"
#include "samples/generators/samples.hpp"
#include "tests/samples/mesh_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace egg::samples {
namespace {

using Eigen::Vector3d;
constexpr double kCh4Edge = 0.012;  // the bench's resolution: 3-5k vertices, like Table 4.1

// One connected, manifold disk (one boundary loop, Euler characteristic 1) of the given box.
void expectDiskOfBox(const TriMesh& mesh, const Vector3d& size, double edge = kCh4Edge) {
  const auto report = testing::inspect(mesh);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.complexVertices, 0);
  EXPECT_EQ(report.boundaryLoops, 1);
  EXPECT_EQ(int(mesh.n_vertices()) - int(mesh.n_edges()) + int(mesh.n_faces()), 1);
  EXPECT_GT(report.minAngleDeg, 20.0);
  EXPECT_NEAR(report.meanEdge, edge, 0.1 * edge);
  const Vector3d box = boundingBox(mesh).size();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(box[k], size[k], 0.02 * size[k]) << "axis " << k;
  // Normals up: a height field seen from above.
  int down = 0;
  for (auto f : mesh.faces()) down += testing::faceNormal(mesh, f).z() <= 0 ? 1 : 0;
  EXPECT_EQ(down, 0);
}

// Boundary vertices where the surface angle exceeds pi (the boundary turns towards the surface).
std::vector<int> reflexBoundaryVertices(const TriMesh& mesh) {
  const auto loops = geodesic::boundaryLoops(mesh);
  EXPECT_EQ(loops.size(), 1u);
  std::vector<int> reflex;
  if (loops.empty()) return reflex;
  const auto inward = geodesic::boundaryBendsInward(mesh, loops[0]);
  for (size_t i = 0; i < loops[0].size(); ++i) {
    if (inward[i]) reflex.push_back(loops[0][i]);
  }
  return reflex;
}

// Gaussian curvature of the interior vertices within `radius` (in plan) of `centre`.
std::vector<double> gaussianNear(const TriMesh& mesh, const CurvatureField& field,
                                 const Eigen::Vector2d& centre, double radius) {
  std::vector<double> values;
  for (auto v : mesh.vertices()) {
    const Vector3d p = toEigen(mesh.point(v));
    if (!field.onBoundary[v.idx()] && (p.head<2>() - centre).norm() < radius)
      values.push_back(field.gaussian[v.idx()]);
  }
  return values;
}

TEST(Chapter4Surfaces, MoonIsADomeOverAKidneyWhoseBayBendsInwards) {
  const TriMesh mesh = generateSample("ch4_moon", {}, kCh4Edge);
  expectDiskOfBox(mesh, Vector3d(0.542, 0.6, 0.106));
  EXPECT_GT(mesh.n_vertices(), 2000u);  // about 2300
  const CurvatureField field = computeCurvature(mesh);
  const auto middle = gaussianNear(mesh, field, Eigen::Vector2d(-0.03, 0.0), 0.12);
  ASSERT_GT(middle.size(), 100u);
  for (double k : middle) EXPECT_GT(k, 0.0);
  // The bay is on the +x side around y = 0: every reflex vertex is there, and there are many
  // (about 0.2 m of reflex boundary).
  const auto reflex = reflexBoundaryVertices(mesh);
  EXPECT_GE(reflex.size(), 8u);
  for (int v : reflex) {
    const Vector3d p = toEigen(mesh.point(TriMesh::VertexHandle(v)));
    EXPECT_GT(p.x(), 0.0);
    EXPECT_LT(std::abs(p.y()), 0.15);
  }
  // Bay depth: from the horns' tips (box max x) to the bay's bottom (the boundary on y = 0).
  double bottom = -1.0;
  for (auto v : mesh.vertices()) {
    const Vector3d p = toEigen(mesh.point(v));
    if (std::abs(p.y()) < 1e-6 && p.x() > 0) bottom = std::max(bottom, p.x());
  }
  EXPECT_NEAR(boundingBox(mesh).max.x() - bottom, 0.08, 0.004);
  // Nothing lies in the bay: no vertex beyond the bottom near y = 0.
  for (auto v : mesh.vertices()) {
    const Vector3d p = toEigen(mesh.point(v));
    if (std::abs(p.y()) < 0.01) {
      EXPECT_LE(p.x(), bottom + 1e-9);
    }
  }
}

TEST(Chapter4Surfaces, MoonWithoutBayIsConvex) {
  const TriMesh mesh = generateSample("ch4_moon", {{"bay", 0.0}}, 0.02);
  expectDiskOfBox(mesh, Vector3d(0.542, 0.6, 0.106), 0.02);
  EXPECT_TRUE(reflexBoundaryVertices(mesh).empty());
}

// Coarse edges make the bay's chords cut deepest (sagitta ~h^2 / 8R): the mesh must stay a valid,
// upward disk, every refinement point snapped back onto the reflex curve included.
TEST(Chapter4Surfaces, MoonStaysValidAtCoarseEdges) {
  for (double edge : {0.03, 0.05}) {
    const TriMesh mesh = generateSample("ch4_moon", {{"bay", 0.1}}, edge);
    expectDiskOfBox(mesh, Vector3d(0.542, 0.6, 0.106), edge);
    EXPECT_FALSE(reflexBoundaryVertices(mesh).empty()) << edge;
  }
}

TEST(Chapter4Surfaces, SaddleHasNegativeCurvatureAndAConvexOutline) {
  const TriMesh mesh = generateSample("ch4_saddle", {}, kCh4Edge);
  expectDiskOfBox(mesh, Vector3d(0.6, 0.45, 0.07));
  const CurvatureField field = computeCurvature(mesh);
  const auto middle = gaussianNear(mesh, field, Eigen::Vector2d::Zero(), 0.12);
  ASSERT_GT(middle.size(), 100u);
  for (double k : middle) EXPECT_LT(k, 0.0);
  EXPECT_TRUE(reflexBoundaryVertices(mesh).empty());
}

TEST(Chapter4Surfaces, HillsHaveBumpsWithBothCurvatureSigns) {
  const TriMesh mesh = generateSample("ch4_hills", {}, kCh4Edge);
  expectDiskOfBox(mesh, Vector3d(0.6, 0.475, 0.059));
  const CurvatureField field = computeCurvature(mesh);
  // Bump tops (at fixed fractions of the half-extents 0.3 x 0.2375) are elliptic...
  for (const Eigen::Vector2d& top :
       {Eigen::Vector2d(-0.135, -0.07125), Eigen::Vector2d(0.12, -0.083125),
        Eigen::Vector2d(0.015, 0.106875)}) {
    const auto values = gaussianNear(mesh, field, top, 0.015);
    ASSERT_FALSE(values.empty());
    for (double k : values) EXPECT_GT(k, 1.0) << top.transpose();
  }
  // ... and their flanks hyperbolic, clearly so (|K| of the bumps' order, not noise).
  int hyperbolic = 0;
  for (auto v : mesh.vertices()) {
    if (!field.onBoundary[v.idx()] && field.gaussian[v.idx()] < -1.0) ++hyperbolic;
  }
  EXPECT_GT(hyperbolic, 100);
  EXPECT_TRUE(reflexBoundaryVertices(mesh).empty());
}

TEST(Chapter4Surfaces, StarshipIsAnElongatedConvexDome) {
  const TriMesh mesh = generateSample("ch4_starship", {}, kCh4Edge);
  expectDiskOfBox(mesh, Vector3d(0.6, 0.404, 0.068));
  const CurvatureField field = computeCurvature(mesh);
  const auto middle = gaussianNear(mesh, field, Eigen::Vector2d(-0.06, 0.0), 0.12);
  ASSERT_GT(middle.size(), 100u);
  for (double k : middle) EXPECT_GT(k, 0.0);
  EXPECT_TRUE(reflexBoundaryVertices(mesh).empty());
}

TEST(Chapter4Surfaces, ParametersScaleTheBox) {
  const TriMesh mesh =
      generateSample("ch4_saddle", {{"length", 0.8}, {"width", 0.3}, {"height", 0.1}}, 0.02);
  const Vector3d box = boundingBox(mesh).size();
  EXPECT_NEAR(box.x(), 0.8, 0.016);
  EXPECT_NEAR(box.y(), 0.3, 0.006);
  EXPECT_NEAR(box.z(), 0.1, 0.002);
}

// Expects InvalidInput whose message names the sample and the parameter.
void expectCh4Invalid(const std::string& name, const Params& params, const std::string& key) {
  try {
    generateSample(name, params, 0.02);
    FAIL() << "expected InvalidInput for " << name << " " << key;
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(name), std::string::npos) << message;
    EXPECT_NE(message.find(key), std::string::npos) << message;
  }
}

TEST(Chapter4Surfaces, RejectsUnknownAndOutOfRangeParameters) {
  expectCh4Invalid("ch4_moon", {{"bey", 0.1}}, "bey");
  expectCh4Invalid("ch4_moon", {{"bay", 0.2}}, "bay");  // above 0.2 x 0.542
  expectCh4Invalid("ch4_moon", {{"bay", -0.01}}, "bay");
  expectCh4Invalid("ch4_saddle", {{"width", 0.0}}, "width");
  expectCh4Invalid("ch4_hills", {{"height", -0.05}}, "height");
  expectCh4Invalid("ch4_starship", {{"length", std::nan("")}}, "length");
  expectCh4Invalid("ch4_saddle", {{"bay", 0.1}}, "bay");
}

}  // namespace
}  // namespace egg::samples
