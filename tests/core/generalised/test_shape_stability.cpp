// Shape stability and E_shape (Section 4.6.2, Eq. 4.9): inflection counts of closed-form kappa_n
// profiles, the Hafner-Bickel test for two inflections (an Euler elastica passes by construction),
// the mutual stabilisation of Fig. 4.14 and malformed input.
#include "core/generalised/shape_stability.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>

namespace egg::generalised {
namespace {

MemberCurvatureProfile shapeSampled(const std::function<double(double)>& kappa, double length,
                                    int intervals = 400) {
  MemberCurvatureProfile profile;
  for (int j = 0; j <= intervals; ++j) {
    const double s = length * j / intervals;
    profile.arcLengthM.push_back(s);
    profile.kappaN.push_back(kappa(s));
  }
  return profile;
}

// kappa_n = amplitude cos(2 pi s / L): an S-curve and back whose end lobes turn by
// amplitude L / (2 pi) radians each.
MemberCurvatureProfile shapeCosineS(double turning, double length = 1.0) {
  const double amplitude = turning * 2.0 * M_PI / length;
  return shapeSampled([=](double s) { return amplitude * std::cos(2.0 * M_PI * s / length); },
                      length);
}

std::string shapeMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no InvalidInput)";
}

TEST(ShapeStability, CountsAndPlacesTheInflectionsOfCosineProfiles) {
  const double length = 2.0;
  const auto none =
      shapeSampled([&](double s) { return 1.0 + 0.5 * std::cos(2 * M_PI * s / length); }, length);
  EXPECT_TRUE(inflectionArcLengths(none).empty());
  for (int k = 1; k <= 3; ++k) {
    const auto profile =
        shapeSampled([&](double s) { return 0.7 * std::cos(k * M_PI * s / length); }, length);
    const auto found = inflectionArcLengths(profile);
    ASSERT_EQ(static_cast<int>(found.size()), k);
    // Zeros of cos(k pi s / L) at s = (2i + 1) L / (2k).
    for (int i = 0; i < k; ++i) EXPECT_NEAR(found[i], (2 * i + 1) * length / (2.0 * k), 1e-4) << k;
  }
}

// Two lobes of opposite sign with a flat stretch between them on which kappa_n is noise: one
// inflection, somewhere on the stretch; without the zero band the noise counts dozens.
TEST(ShapeStability, NoiseOnAFlatStretchIsNoInflection) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  const auto profile = shapeSampled(
      [&](double s) {
        if (s < 1.0) return std::sin(M_PI * s);
        if (s < 2.0) return noise(random);
        return -std::sin(M_PI * (s - 2.0));
      },
      3.0, 600);
  const auto found = inflectionArcLengths(profile);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_GT(found[0], 1.0);
  EXPECT_LT(found[0], 2.0);
  ShapeStabilityOptions exact;
  exact.relativeZeroTolerance = 0.0;
  exact.absoluteZeroToleranceInvM = 0.0;
  EXPECT_GT(inflectionArcLengths(profile, exact).size(), 20u);
  // A member with no curvature to speak of is straight.
  EXPECT_TRUE(inflectionArcLengths(shapeSampled([&](double) { return noise(random) * 1e-9; }, 1.0))
                  .empty());
}

TEST(ShapeStability, ConstantCurvatureIntegratesToACircle) {
  const double radius = 0.8;
  const auto points =
      planarCurveFromCurvature(shapeSampled([&](double) { return 1.0 / radius; }, M_PI * radius));
  for (const auto& p : points) EXPECT_NEAR((p - Eigen::Vector2d(0.0, radius)).norm(), radius, 1e-5);
  EXPECT_NEAR(points.back().x(), 0.0, 1e-5);
  EXPECT_NEAR(points.back().y(), 2.0 * radius, 1e-5);
}

// kappa_n = k cos(2 pi s / L) is mirror-symmetric about its middle normal; the line through the
// inflection points is perpendicular to that mirror. With end lobes turning 2 rad each they stay
// below the line and the middle lobe above it: an equilibrium. Turning 4 rad (> pi), the end
// lobes curl back across the line: no stiffness distribution holds that shape.
TEST(ShapeStability, HafnerBickelSeparatesTheSymmetricSCurves) {
  const auto held = shapeCosineS(2.0);
  const auto heldInflections = inflectionArcLengths(held);
  ASSERT_EQ(heldInflections.size(), 2u);
  EXPECT_TRUE(hafnerBickelTwoInflections(held, heldInflections));
  const auto curled = shapeCosineS(4.0);
  const auto curledInflections = inflectionArcLengths(curled);
  ASSERT_EQ(curledInflections.size(), 2u);
  EXPECT_FALSE(hafnerBickelTwoInflections(curled, curledInflections));
}

