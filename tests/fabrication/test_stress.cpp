#include "fabrication/stress.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::fabrication {
namespace {

// A lamella wrapped round a cylinder of radius R (axis y): points on the circle at uneven angles,
// the surface normal radial.
void arc(double radius, std::vector<Eigen::Vector3d>& points,
         std::vector<Eigen::Vector3d>& normals) {
  double phi = -0.6;
  for (int k = 0; k < 14; ++k) {
    const Eigen::Vector3d n(std::sin(phi), 0.0, std::cos(phi));
    points.push_back(radius * n);
    normals.push_back(n);
    phi += 0.05 + 0.02 * (k % 3);  // uneven spacing: the circumcircle is still the circle
  }
}

TEST(Stress, LamellaBentToAKnownRadiusGivesSigmaEqualsEKappaTOverTwo) {
  const MaterialProperties& lime = materialByName("limewood");
  const double radius = 2.0, t = 0.001;
  std::vector<Eigen::Vector3d> points, normals;
  arc(radius, points, normals);
  for (const auto& k : polylineCurvature(points)) EXPECT_NEAR(k.norm(), 1.0 / radius, 1e-12);
  const LamellaStress s = lamellaStress(points, &normals, t, lime);
  EXPECT_NEAR(s.maxCurvaturePerM, 0.5, 1e-12);
  // sigma = E kappa t / 2 = 9.1e9 * 0.5 * 0.001 / 2 = 2.275 MPa, exactly.
  EXPECT_NEAR(s.maxBendingStressPa, 2.275e6, 1e-3);
  EXPECT_NEAR(s.maxBendingStressPa, lime.youngsModulusPa * (1.0 / radius) * t / 2.0, 1e-6);
  EXPECT_NEAR(s.maxTwistRateRadPerM, 0.0, 1e-12);  // the normal stays in the bending plane
  EXPECT_NEAR(s.stressRatio, 2.275e6 / lime.bendingStrengthPa, 1e-12);
  // Without normals (a deployed centreline) the whole curvature counts: the same here.
  EXPECT_NEAR(lamellaStress(points, nullptr, t, lime).maxBendingStressPa, 2.275e6, 1e-3);
}

TEST(Stress, CurvatureAboutTheStrongAxisIsNotWeakAxisBending) {
  // The same arc with the normal along the cylinder axis: the lamella bends in its own plane
  // (geodesic curvature), so the weak-axis curvature is zero.
  std::vector<Eigen::Vector3d> points, normals;
  arc(2.0, points, normals);
  for (auto& n : normals) n = Eigen::Vector3d::UnitY();
  EXPECT_NEAR(lamellaStress(points, &normals, 0.001, materialByName("limewood")).maxCurvaturePerM,
              0.0, 1e-12);
}

TEST(Stress, TwistedStripGivesTauEqualsGThetaPrimeT) {
  // A straight strip along x whose normal turns at 0.5 rad/m about the strip.
  std::vector<Eigen::Vector3d> points, normals;
  for (int k = 0; k <= 10; ++k) {
    const double x = 0.1 * k;
    points.emplace_back(x, 0.0, 0.0);
    normals.emplace_back(0.0, -std::sin(0.5 * x), std::cos(0.5 * x));
  }
  for (double r : polylineTwistRate(points, normals)) EXPECT_NEAR(std::abs(r), 0.5, 1e-12);
  const MaterialProperties& poplar = materialByName("poplar_plywood");
  const LamellaStress s = lamellaStress(points, &normals, 0.003, poplar);
  EXPECT_NEAR(s.maxCurvaturePerM, 0.0, 1e-12);
  EXPECT_NEAR(s.maxTorsionStressPa, poplar.shearModulusPa * 0.5 * 0.003, 1e-6);
  EXPECT_NEAR(s.stressRatio, s.maxTorsionStressPa / poplar.shearStrengthPa, 1e-12);
}

TEST(Stress, ShortPolylinesHaveNoCurvature) {
  EXPECT_EQ(polylineCurvature({}).size(), 0u);
  const auto k = polylineCurvature({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()});
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k[0].norm(), 0.0);
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

TEST(Stress, WindowedCurvatureIsExactOnACircleAndIgnoresMeshKinks) {
  const MaterialProperties& lime = materialByName("limewood");
  // A 2 m radius arc through 200 points 10 mm apart, every other point pushed 0.2 mm off the
  // circle: vertex by vertex the polyline is kinked, over a 0.2 m window it is nearly the circle
  // (an offset d of one point changes the curvature by at most about 2 d / window^2 = 0.01).
  std::vector<Eigen::Vector3d> clean, kinked, normals;
  for (int k = 0; k < 200; ++k) {
    const double phi = -0.5 + 0.005 * k;
    const Eigen::Vector3d n(std::sin(phi), 0.0, std::cos(phi));
    clean.push_back(2.0 * n);
    kinked.push_back((2.0 + (k % 2 ? 0.0002 : 0.0)) * n);
    normals.push_back(n);
  }
  EXPECT_NEAR(lamellaStress(clean, &normals, 0.001, lime, 0.2).maxCurvaturePerM, 0.5, 1e-12);
  EXPECT_NEAR(lamellaStress(clean, &normals, 0.001, lime, 0.2).maxBendingStressPa, 2.275e6, 1e-5);
  EXPECT_GT(lamellaStress(kinked, &normals, 0.001, lime).maxCurvaturePerM,
            4.0);  // vertex by vertex: 8 x too much
  EXPECT_NEAR(lamellaStress(kinked, &normals, 0.001, lime, 0.2).maxCurvaturePerM, 0.5, 0.015);
  EXPECT_NEAR(lamellaStress(kinked, nullptr, 0.001, lime, 0.2).maxCurvaturePerM, 0.5, 0.015);
  // The window: twice the width, or three median segments (10 mm here).
  EXPECT_NEAR(curvatureWindowM(clean, 0.1), 0.2, 1e-12);
  EXPECT_NEAR(curvatureWindowM(clean, 0.001), 3.0 * 2.0 * 2.0 * std::sin(0.0025), 1e-9);
}

TEST(Stress, WindowedTwistRate) {
  std::vector<Eigen::Vector3d> points, normals;
  for (int k = 0; k <= 100; ++k) {
    const double x = 0.02 * k;
    points.emplace_back(x, 0.0, 0.0);
    normals.emplace_back(0.0, -std::sin(0.5 * x), std::cos(0.5 * x));
  }
  const auto& poplar = materialByName("poplar_plywood");
  EXPECT_NEAR(lamellaStress(points, &normals, 0.003, poplar, 0.3).maxTwistRateRadPerM, 0.5, 1e-3);
}

}  // namespace
}  // namespace egg::fabrication

