#include "core/egg/illinois_bracket.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

// Runs the bracket on f from [a, b] until |f| <= tolerance; returns the step count.
template <class F>
int solve(F f, IllinoisBracket& r, double tolerance, int maxSteps) {
  for (int step = 1; step <= maxSteps; ++step) {
    const double x = r.falsePosition();
    const double g = f(x);
    if (std::abs(g) <= tolerance) {
      r.a = r.b = x;
      return step;
    }
    r.replace(x, g, (g > 0.0) == (r.gb > 0.0));
  }
  return -1;
}

TEST(IllinoisBracket, FalsePositionOfALineIsItsRoot) {
  const IllinoisBracket r{1.0, 3.0, -2.0, 2.0};
  EXPECT_DOUBLE_EQ(r.falsePosition(), 2.0);
}

TEST(IllinoisBracket, ConvexFunctionConvergesFastToTheCubeRootOfTwo) {
  // x^3 - 2 is convex on [0, 2]: plain regula falsi keeps the end b = 2 for ever and needs ~40
  // steps for 1e-12; the Illinois halving needs about ten.
  const auto f = [](double x) { return x * x * x - 2.0; };
  IllinoisBracket r{0.0, 2.0, f(0.0), f(2.0)};
  const int steps = solve(f, r, 1e-13, 40);
  ASSERT_GT(steps, 0);
  EXPECT_LE(steps, 15);
  EXPECT_NEAR(r.a, std::cbrt(2.0), 1e-13);
}

TEST(IllinoisBracket, KeepsTheRootBracketedAndHalvesAKeptEnd) {
  IllinoisBracket r{0.0, 1.0, -1.0, 3.0};
  r.replace(0.25, -0.5, false);  // a moves; b kept once
  EXPECT_EQ(r.kept, 1);
  EXPECT_DOUBLE_EQ(r.gb, 3.0);
  r.replace(0.5, -0.1, false);  // a moves again: b kept twice, its value halved
  EXPECT_DOUBLE_EQ(r.gb, 1.5);
  EXPECT_DOUBLE_EQ(r.a, 0.5);
  r.replace(0.75, 0.2, true);  // b moves; the sign change stays inside [a, b]
  EXPECT_EQ(r.kept, -1);
  EXPECT_LT(r.ga * r.gb, 0.0);
  EXPECT_LT(r.a, r.b);
}

}  // namespace
}  // namespace egg
