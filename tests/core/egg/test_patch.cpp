#include "core/egg/patch.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace egg {
namespace {

const TriMesh& planeMesh() {
  static const TriMesh mesh =
      samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.7);
  return mesh;
}

void expectBoundaryIsTheQuad(const Patch& patch) {
  // Every boundary vertex of the patch mesh lies on one of the four side chains and vice versa.
  std::set<int> chain;
  for (const auto& side : patch.sides) chain.insert(side.begin(), side.end());
  std::set<int> boundary;
  for (auto vh : patch.mesh.vertices())
    if (patch.mesh.is_boundary(vh)) boundary.insert(vh.idx());
  EXPECT_EQ(chain, boundary);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(patch.sides[k].front(), patch.cornerVertices[k]);
    EXPECT_EQ(patch.sides[k].back(), patch.cornerVertices[(k + 1) % 4]);
  }
}

TEST(Patch, PlaneSquareHasExactSidesAnglesAndArea) {
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3.2, -3, 0}, {3, 3.1, 0}, {-3, 3, 0}};
  const Patch patch = makePatch(planeMesh(), corners);
  expectBoundaryIsTheQuad(patch);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(patch.sideLengths[k], (corners[(k + 1) % 4] - corners[k]).norm(), 1e-9) << k;
    EXPECT_NEAR(patch.cornerOffsets[k], 0.0, 1e-12);
  }
  // Shoelace area and planar angles of the quad.
  double area = 0.0;
  for (int k = 0; k < 4; ++k)
    area += 0.5 *
            (corners[k].x() * corners[(k + 1) % 4].y() - corners[(k + 1) % 4].x() * corners[k].y());
  EXPECT_NEAR(patch.area, area, 1e-9);
  double angleSum = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d a = corners[(k + 1) % 4] - corners[k],
                          b = corners[(k + 3) % 4] - corners[k];
    EXPECT_NEAR(patch.innerAngles[k], std::acos(a.normalized().dot(b.normalized())), 1e-9) << k;
    angleSum += patch.innerAngles[k];
  }
  EXPECT_NEAR(angleSum, 2 * M_PI, 1e-9);
}

TEST(Patch, CornersInNeighbouringFacesAreInsertedOneAtATime) {
  // makePatch inserts the four corners in one mesh rebuild when their faces' neighbourhoods are
  // disjoint, one at a time otherwise. A square of 0.3 m on a plane meshed at 2 m puts its corners
  // in the same face (three of them here), so it takes the second path: the known answer must hold.
  // (Inserted together into that face, or snapped on the unsplit surface, they break it.)
  const TriMesh coarse = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 2.0);
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(0.1, 0.2, 0), {0.4, 0.2, 0}, {0.4, 0.5, 0}, {0.1, 0.5, 0}};
  std::set<int> faces;
  for (const auto& c : corners) faces.insert(geodesic::snapToSurface(coarse, c).face);
  std::set<int> neighbourhoods;
  bool disjoint = true;
  for (int f : faces) {
    disjoint = neighbourhoods.insert(f).second && disjoint;
    for (auto fh : coarse.ff_range(TriMesh::FaceHandle(f)))
      disjoint = neighbourhoods.insert(fh.idx()).second && disjoint;
  }
  ASSERT_LT(faces.size(), 4u);  // corners share a face: they cannot go in together
  ASSERT_FALSE(disjoint);
  const Patch patch = makePatch(coarse, corners);
  expectBoundaryIsTheQuad(patch);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(patch.sideLengths[k], 0.3, 1e-12) << k;
    EXPECT_NEAR(patch.innerAngles[k], M_PI / 2, 1e-12) << k;
    EXPECT_NEAR((patch.corners[k] - corners[k]).norm(), 0.0, 1e-12) << k;
  }
  EXPECT_NEAR(patch.area, 0.09, 1e-12);
}

TEST(Patch, ClockwiseCornersGiveTheSameRegion) {
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {-3, 3, 0}, {3, 3, 0}, {3, -3, 0}};
  const Patch patch = makePatch(planeMesh(), corners);
  expectBoundaryIsTheQuad(patch);
  EXPECT_NEAR(patch.area, 36.0, 1e-9);
}

TEST(Patch, SidePointsRunAtConstantSpeed) {
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}};
  const Patch patch = makePatch(planeMesh(), corners);
  for (double s : {0.0, 1.3, 4.7, 6.0}) {
    const Eigen::Vector3d p = position(patch.mesh, sidePoint(patch, 1, s));
    EXPECT_NEAR((p - Eigen::Vector3d(3, -3 + s, 0)).norm(), 0.0, 1e-9) << s;
  }
}

// The exception type and the reason its message gives.
template <class Error>
void expectRejected(const std::array<Eigen::Vector3d, 4>& corners, const std::string& reason) {
  try {
    makePatch(planeMesh(), corners);
    ADD_FAILURE() << "accepted; expected: " << reason;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

TEST(Patch, BadCornersAreRejectedWithAReason) {
  // Off the surface: how far, and which corner.
  expectRejected<InvalidInput>({Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {40, 40, 0}},
                               "corner 3 (40, 40, 0) lies 49.49");
  // Collinear: corner 1 lies on the segment c0 c2, its inner angle is pi.
  expectRejected<InfeasiblePatch>({Eigen::Vector3d(-3, -3, 0), {0, 0, 0}, {3, 3, 0}, {-3, 3, 0}},
                                  "inner angle at corner 1 is 3.14159");
  // Concave (a dart): the inner angle at corner 1 exceeds pi.
  expectRejected<InfeasiblePatch>({Eigen::Vector3d(-3, -3, 0), {0, -1, 0}, {3, -3, 0}, {0, 3, 0}},
                                  "corner 1 is 4.3");
  expectRejected<InfeasiblePatch>({Eigen::Vector3d(-3, -3, 0), {0, -1, 0}, {3, -3, 0}, {0, 3, 0}},
                                  "criterion iv");
  // Bow tie: boundaries 0 and 2 cross.
  expectRejected<InfeasiblePatch>({Eigen::Vector3d(-3, -3, 0), {3, 3, 0}, {3, -3, 0}, {-3, 3, 0}},
                                  "boundaries cross");
  // Repeated corner.
  expectRejected<InvalidInput>({Eigen::Vector3d(-3, -3, 0), {-3, -3, 0}, {3, 3, 0}, {-3, 3, 0}},
                               "corners 0 and 1 coincide");
}

TEST(Patch, WholeSurfaceWithStraightBoundaryIsAccepted) {
  // Corners at the rectangle's corners: the sides run along the straight surface boundary.
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-5, -5, 0), {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  const Patch patch = makePatch(planeMesh(), corners);
  EXPECT_NEAR(patch.area, 100.0, 1e-9);
  expectBoundaryIsTheQuad(patch);
}

}  // namespace
}  // namespace egg
