#include "samples/generators/domain_triangulation.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::samples::detail {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// A 4 x 4 square with a 1 x 1 square hole and one required point.
const std::vector<std::vector<Vec2>> kSquareWithHole{{{0, 0}, {4, 0}, {4, 4}, {0, 4}},
                                                     {{1, 1}, {1, 2}, {2, 2}, {2, 1}}};

TEST(DomainTriangulation, CoversTheDomainWithoutTheHole) {
  const auto lift = [](const Vec2& u) { return Vec3(u.x(), u.y(), 0.0); };
  const DomainTriangulation result = triangulateDomain(kSquareWithHole, {{3.0, 3.3}}, lift, 0.5);
  double area = 0.0;
  double minSine2 = 1.0;
  for (const auto& t : result.triangles) {
    const Vec2 a = result.points[t[0]], b = result.points[t[1]], c = result.points[t[2]];
    const double doubled = cross(b - a, c - a);
    EXPECT_GT(doubled, 0.0);  // counter-clockwise
    area += 0.5 * doubled;
    const Vec2 centroid = (a + b + c) / 3.0;
    EXPECT_FALSE(centroid.x() > 1 && centroid.x() < 2 && centroid.y() > 1 && centroid.y() < 2);
    double lengths[3] = {(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()};
    std::sort(lengths, lengths + 3);
    EXPECT_LE(lengths[2], 0.25 * (1 + 1e-12));  // size bound 0.5
    minSine2 = std::min(minSine2, doubled * doubled / (lengths[1] * lengths[2]));
  }
  EXPECT_NEAR(area, 15.0, 1e-9);
  EXPECT_GE(minSine2, 0.125 - 1e-9);  // CGAL's guarantee: smallest angle >= 20.7 degrees
  // Every input point survives with its index; the required point is index 8.
  int inputs = 0;
  for (size_t i = 0; i < result.points.size(); ++i) {
    const int input = result.inputIndex[i];
    if (input < 0) continue;
    ++inputs;
    const Vec2 expected = input == 8  ? Vec2(3.0, 3.3)
                          : input < 4 ? kSquareWithHole[0][input]
                                      : kSquareWithHole[1][input - 4];
    EXPECT_EQ(result.points[i], expected);
  }
  EXPECT_EQ(inputs, 9);
}

TEST(DomainTriangulation, SizeIsMeasuredOnTheLiftedSurface) {
  // A plane of slope 3 in x: a footprint edge along x is sqrt(10) times longer in 3D.
  const auto lift = [](const Vec2& u) { return Vec3(u.x(), u.y(), 3.0 * u.x()); };
  const DomainTriangulation result = triangulateDomain({kSquareWithHole[0]}, {}, lift, 0.8);
  for (const auto& t : result.triangles) {
    for (int k = 0; k < 3; ++k) {
      const double length =
          (lift(result.points[t[k]]) - lift(result.points[t[(k + 1) % 3]])).norm();
      // Input edges along x are 4 * sqrt(10) long in 3D: refinement must have split them.
      EXPECT_LE(length, 0.8 * (1 + 1e-9));
    }
  }
}

TEST(DomainTriangulation, GivesUpOnAHopelessDomain) {
  // 1000 x 0.001: angle-bounded refinement needs ~10^6 points; a budget of 5000 stops it.
  const auto lift = [](const Vec2& u) { return Vec3(u.x(), u.y(), 0.0); };
  const std::vector<Vec2> sliver{{0, 0}, {1000, 0}, {1000, 0.001}, {0, 0.001}};
  EXPECT_THROW(triangulateDomain({sliver}, {}, lift, 1.0, 0.125, 5000), InvalidInput);
}

}  // namespace
}  // namespace egg::samples::detail
