#include "core/egg/members.hpp"

#include "core/errors.hpp"
#include "synthetic_maps.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

// Identity cladding function with member lengths C(x) given by `length`.
template <class Length>
CladdingFunction identityCladding(Length length, int n = 201) {
  CladdingFunction f;
  f.connectsCorners = true;
  for (int k = 0; k < n; ++k) {
    const double x = double(k) / (n - 1);
    f.points.emplace_back(x, x);
    f.lengths.push_back(length(x));
  }
  return f;
}

const PlanarQuad kSquare = *planarQuad({1, 1, 1, 1}, M_PI / 2);

TEST(Members, AnglesWithTheSides) {
  auto angles = boundaryAngles(kSquare, Family::U, 0.3, 0.3);  // horizontal member
  EXPECT_NEAR(angles[0], M_PI / 2, 1e-14);
  EXPECT_NEAR(angles[1], M_PI / 2, 1e-14);
  angles = boundaryAngles(kSquare, Family::U, 0.0, 1.0);  // the diagonal c0c2
  EXPECT_NEAR(angles[0], M_PI / 4, 1e-14);
  EXPECT_NEAR(angles[1], M_PI / 4, 1e-14);
  EXPECT_NEAR(lamellaFootprint(0.1, M_PI / 6), 0.2, 1e-15);
}

TEST(Members, ConstantLengthsAreSpacedEvenlyAtTheTargetSpacing) {
  // No features: boundaries plus round(side / target) - 1 evenly spaced members.
  MemberOptions options;
  options.lamellaWidthM = 0.05;
  options.spacingFactor = 5.0;  // target 0.25 m on sides of 1 m -> members at 0, .25, .5, .75, 1
  const auto members = placeMembers(identityCladding([](double) { return 1.0; }), kSquare, 1.0, 1.0, options);
  ASSERT_EQ(members.x1.size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(members.x1[k], 0.25 * k, 1e-12);
    EXPECT_NEAR(members.x2[k], 0.25 * k, 1e-12);
  }
  EXPECT_EQ(members.origin.front(), MemberOrigin::Boundary);
  EXPECT_EQ(members.origin[2], MemberOrigin::Filled);
}

TEST(Members, LongestGeodesicGetsAMember) {
  // C has a single bump at x = 0.3: the locally longest member is placed there first.
  MemberOptions options;
  options.lamellaWidthM = 0.02;
  options.spacingFactor = 10.0;
  const auto members = placeMembers(
      identityCladding([](double x) { return 1.0 + 0.1 * std::exp(-std::pow((x - 0.3) / 0.08, 2)); }), kSquare, 1.0,
      1.0, options);
  int found = 0;
  for (size_t k = 0; k < members.x1.size(); ++k)
    if (members.origin[k] == MemberOrigin::LengthExtremum) {
      ++found;
      EXPECT_NEAR(members.x1[k], 0.3, 0.01);
    }
  EXPECT_EQ(found, 1);
  // Spacing: increasing, no two members closer than the lamella footprint, gaps near the target.
  for (size_t k = 1; k < members.x1.size(); ++k) {
    const double gap = members.x1[k] - members.x1[k - 1];
    EXPECT_GT(gap, options.lamellaWidthM);
    EXPECT_LT(gap, 1.6 * options.spacingFactor * options.lamellaWidthM);
  }
}

TEST(Members, FixedCountIsEvenAndChecksDensity) {
  MemberOptions options;
  options.count = 5;
  const auto members = placeMembers(identityCladding([](double x) { return 1.0 + x * x; }), kSquare, 1.0, 1.0, options);
  ASSERT_EQ(members.x1.size(), 5u);
  EXPECT_NEAR(members.x1[1], 0.25, 1e-12);
  EXPECT_NEAR(members.lengths[2], 1.25, 1e-4);
  options.count = 100;
  options.lamellaWidthM = 0.05;  // 100 lamellas of 5 cm do not fit on a 1 m side
  EXPECT_THROW(placeMembers(identityCladding([](double) { return 1.0; }), kSquare, 1.0, 1.0, options), InvalidInput);
}

TEST(Members, NonBijectiveCladdingIsInfeasible) {
  CladdingFunction f;
  f.points = {{0, 0}, {1, 0}, {1, 1}};
  f.lengths = {1, 1, 1};
  EXPECT_THROW(placeMembers(f, kSquare, 1.0, 1.0), InfeasiblePatch);
  MemberOptions bad;
  bad.count = 1;
  EXPECT_THROW(bad.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg
