#include "core/egg/members.hpp"

#include "core/errors.hpp"
#include "synthetic_maps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

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
  const auto members =
      placeMembers(identityCladding([](double) { return 1.0; }), kSquare, 1.0, 1.0, options);
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
  const auto members = placeMembers(identityCladding([](double x) {
                                      return 1.0 + 0.1 * std::exp(-std::pow((x - 0.3) / 0.08, 2));
                                    }),
                                    kSquare, 1.0, 1.0, options);
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

// Members placed automatically on C(x) (target spacing 0.1 on unit sides, C smoothed over 5 cm):
// a bump of C at x0 (a locally longest member) and a dip at 0.72.
MemberOptions featureOptions() {
  MemberOptions options;
  options.lamellaWidthM = 0.01;
  options.spacingFactor = 10.0;
  return options;
}
double bumpAndDip(double x, double x0) {
  return 1.0 + 0.1 * std::exp(-std::pow((x - x0) / 0.08, 2)) -
         0.06 * std::exp(-std::pow((x - 0.72) / 0.1, 2));
}
// Deterministic noise in [-1, 1] per cladding point.
double noise(int k) {
  const double v = std::sin(12.9898 * k + 78.233) * 43758.5453;
  return 2.0 * (v - std::floor(v)) - 1.0;
}
template <class Length>
CladdingFunction noisyCladding(Length length, double relative, int n = 201) {
  CladdingFunction f = identityCladding(length, n);
  for (size_t k = 0; k < f.lengths.size(); ++k)
    f.lengths[k] *= 1.0 + relative * noise(static_cast<int>(k));
  return f;
}
double largestShift(const FamilyMembers& a, const FamilyMembers& b) {
  if (a.x1.size() != b.x1.size()) return 1.0;
  double shift = 0.0;
  for (size_t k = 0; k < a.x1.size(); ++k) shift = std::max(shift, std::abs(a.x1[k] - b.x1[k]));
  return shift;
}

TEST(Members, LengthExtremaAreFoundBetweenSamples) {
  // The bump's maximum at x0 and the dip's minimum at 0.72 are analytic (the tails of the other
  // feature are below 1e-11 there, and smoothing a symmetric feature does not move its centre);
  // x0 lies between the samples of any grid with a round count of samples on [0, 1].
  const double x0 = 0.3 + 0.37 / 255;
  const auto members = placeMembers(identityCladding([&](double x) { return bumpAndDip(x, x0); }),
                                    kSquare, 1.0, 1.0, featureOptions());
  std::vector<double> extrema;
  for (size_t k = 0; k < members.x1.size(); ++k)
    if (members.origin[k] == MemberOrigin::LengthExtremum) extrema.push_back(members.x1[k]);
  ASSERT_EQ(extrema.size(), 2u);
  EXPECT_NEAR(extrema[0], x0, 1e-4);  // 1e-4 of the total length (1 m)
  EXPECT_NEAR(extrema[1], 0.72, 1e-4);
}

TEST(Members, TinyNoiseOnCMovesNoMember) {
  // Relative noise of 1e-6 on C must move every member by far less than a millimetre on a 1 m
  // side. Member positions on a sample grid (256 samples: steps of 3.9 mm) jumped by a whole step
  // whenever an extremum sat near the middle between two samples; x0 sweeps one such step in 80
  // offsets.
  for (int j = 0; j < 80; ++j) {
    const double x0 = 0.3 + j / (80.0 * 255.0);
    const auto length = [&](double x) { return bumpAndDip(x, x0); };
    const auto exact = placeMembers(identityCladding(length), kSquare, 1.0, 1.0, featureOptions());
    const auto noisy =
        placeMembers(noisyCladding(length, 1e-6), kSquare, 1.0, 1.0, featureOptions());
    ASSERT_EQ(exact.x1.size(), noisy.x1.size()) << "x0 = " << x0;
    EXPECT_LT(largestShift(exact, noisy), 1e-4) << "x0 = " << x0;
  }
}

TEST(Members, MirrorSymmetricLengthsGiveMirrorSymmetricMembers) {
  // C(x) = C(1 - x) on the square: the members are symmetric about x = 1/2.
  const auto length = [](double x) {
    return 1.0 + 0.1 * std::exp(-std::pow((x - 0.5) / 0.1, 2)) +
           0.04 * std::exp(-std::pow((x - 0.17) / 0.06, 2)) +
           0.04 * std::exp(-std::pow((x - 0.83) / 0.06, 2));
  };
  const auto members = placeMembers(identityCladding(length), kSquare, 1.0, 1.0, featureOptions());
  const size_t n = members.x1.size();
  ASSERT_GE(n, 5u);
  int features = 0;
  for (size_t k = 0; k < n; ++k) {
    EXPECT_NEAR(members.x1[k] + members.x1[n - 1 - k], 1.0, 1e-9) << k;
    EXPECT_EQ(members.origin[k], members.origin[n - 1 - k]) << k;
    features += members.origin[k] == MemberOrigin::LengthExtremum ||
                members.origin[k] == MemberOrigin::CurvatureExtremum;
  }
  EXPECT_GE(features, 3);  // the centre bump's maximum and the side bumps
}

