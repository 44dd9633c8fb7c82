#include "core/mesh/soup_repair.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

// Unit square split into two triangles, written the STL way: every corner its own vertex.
TriangleSoup squareAsStl() {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {3, 4, 5}};
  return soup;
}

TEST(SoupRepair, ExactMergeJoinsBitwiseEqualCorners) {
  TriangleSoup soup = squareAsStl();
  std::vector<int> oldToNew;
  EXPECT_EQ(mergeDuplicateVertices(soup, 0.0, &oldToNew), 2);
  ASSERT_EQ(soup.vertices.size(), 4u);
  EXPECT_EQ(soup.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(oldToNew, (std::vector<int>{0, 1, 2, 0, 2, 3}));
}

TEST(SoupRepair, ToleranceMergeJoinsNearbyButNotDistantVertices) {
  TriangleSoup soup = squareAsStl();
  soup.vertices[3] += Eigen::Vector3d(4e-7, -3e-7, 0.0);  // 5e-7 away from vertex 0
  soup.vertices[4] += Eigen::Vector3d(0.0, 2e-6, 0.0);    // 2e-6 away from vertex 2
  EXPECT_EQ(mergeDuplicateVertices(soup, 1e-6), 1);
  EXPECT_EQ(soup.vertices.size(), 5u);
  EXPECT_EQ(soup.triangles[1][0], 0);
  EXPECT_NE(soup.triangles[1][1], 2);
}

TEST(SoupRepair, NonFiniteVerticesAreNeverMerged) {
  TriangleSoup soup;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  soup.vertices = {{nan, 0, 0}, {nan, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(mergeDuplicateVertices(soup, 0.0), 0);
  EXPECT_EQ(mergeDuplicateVertices(soup, 0.1), 0);
}

TEST(SoupRepair, CollapsedAndDuplicateTrianglesAreDropped) {
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 0, 1}, {2, 1, 0}, {1, 2, 0}};
  std::vector<int> kept;
  const auto [collapsed, duplicates] = dropCollapsedAndDuplicateTriangles(soup, &kept);
  EXPECT_EQ(collapsed, 1);
  EXPECT_EQ(duplicates, 2);  // same vertex set, either orientation
  EXPECT_EQ(kept, (std::vector<int>{0}));
}

TEST(SoupRepair, UnreferencedVerticesAreDroppedKeepingOrder) {
  TriangleSoup soup;
  soup.vertices = {{9, 9, 9}, {0, 0, 0}, {1, 0, 0}, {8, 8, 8}, {0, 1, 0}};
  soup.triangles = {{1, 2, 4}};
  EXPECT_EQ(dropUnreferencedVertices(soup), 2);
  EXPECT_EQ(soup.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(soup.vertices[2], Eigen::Vector3d(0, 1, 0));
}

TEST(SoupRepair, LargestComponentByAreaIsKept) {
  TriangleSoup soup;
  // A small triangle (area 0.005) first, then a unit square (area 1).
  soup.vertices = {{5, 5, 0}, {5.1, 5, 0}, {5, 5.1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {3, 4, 5}, {3, 5, 6}};
  int count = 0;
  EXPECT_EQ(triangleComponents(soup, count), (std::vector<int>{0, 1, 1}));
  EXPECT_EQ(count, 2);
  EXPECT_EQ(keepLargestComponent(soup), 1);
  EXPECT_EQ(soup.triangles.size(), 2u);
  EXPECT_EQ(soup.vertices.size(), 4u);
  EXPECT_EQ(soup.vertices[0], Eigen::Vector3d(0, 0, 0));
}

TEST(SoupRepair, OrientationFollowsTheMajority) {
  // A fan of four triangles around vertex 0 with one flipped.
  TriangleSoup soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 3, 2}, {0, 3, 4}, {0, 4, 1}};  // triangle 1 is flipped
  EXPECT_EQ(orientConsistently(soup), 1);
  EXPECT_EQ(soup.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(soup.triangles[0], (std::array<int, 3>{0, 1, 2}));
}

TEST(SoupRepair, MoebiusBandIsNotOrientable) {
  // A Moebius band from a strip of 6 quads whose ends are glued with a half twist.
  TriangleSoup soup;
  const int n = 6;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const double twist = 0.5 * a;
    const Eigen::Vector3d centre(std::cos(a), std::sin(a), 0.0);
    const Eigen::Vector3d across =
        0.3 * (std::cos(twist) * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0) +
               std::sin(twist) * Eigen::Vector3d::UnitZ());
    soup.vertices.push_back(centre - across);
    soup.vertices.push_back(centre + across);
  }
  for (int i = 0; i < n; ++i) {
    const int a0 = 2 * i, a1 = 2 * i + 1;
    int b0 = 2 * ((i + 1) % n), b1 = b0 + 1;
    if (i == n - 1) std::swap(b0, b1);  // the half twist
    soup.triangles.push_back({a0, b0, b1});
    soup.triangles.push_back({a0, b1, a1});
  }
  const auto before = soup.triangles;
  EXPECT_EQ(orientConsistently(soup), -1);
  EXPECT_EQ(soup.triangles, before);
}

}  // namespace
}  // namespace egg