namespace egg::fabrication {
namespace {

// A helix of radius a and pitch 2 pi b is a geodesic of its cylinder: curvature a / (a^2 + b^2),
// all of it normal curvature, and geodesic torsion b / (a^2 + b^2) (the cylinder's normal turns
// about the tangent at that rate). 5 mm steps, measured over a 0.3 m window.
TEST(Stress, HelixGivesItsAnalyticCurvatureAndTorsion) {
  const double a = 2.0, b = 0.5, speed = std::hypot(a, b);
  std::vector<Eigen::Vector3d> points, normals;
  for (int k = 0; k <= 1200; ++k) {
    const double phi = 0.005 * k / speed;
    points.emplace_back(a * std::cos(phi), a * std::sin(phi), b * phi);
    normals.emplace_back(std::cos(phi), std::sin(phi), 0.0);
  }
  const auto& poplar = materialByName("poplar_plywood");
  const double t = 0.01;
  const LamellaStress s = lamellaStress(points, &normals, t, poplar, 0.3);
  const double kappa = a / (a * a + b * b), torsion = b / (a * a + b * b);  // 0.4706 and 0.1176 1/m
  EXPECT_NEAR(s.maxCurvaturePerM, kappa, 1e-3 * kappa);
  // The turn of the chord-projected normal carries an error of the order (kappa window)^2 = 2 %.
  EXPECT_NEAR(s.maxTwistRateRadPerM, torsion, 0.02 * torsion);
  EXPECT_NEAR(s.maxBendingStressPa, poplar.youngsModulusPa * kappa * t / 2.0,
              1e-3 * s.maxBendingStressPa);
  EXPECT_NEAR(s.maxTorsionStressPa, poplar.shearModulusPa * s.maxTwistRateRadPerM * t,
              1e-9 * s.maxTorsionStressPa);
}

// The Lilium's base side P8-U0 (a patch side on the mesh): 9 vertices over 4.25 m, three pairs of
// them 1-4 mm apart whose vertex normals differ by about 0.09 rad. The window (three median
// segments, 2.25 m) leaves no vertex a window from both ends; measured vertex by vertex instead the
// twist was 41 rad/m (tau = 984 MPa, ratio 197). The twist the normals describe end to end is what
// counts: here the frame turns by a known 0.4 rad about the straight side, 0.094 rad/m.
TEST(Stress, ShortLamellaWithCrowdedVerticesIsMeasuredOverItsLength) {
  const std::vector<double> x{0.0, 0.5, 0.504, 1.5, 1.504, 2.5, 2.501, 3.4, 4.25};
  std::vector<Eigen::Vector3d> points, normals;
  for (size_t k = 0; k < x.size(); ++k) {
    // The frame's smooth turn, plus a 0.09 rad jump inside every crowded pair (mesh normals).
    const double jump = (k == 1 || k == 3 || k == 5) ? 0.09 : 0.0;
    const double angle = 0.4 * x[k] / 4.25 + jump;
    points.emplace_back(x[k], 0.0, 0.0);
    normals.emplace_back(0.0, -std::sin(angle), std::cos(angle));
  }
  const auto& poplar = materialByName("poplar_plywood");
  const double window = curvatureWindowM(points, 0.5);
  EXPECT_NEAR(window, 3.0 * 0.85, 1e-12);  // three median segments (0.85 m) > twice the width
  const LamellaStress s = lamellaStress(points, &normals, 0.05, poplar, window);
  // Only the most central vertex (x = 2.5) lies 1.75 m from both ends: measured from x = 0.504 to
  // 4.25, where the frame turns at its mean rate.
  EXPECT_NEAR(s.maxTwistRateRadPerM, 0.4 / 4.25, 1e-9);
  EXPECT_LT(s.stressRatio, 1.0);
  // Vertex by vertex (no window) the jumps dominate: 0.09 rad over 1 mm.
  EXPECT_GT(lamellaStress(points, &normals, 0.05, poplar).maxTwistRateRadPerM, 80.0);
}

}  // namespace
}  // namespace egg::fabrication