TEST(Members, NeitherTheScanNorTheSamplingOfCMovesMembers) {
  // The extrema are roots of C smoothed over a physical length (half the target spacing):
  // doubling the scan that brackets them, or sampling C twice as finely, moves no member by more
  // than 1e-4 of the side.
  const auto length = [](double x) { return bumpAndDip(x, 0.3 + 0.37 / 255); };
  const auto reference =
      placeMembers(identityCladding(length), kSquare, 1.0, 1.0, featureOptions());
  ASSERT_GE(reference.x1.size(), 7u);
  MemberOptions finerScan = featureOptions();
  finerScan.scanSamplesPerSigma *= 2;
  EXPECT_LT(
      largestShift(placeMembers(identityCladding(length), kSquare, 1.0, 1.0, finerScan), reference),
      1e-4);
  EXPECT_LT(
      largestShift(placeMembers(identityCladding(length, 401), kSquare, 1.0, 1.0, featureOptions()),
                   reference),
      1e-4);
}

// Counts of the members that have each origin.
std::array<int, 5> originCounts(const FamilyMembers& m) {
  std::array<int, 5> counts{};
  for (MemberOrigin origin : m.origin) ++counts[static_cast<size_t>(origin)];
  return counts;
}

TEST(Members, SamplingCoarserThanTheSmoothingAddsNoFeatures) {
  // Sides of 40 m, default lamellas (w = 5 cm, target spacing 0.4 m, smoothing 0.2 m). Sampled
  // every 0.40 m (100 samples), each slope change of the piecewise-linear C used to be a bump of
  // the smoothed curvature of its own: 103 members, 15 of them curvature extrema, against 101 and
  // 4 with 200 samples. The smoothing now spans at least 1.5 sample steps.
  const PlanarQuad square = *planarQuad({40, 40, 40, 40}, M_PI / 2);
  const auto place = [&](int n, const MemberOptions& options) {
    return placeMembers(identityCladding([](double x) { return 40.0 * bumpAndDip(x, 0.3); }, n),
                        square, 40.0, 40.0, options);
  };
  const auto coarse = place(100, {}), finer = place(200, {}), fine = place(2001, {});
  EXPECT_EQ(originCounts(fine)[static_cast<size_t>(MemberOrigin::CurvatureExtremum)], 4);
  EXPECT_EQ(originCounts(coarse), originCounts(fine));
  EXPECT_EQ(originCounts(finer), originCounts(fine));
  ASSERT_EQ(coarse.x1.size(), finer.x1.size());
  for (size_t k = 0; k < coarse.x1.size(); ++k) {
    EXPECT_EQ(coarse.origin[k], finer.origin[k]) << k;
    // The smoothing differs (0.61 m and 0.30 m), which moves curvature extrema (measured 2.1e-3
    // of the side) but not the extrema of the symmetric bump and dip (1e-4 = 4 mm).
    const bool length = coarse.origin[k] == MemberOrigin::LengthExtremum;
    EXPECT_NEAR(coarse.x1[k], finer.x1[k], length ? 1e-4 : 2.5e-3)
        << k;  // 2.5e-3: a quarter of the spacing
  }
  // The coarse samples change nothing but the smoothing width: 100 samples give the members of a
  // finely sampled C smoothed over 1.5 steps of 40/99 m (measured 1.9e-4; before, 2 members more).
  MemberOptions wide;
  wide.smoothingFraction = 1.5 * (40.0 / 99) / 0.4;
  EXPECT_LT(largestShift(coarse, place(4001, wide)), 5e-4);
  // w = 1 mm (smoothing 4 mm) on samples 0.4 m apart: still the 4 curvature members of the bump
  // and dip, not one per sample.
  MemberOptions thin;
  thin.lamellaWidthM = 1e-3;
  EXPECT_EQ(originCounts(place(100, thin))[static_cast<size_t>(MemberOrigin::CurvatureExtremum)],
            4);
}