// An asymmetric profile, three bumps of kappa_n (+, -, +) with a weak middle one: the outer lobes
// turn so far that each reaches both sides of the line through the two inflection points.
TEST(ShapeStability, HafnerBickelRejectsOuterLobesAcrossTheLine) {
  const auto bump = [](double s, double centre, double width) {
    return std::exp(-std::pow((s - centre) / width, 2));
  };
  const auto profile = shapeSampled(
      [&](double s) {
        return 6.0 * bump(s, 0.15, 0.08) - 4.0 * bump(s, 0.42, 0.06) + 6.0 * bump(s, 0.8, 0.08);
      },
      1.0, 1000);
  const auto found = inflectionArcLengths(profile);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_FALSE(hafnerBickelTwoInflections(profile, found));
  // A stronger middle bump straightens the outer lobes' reach: then the shape is held.
  const auto strong = shapeSampled(
      [&](double s) {
        return 6.0 * bump(s, 0.15, 0.08) - 10.0 * bump(s, 0.42, 0.06) + 6.0 * bump(s, 0.8, 0.08);
      },
      1.0, 1000);
  const auto strongFound = inflectionArcLengths(strong);
  ASSERT_EQ(strongFound.size(), 2u);
  EXPECT_TRUE(hafnerBickelTwoInflections(strong, strongFound));
}

// An Euler elastica (uniform stiffness, end force along x): theta'' = -lambda sin(theta), so
// kappa = theta' is proportional to the distance from the force's line. Integrated by RK4 and cut
// between its second and third inflections, it must pass, and the planar curve rebuilt from kappa
// alone must show kappa proportional to the distance from the line through its inflections.
TEST(ShapeStability, AnEulerElasticaPassesHafnerBickel) {
  const double lambda = 1.0, h = 0.005;
  MemberCurvatureProfile full;
  double theta = 0.3, kappa = 1.2;
  for (int j = 0; j <= 3000; ++j) {
    full.arcLengthM.push_back(j * h);
    full.kappaN.push_back(kappa);
    const auto f = [&](double t, double k) {
      return std::array<double, 2>{k, -lambda * std::sin(t)};
    };
    const auto k1 = f(theta, kappa);
    const auto k2 = f(theta + 0.5 * h * k1[0], kappa + 0.5 * h * k1[1]);
    const auto k3 = f(theta + 0.5 * h * k2[0], kappa + 0.5 * h * k2[1]);
    const auto k4 = f(theta + h * k3[0], kappa + h * k3[1]);
    theta += h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
    kappa += h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
  }
  const auto all = inflectionArcLengths(full);
  ASSERT_GE(all.size(), 3u);
  MemberCurvatureProfile cut;
  for (size_t j = 0; full.arcLengthM[j] < 0.5 * (all[1] + all[2]); ++j) {
    cut.arcLengthM.push_back(full.arcLengthM[j]);
    cut.kappaN.push_back(full.kappaN[j]);
  }
  const auto found = inflectionArcLengths(cut);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_TRUE(hafnerBickelTwoInflections(cut, found));

  const auto points = planarCurveFromCurvature(cut);
  const auto at = [&](double s) {
    const size_t j = static_cast<size_t>(s / h);
    const double t = (s - cut.arcLengthM[j]) / h;
    return Eigen::Vector2d((1 - t) * points[j] + t * points[j + 1]);
  };
  const Eigen::Vector2d p1 = at(found[0]), chord = at(found[1]) - p1;
  const Eigen::Vector2d normal = Eigen::Vector2d(-chord.y(), chord.x()).normalized();
  double dd = 0.0, kd = 0.0;
  for (size_t j = 0; j < points.size(); ++j) {
    const double d = normal.dot(points[j] - p1);
    dd += d * d;
    kd += cut.kappaN[j] * d;
  }
  const double c = kd / dd;
  EXPECT_NEAR(std::abs(c), lambda, 1e-3);  // K kappa = |F| d with K = 1 and |F| = lambda
  for (size_t j = 0; j < points.size(); ++j)
    EXPECT_NEAR(cut.kappaN[j], c * normal.dot(points[j] - p1), 1e-3) << j;
}

