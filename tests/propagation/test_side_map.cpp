// Side maps: the piecewise-linear cladding function read forwards, backwards (F^-1, Fig. 3.8's
// back-propagation) and with both parameters reversed.
#include "propagation/side_map.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg::propagation {
namespace {

PiecewiseLinearMap kinked() { return PiecewiseLinearMap({{0, 0}, {0.5, 0.25}, {1, 1}}); }

TEST(SideMap, IdentityByDefault) {
  const PiecewiseLinearMap identity;
  for (double x : {0.0, 0.3, 1.0}) {
    EXPECT_DOUBLE_EQ(identity.value(x), x);
    EXPECT_DOUBLE_EQ(identity.inverse(x), x);
    EXPECT_DOUBLE_EQ(identity.slope(x), 1.0);
  }
}

TEST(SideMap, ValueSlopeInverseOfAKinkedMap) {
  const auto f = kinked();
  EXPECT_DOUBLE_EQ(f.value(0.25), 0.125);
  EXPECT_DOUBLE_EQ(f.value(0.75), 0.625);
  EXPECT_DOUBLE_EQ(f.slope(0.25), 0.5);
  EXPECT_DOUBLE_EQ(f.slope(0.5), 1.5);  // right-continuous at the kink
  EXPECT_DOUBLE_EQ(f.slope(1.0), 1.5);
  for (double x : {0.0, 0.1, 0.5, 0.9, 1.0}) EXPECT_NEAR(f.inverse(f.value(x)), x, 1e-15);
  EXPECT_DOUBLE_EQ(f.value(-1.0), 0.0);  // clamped
  EXPECT_DOUBLE_EQ(f.value(2.0), 1.0);
}

TEST(SideMap, InvertedAndMirrored) {
  const auto f = kinked();
  const auto inv = f.inverted();
  const auto mir = f.mirrored();
  for (double x : {0.05, 0.3, 0.6, 0.95}) {
    EXPECT_NEAR(inv.value(x), f.inverse(x), 1e-15);
    EXPECT_NEAR(inv.slope(x), 1.0 / f.slope(f.inverse(x)), 1e-12);
    EXPECT_NEAR(mir.value(x), 1.0 - f.value(1.0 - x), 1e-15);
  }
}

TEST(SideMap, RejectsKnotsThatDoNotIncrease) {
  EXPECT_THROW(PiecewiseLinearMap({{0, 0}, {0.5, 0.5}, {0.5, 0.7}, {1, 1}}), InvalidInput);
  EXPECT_THROW(PiecewiseLinearMap({{0, 0}, {1, 0.9}}), InvalidInput);
  EXPECT_THROW(PiecewiseLinearMap({{0, 0}}), InvalidInput);
}

}  // namespace
}  // namespace egg::propagation