TEST(Members, NonFiniteLengthsAreRejected) {
  // One NaN in C at x = 0.5 used to drop out of every sign test: the bump's member at 0.3 vanished
  // and filled members took its place. Now it is an error naming the cladding point.
  for (double bad : {NAN, INFINITY}) {
    CladdingFunction f = identityCladding(
        [](double x) { return 1.0 + 0.1 * std::exp(-std::pow((x - 0.3) / 0.08, 2)); });
    f.lengths[100] = bad;  // x = 0.5
    for (int count : {0, 5}) {
      MemberOptions options = featureOptions();
      options.count = count;
      try {
        placeMembers(f, kSquare, 1.0, 1.0, options);
        ADD_FAILURE() << "no exception for C = " << bad << ", count " << count;
      } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("point 100 (x1 = 0.5"), std::string::npos) << e.what();
      }
    }
  }
  CladdingFunction f = identityCladding([](double) { return 1.0; });
  f.lengths.pop_back();
  EXPECT_THROW(placeMembers(f, kSquare, 1.0, 1.0), InvalidInput);
}

TEST(Members, RippleFinerThanTheSpacingIsNoFeature) {
  // A 1 mm ripple of period 2 cm (a fifth of the target spacing) cannot carry members of its own:
  // the smoothing over 5 cm removes it and the members are spaced as for a constant C.
  const auto members = placeMembers(
      identityCladding([](double x) { return 1.0 + 1e-3 * std::sin(2 * M_PI * x / 0.02); }),
      kSquare, 1.0, 1.0, featureOptions());
  ASSERT_EQ(members.x1.size(), 11u);
  for (size_t k = 0; k < 11; ++k) EXPECT_NEAR(members.x1[k], 0.1 * k, 1e-9);
}

TEST(Members, NearTiesMoveTheMemberContinuously) {
  // Two bumps 8 cm apart (closer than half the target spacing, so only one member fits) with
  // heights 0.1 and 0.1 (1 + e): a strict ranking puts the member on the higher bump and jumps
  // 8 cm as e changes sign; within the tie band the member slides between them, through the
  // midpoint 0.49 at e = 0.
  MemberOptions options = featureOptions();
  options.lamellaWidthM = 0.02;      // target spacing 0.2
  options.smoothingFraction = 0.05;  // sigma 1 cm keeps the two bumps apart
  const auto nearest = [](const FamilyMembers& m, double x) {
    double best = 1.0;
    for (double v : m.x1) best = std::abs(v - x) < std::abs(best - x) ? v : best;
    return best;
  };
  const auto place = [&](double e, const MemberOptions& o) {
    return placeMembers(identityCladding(
                            [&](double x) {
                              return 1.0 + 0.1 * std::exp(-std::pow((x - 0.45) / 0.015, 2)) +
                                     0.1 * (1 + e) * std::exp(-std::pow((x - 0.53) / 0.015, 2));
                            },
                            801),
                        kSquare, 1.0, 1.0, o);
  };
  EXPECT_NEAR(nearest(place(0.0, options), 0.49), 0.49, 1e-6);
  double previous = nearest(place(-0.1, options), 0.49), largestStep = 0.0;
  EXPECT_NEAR(previous, 0.45, 2e-3);  // outside the band: the higher bump alone
  for (int k = -19; k <= 20; ++k) {
    const double x = nearest(place(0.005 * k, options), 0.49);
    largestStep = std::max(largestStep, std::abs(x - previous));
    previous = x;
  }
  EXPECT_NEAR(previous, 0.53, 2e-3);
  EXPECT_LT(largestStep, 0.01);
  options.tieBand = 0.0;  // strict ranking: the jump
  EXPECT_NEAR(nearest(place(-1e-6, options), 0.49) - nearest(place(1e-6, options), 0.49), -0.08,
              2e-3);
}

TEST(Members, FixedCountIsEvenAndChecksDensity) {
  MemberOptions options;
  options.count = 5;
  const auto members = placeMembers(identityCladding([](double x) { return 1.0 + x * x; }), kSquare,
                                    1.0, 1.0, options);
  ASSERT_EQ(members.x1.size(), 5u);
  EXPECT_NEAR(members.x1[1], 0.25, 1e-12);
  EXPECT_NEAR(members.lengths[2], 1.25, 1e-4);
  options.count = 100;
  options.lamellaWidthM = 0.05;  // 100 lamellas of 5 cm do not fit on a 1 m side
  EXPECT_THROW(
      placeMembers(identityCladding([](double) { return 1.0; }), kSquare, 1.0, 1.0, options),
      InvalidInput);
}

TEST(Members, NonBijectiveCladdingIsInfeasible) {
  CladdingFunction f;
  f.points = {{0, 0}, {1, 0}, {1, 1}};
  f.lengths = {1, 1, 1};
  EXPECT_THROW(placeMembers(f, kSquare, 1.0, 1.0), InfeasiblePatch);
  MemberOptions bad;
  bad.count = 1;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = MemberOptions{};
  bad.smoothingFraction = 0.0;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = MemberOptions{};
  bad.scanSamplesPerSigma = 1;
  EXPECT_THROW(bad.validate(), InvalidInput);
  bad = MemberOptions{};
  bad.tieBand = 1.0;
  EXPECT_THROW(bad.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg
