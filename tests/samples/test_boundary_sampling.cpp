#include "samples/generators/boundary_sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace egg::samples::detail {
namespace {

constexpr double kPi = std::numbers::pi;

SurfaceSpec flat(std::vector<BoundaryLoop> boundary) {
  SurfaceSpec spec;
  spec.position = [](const Vec2& u) { return Vec3(u.x(), u.y(), 0.0); };
  spec.boundary = std::move(boundary);
  return spec;
}

BoundaryLoop circle(double radius) {
  return {{[radius](double s) {
    return Vec2(radius * std::cos(2 * kPi * s), radius * std::sin(2 * kPi * s));
  }}};
}

TEST(BoundarySampling, CircleGetsEvenChordsOnTheCurve) {
  const SurfaceSpec spec = flat({circle(5.0)});
  const auto loops = sampleBoundary(spec, 0.5);
  ASSERT_EQ(loops.size(), 1u);
  const auto& points = loops[0].points;
  ASSERT_EQ(points.size(), 63u);  // round(10 pi / 0.5)
  const double chord = 2 * 5.0 * std::sin(kPi / 63);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(points[i].domain.norm(), 5.0, 1e-12);
    EXPECT_NEAR((points[(i + 1) % points.size()].domain - points[i].domain).norm(), chord,
                1e-3 * chord);
  }
}

TEST(BoundarySampling, CurveEndsAreSamplesAndSpacingIsMeasuredIn3d) {
  // The map stretches y by 4: the vertical sides of a unit square are 4 m long in 3D.
  SurfaceSpec spec;
  spec.position = [](const Vec2& u) { return Vec3(u.x(), 4 * u.y(), 0.0); };
  const Vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  BoundaryLoop square;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = corners[i], b = corners[(i + 1) % 4];
    square.push_back({[a, b](double s) { return Vec2(a + s * (b - a)); }});
  }
  spec.boundary = {square};
  const auto loops = sampleBoundary(spec, 0.5);
  ASSERT_EQ(loops[0].points.size(), 2u + 8u + 2u + 8u);
  int corner = 0;
  for (const auto& sample : loops[0].points) {
    if (sample.s == 0.0) {
      EXPECT_EQ(sample.domain, corners[corner++]);
    }
  }
  EXPECT_EQ(corner, 4);
  EXPECT_NEAR(curveLength3d(spec, square[1], 64), 4.0, 1e-12);
}

TEST(BoundarySampling, TinyLoopStillHasThreePoints) {
  const auto loops = sampleBoundary(flat({circle(0.01)}), 1.0);
  EXPECT_EQ(loops[0].points.size(), 3u);
}

TEST(BoundarySampling, SnapMovesChordPointsOntoTheCurve) {
  const SurfaceSpec spec = flat({circle(5.0)});
  const auto loops = sampleBoundary(spec, 0.5);
  const Vec2 a = loops[0].points[10].domain, b = loops[0].points[11].domain;
  bool found = false;
  const Vec2 snapped = snapToBoundary(spec, loops, 0.5 * (a + b), 1e-9, found);
  EXPECT_TRUE(found);
  EXPECT_NEAR(snapped.norm(), 5.0, 1e-12);
  // The last chord closes the loop back to parameter 1 = 0.
  const Vec2 last = loops[0].points.back().domain, first = loops[0].points.front().domain;
  const Vec2 closing = snapToBoundary(spec, loops, 0.5 * (last + first), 1e-9, found);
  EXPECT_TRUE(found);
  EXPECT_NEAR(closing.norm(), 5.0, 1e-12);
  EXPECT_LT(closing.y(), 0.0);
  const Vec2 inside = snapToBoundary(spec, loops, Vec2(1.0, 1.0), 1e-9, found);
  EXPECT_FALSE(found);
  EXPECT_EQ(inside, Vec2(1.0, 1.0));
}

}  // namespace
}  // namespace egg::samples::detail
