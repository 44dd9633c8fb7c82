#include "patching/footprint.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::patching {
namespace {

TEST(Footprint, PolygonBasics) {
  const Polygon square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_DOUBLE_EQ(signedArea(square), 4.0);
  EXPECT_DOUBLE_EQ(signedArea(Polygon(square.rbegin(), square.rend())), -4.0);
  EXPECT_TRUE(insidePolygon(square, {1, 1}));
  EXPECT_FALSE(insidePolygon(square, {3, 1}));
  EXPECT_DOUBLE_EQ(distanceToPolygon(square, {1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(distanceToPolygon(square, {5, 2}), 3.0);
  // An L: every vertex but the reflex one (1, 1) is on the hull.
  const Polygon l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_EQ(convexHullMarks(l), (std::vector<char>{1, 1, 1, 0, 1, 1}));
}

TEST(Footprint, ARoofKeepsItsAxesAndTheHoleIsFound) {
  const TriMesh court = samples::generateSample("great_court", {}, 4.0);
  const Plan plan = planOf(court);
  EXPECT_EQ(plan.normal, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(plan.e1, Eigen::Vector3d::UnitX());
  const Footprint foot = footprintOf(court, plan);
  ASSERT_EQ(foot.holes.size(), 1u);
  EXPECT_GT(signedArea(foot.outer), 0.0);  // counter-clockwise
  EXPECT_EQ(foot.outer.size(), foot.outer3d.size());
  // The Reading Room (radius 22.245 m) is off the footprint; a point between it and the rectangle
  // is on it.
  EXPECT_FALSE(foot.contains(plan(Eigen::Vector3d(0, 0, 0))));
  EXPECT_TRUE(foot.contains(plan(Eigen::Vector3d(30, 30, 0))));
  EXPECT_FALSE(
      foot.containsSegment(plan(Eigen::Vector3d(-30, 0, 0)), plan(Eigen::Vector3d(30, 0, 0))));
}

TEST(Footprint, ArcsRunByArcLength) {
  Footprint foot;
  foot.outer = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
  foot.outer3d = {{0, 0, 0}, {4, 0, 1}, {4, 2, 1}, {0, 2, 0}};
  const Arc arc = arcOf(foot, 0, 2);  // (0,0) -> (4,0) -> (4,2): 6 m
  EXPECT_TRUE(arc.at(0.5).isApprox(Vec2(3, 0)));
  EXPECT_TRUE(arc.at(5.0 / 6.0).isApprox(Vec2(4, 1)));
  EXPECT_TRUE(arc.at3d(0.5).isApprox(Eigen::Vector3d(3, 0, 0.75)));
  const Arc wrapping = arcOf(foot, 3, 0);  // the closing side
  EXPECT_TRUE(wrapping.at(0.25).isApprox(Vec2(0, 1.5)));
}

TEST(Footprint, TheLifterFindsTheSurfaceOverAPlanPoint) {
  // Two unit squares over each other (z = 0 and z = 1), and a tilted one beside them.
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},   {0, 0, 1},   {1, 0, 1},
                   {1, 1, 1}, {0, 1, 1}, {2, 0, 0}, {3, 0, 0.5}, {3, 1, 0.7}, {2, 1, 0.2}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {8, 9, 10}, {8, 10, 11}};
  const TriMesh mesh = meshFromSoup(soup);
  const PlanLifter lifter(mesh, Plan{});
  int sheets = 0;
  EXPECT_TRUE(lifter.lift({0.3, 0.4}, std::nullopt, &sheets)
                  .isApprox(Eigen::Vector3d(0.3, 0.4, 1.0)));  // the upper one
  EXPECT_EQ(sheets, 2);
  EXPECT_TRUE(lifter.lift({0.3, 0.4}, Eigen::Vector3d(0.3, 0.4, 0.1))
                  .isApprox(Eigen::Vector3d(0.3, 0.4, 0.0)));  // the one near
  // On the tilted square z = 0.5 (x - 2) + 0.2 y, exactly (it is linear).
  const Eigen::Vector3d tilted = lifter.lift({2.6, 0.3}, std::nullopt, &sheets);
  EXPECT_NEAR(tilted.z(), 0.36, 1e-12);
  EXPECT_EQ(sheets, 1);
  // Off every face: the nearest point of the nearest face.
  const Eigen::Vector3d off = lifter.lift({3.5, 0.5}, std::nullopt, &sheets);
  EXPECT_EQ(sheets, 0);
  EXPECT_NEAR(off.x(), 3.0, 1e-12);
}

}  // namespace
}  // namespace egg::patching
