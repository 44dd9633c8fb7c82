// The flat grid a deployment starts from (assembly/flat_grid.hpp): placed where the deployed grid
// is when that is the planar grid moved rigidly, its layer 1 side towards the deployed normals.
#include "assembly/flat_grid.hpp"

#include "assembly/grid_to_rods.hpp"
#include "core/errors.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace egg::assembly {
namespace {

// Two u members along x and two v members along y in the plane, moved rigidly into space by
// (rotation, translation); the surface normals are the moved +z, or its opposite when `flipped`.
EggGrid movedGrid(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
                  bool flipped) {
  const auto move = [&](const Eigen::Vector2d& p) {
    return (rotation * Eigen::Vector3d(p.x(), p.y(), 0.0) + translation).eval();
  };
  // Flipped: the planar layout seen from below is its mirror image; the deployed grid is the
  // mirror moved, so that its members turn the same way seen from the side its normals point to.
  const double mirror = flipped ? -1.0 : 1.0;
  const Eigen::Vector3d normal = rotation * Eigen::Vector3d(0, 0, mirror);
  EggGrid grid;
  for (int k = 0; k < 2; ++k) {
    GridMember u;
    u.family = Family::U;
    u.index = k;
    u.planarStart = {0.0, 1.5 * k};
    u.planarEnd = {3.0, 1.5 * k};
    u.planarLength = u.spatialLength = 3.0;
    u.spatial = {move({0.0, mirror * 1.5 * k}), move({3.0, mirror * 1.5 * k})};
    u.normals = {normal, normal};
    grid.u.push_back(u);
    GridMember v;
    v.family = Family::V;
    v.index = k;
    v.planarStart = {1.0 + k, -0.5};
    v.planarEnd = {1.0 + k, 2.0};
    v.planarLength = v.spatialLength = 2.5;
    v.spatial = {move({1.0 + k, mirror * -0.5}), move({1.0 + k, mirror * 2.0})};
    v.normals = {normal, normal};
    grid.v.push_back(v);
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      GridConnection c;
      c.memberU = i;
      c.memberV = j;
      c.planar = {1.0 + j, 1.5 * i};
      c.spatial = move({1.0 + j, mirror * 1.5 * i});
      c.normal = normal;
      c.sBarU = c.sU = 1.0 + j;
      c.sBarV = c.sV = 0.5 + 1.5 * i;
      c.onBoundary = true;
      grid.connections.push_back(c);
    }
  grid.anchors = {{0, "corner"}, {3, "corner"}};
  return grid;
}

void expectFlatIsTheDeployedGrid(bool flipped) {
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const EggGrid grid = movedGrid(rotation, {5, -2, 8}, flipped);
  const rods::RodNetwork deployed = rodNetworkFromGrid(grid, {});
  const FlatGrid flat = flatGrid(grid, deployed);
  EXPECT_LT(flat.placementRmsM, 1e-12);
  ASSERT_EQ(flat.flat.positions.size(), 2u);
  for (size_t a = 0; a < 2; ++a) {
    EXPECT_LT((flat.flat.positions[a] - flat.deployed.positions[a]).norm(), 1e-12);
    EXPECT_LT((flat.flat.normals[a] - flat.deployed.normals[a]).norm(), 1e-12);
  }
  // Every rod straight at its planar length, the bolts where the planar members cross.
  for (size_t r = 0; r < flat.network.rods.size(); ++r) {
    const rods::Rod& rod = flat.network.rods[r];
    ASSERT_EQ(rod.guess.size(), 2u);
    EXPECT_NEAR((rod.guess[1] - rod.guess[0]).norm(), rod.lengthM, 1e-12);
  }
  for (const rods::Connection& c : flat.network.connections) {
    EXPECT_EQ(c.startAM, c.sAM);
    EXPECT_EQ(c.startBM, c.sBM);
  }
}

TEST(FlatGrid, ARigidlyMovedPlanarGridIsPlacedBackOntoItself) {
  expectFlatIsTheDeployedGrid(false);
}

TEST(FlatGrid, NormalsOnTheOtherSideTurnTheFlatGridOver) { expectFlatIsTheDeployedGrid(true); }

// A bolt drilled 7 mm off the planar crossing along its u lamella: the straight lamellas miss each
// other there by 7 mm (the flat grid cannot be bolted without strain); elsewhere they meet.
TEST(FlatGrid, ABoltDrilledOffTheCrossingIsMeasuredAsTheFlatMisfit) {
  EggGrid grid = movedGrid(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), false);
  EXPECT_LT(flatGrid(grid, rodNetworkFromGrid(grid, {})).boltMisfitMaxM, 1e-12);
  grid.connections[2].sBarU += 0.007;
  const FlatGrid flat = flatGrid(grid, rodNetworkFromGrid(grid, {}));
  EXPECT_NEAR(flat.boltMisfitMaxM, 0.007, 1e-12);
  EXPECT_EQ(flat.boltMisfitMaxConnection, 2);
}

TEST(FlatGrid, ANetworkOfAnotherGridIsRefused) {
  const EggGrid grid = movedGrid(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), false);
  rods::RodNetwork deployed = rodNetworkFromGrid(grid, {});
  deployed.rods.pop_back();
  EXPECT_THROW(flatGrid(grid, deployed), InvalidInput);
}

}  // namespace
}  // namespace egg::assembly