// Fig. 4.14 and Eq. 4.9. Member 0: two inflections, curled (unstable on its own), crossed in its
// middle segment by the stable member 1: eta = 1. Member 2: four inflections, three segments, of
// which only one is crossed by a stable member (member 1 also crosses it before its first
// inflection, where no support is needed, and the unstable member 3 crosses another): eta = 1/3.
// Member 3: three inflections, crossed only by member 2, itself unstable: eta = 0.
TEST(ShapeStability, MutualStabilisationOfFigure414) {
  const auto cosine = [](double k) {
    return shapeSampled([=](double s) { return 2.0 * std::cos(k * M_PI * s); }, 1.0);
  };
  const std::vector<MemberCurvatureProfile> profiles{
      shapeCosineS(4.0), shapeSampled([](double) { return 0.5; }, 1.0), cosine(4.0), cosine(3.0)};
  // Member 2's inflections at 1/8, 3/8, 5/8, 7/8; member 3's at 1/6, 1/2, 5/6.
  const std::vector<StabilityCrossing> crossings{
      {0, 0.5, 1, 0.2}, {2, 0.25, 1, 0.6}, {2, 0.5, 3, 0.5}, {1, 0.9, 2, 0.05}};
  const auto result = shapeStability(profiles, crossings);
  EXPECT_EQ(result.inflections, (std::vector<int>{2, 0, 4, 3}));
  EXPECT_EQ(result.ownEta, (std::vector<double>{0.0, 1.0, 0.0, 0.0}));
  ASSERT_EQ(result.eta.size(), 4u);
  EXPECT_DOUBLE_EQ(result.eta[0], 1.0);
  EXPECT_DOUBLE_EQ(result.eta[1], 1.0);
  EXPECT_DOUBLE_EQ(result.eta[2], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(result.eta[3], 0.0);
  EXPECT_DOUBLE_EQ(result.eShape, (1.0 + 1.0 + 1.0 / 3.0 + 0.0) / 4.0);

  // Without the crossings nothing is supported: E_shape is the share of stable members.
  EXPECT_DOUBLE_EQ(shapeStability(profiles, {}).eShape, 0.25);
  // A crossing given the other way round is the same crossing.
  auto swapped = crossings;
  for (auto& c : swapped) c = {c.second, c.secondArcLengthM, c.first, c.firstArcLengthM};
  EXPECT_EQ(shapeStability(profiles, swapped).eta, result.eta);
}

TEST(ShapeStability, MalformedInputIsNamed) {
  const auto good = shapeSampled([](double s) { return s; }, 1.0, 10);
  auto shortKappa = good;
  shortKappa.kappaN.pop_back();
  EXPECT_NE(shapeMessage([&] {
              shapeStability({good, shortKappa}, {});
            }).find("member 1"),
            std::string::npos);
  auto backwards = good;
  backwards.arcLengthM[4] = backwards.arcLengthM[3];
  const auto message = shapeMessage([&] { shapeStability({backwards}, {}); });
  EXPECT_NE(message.find("member 0"), std::string::npos) << message;
  EXPECT_NE(message.find("strictly increasing"), std::string::npos) << message;
  EXPECT_NE(shapeMessage([&] {
              shapeStability({good, good}, {{0, 0.5, 5, 0.5}});
            }).find("member 5"),
            std::string::npos);
  EXPECT_NE(shapeMessage([&] {
              shapeStability({good, good}, {{0, 0.5, 1, 0.2}, {0, 1.5, 1, 0.5}});
            }).find("crossing 1"),
            std::string::npos);
  EXPECT_THROW(shapeStability({good, good}, {{1, 0.5, 1, 0.5}}), InvalidInput);
  EXPECT_THROW(shapeStability({}, {}), InvalidInput);
  EXPECT_THROW(hafnerBickelTwoInflections(good, {0.5}), InvalidInput);

  ShapeStabilityOptions options;
  options.relativeZeroTolerance = -0.1;
  try {
    shapeStability({good}, {}, options);
    ADD_FAILURE() << "a negative relativeZeroTolerance was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.field(), "relativeZeroTolerance");
  }
  options = {};
  options.lineSideTolerance = std::nan("");
  EXPECT_THROW(options.validate(), InvalidInput);
}

}  // namespace
}  // namespace egg::generalised
