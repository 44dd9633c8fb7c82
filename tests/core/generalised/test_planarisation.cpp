// Planarisation of generalised grids (Section 4.7): gradients against finite differences, a flat
// grid recovered without notches, a spherical grid that cannot be (Gauss' theorema egregium),
// and the fabrication term of Fig. 4.18.
#include "core/generalised/planarisation.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace egg::generalised {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// Parameter along segment a of its crossing with segment b (straight lines in the plane).
double crossingFraction(const Segment2& a, const Segment2& b) {
  const Vec2 r = a[1] - a[0], s = b[1] - b[0], d = b[0] - a[0];
  const double cross = r.x() * s.y() - r.y() * s.x();
  return (d.x() * s.y() - d.y() * s.x()) / cross;
}

// A flat grid: family 0 running left to right at heights ys (tilted by `tilt`), family 1 bottom
// to top at abscissae xs; every member crosses every member of the other family.
PlanarisationProblem flatGrid(const std::vector<double>& ys, const std::vector<double>& xs,
                              double tilt, std::vector<Segment2>& exact) {
  PlanarisationProblem p;
  exact.clear();
  for (double y : ys) exact.push_back({Vec2(-2.0, y - tilt), Vec2(2.0, y + tilt)});
  for (double x : xs) exact.push_back({Vec2(x + tilt, -2.0), Vec2(x - tilt, 2.0)});
  const int g = static_cast<int>(ys.size());
  for (size_t i = 0; i < exact.size(); ++i)
    p.members.push_back({(exact[i][1] - exact[i][0]).norm(), static_cast<int>(i) < g ? 0 : 1});
  for (int i = 0; i < g; ++i) {
    for (size_t j = g; j < exact.size(); ++j) {
      p.crossings.push_back({i, static_cast<int>(j), crossingFraction(exact[i], exact[j]),
                             crossingFraction(exact[j], exact[i])});
    }
  }
  // Family 0: the next one up lies to the left; family 1 runs upwards, the next one right lies to
  // its right, so the pair is (next, this).
  for (int i = 0; i + 1 < g; ++i) p.neighbours.push_back({i, i + 1});
  for (int j = g; j + 1 < static_cast<int>(exact.size()); ++j) p.neighbours.push_back({j + 1, j});
  return p;
}

std::vector<double> flatten(const std::vector<Segment2>& segments) {
  std::vector<double> x;
  for (const auto& s : segments) x.insert(x.end(), {s[0].x(), s[0].y(), s[1].x(), s[1].y()});
  return x;
}

// The initial layout: the exact one turned, shifted and disturbed.
std::vector<Segment2> disturbed(const std::vector<Segment2>& exact, double noise, int seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  const Eigen::Rotation2Dd turn(0.3);
  std::vector<Segment2> out;
  for (const auto& s : exact) {
    out.push_back({turn * s[0] + Vec2(0.7 + u(rng), -0.4 + u(rng)),
                   turn * s[1] + Vec2(0.7 + u(rng), -0.4 + u(rng))});
  }
  return out;
}

TEST(Planarisation, GradientsMatchFiniteDifferences) {
  std::vector<Segment2> exact;
  PlanarisationProblem p = flatGrid({-1.0, -0.1, 0.9}, {-0.8, 0.05, 1.0}, 0.2, exact);
  p.widthM = 0.9;  // wide: some facing edges cross, so both signs of the distances are tested
  p.initial = disturbed(exact, 0.2, 3);
  const std::vector<double> x = flatten(p.initial);
  std::vector<double> gradient;
  notchEnergy(p, x, &gradient);
  std::vector<double> values, jacobian;
  lengthConstraints(p, x, values, &jacobian);
  const double h = 1e-6;
  for (size_t k = 0; k < x.size(); ++k) {
    std::vector<double> plus = x, minus = x;
    plus[k] += h;
    minus[k] -= h;
    const double fd = (notchEnergy(p, plus, nullptr) - notchEnergy(p, minus, nullptr)) / (2.0 * h);
    EXPECT_NEAR(gradient[k], fd, 1e-7 * (1.0 + std::abs(fd))) << "coordinate " << k;
    std::vector<double> vp, vm;
    lengthConstraints(p, plus, vp, nullptr);
    lengthConstraints(p, minus, vm, nullptr);
    for (size_t i = 0; i < values.size(); ++i)
      EXPECT_NEAR(jacobian[i * x.size() + k], (vp[i] - vm[i]) / (2.0 * h), 1e-7) << i << " " << k;
  }
  int positive = 0, negative = 0;
  for (const NeighbourPair& pair : p.neighbours) {
    std::array<Eigen::Matrix<double, 8, 1>, 4> gradients;
    const auto e = overlapDistances(p, pair, x, &gradients);
    for (double v : e) (v > 0.0 ? positive : negative) += 1;
    const int members[2] = {pair.first, pair.second};
    for (int c = 0; c < 8; ++c) {
      std::vector<double> plus = x, minus = x;
      plus[4 * members[c / 4] + c % 4] += h;
      minus[4 * members[c / 4] + c % 4] -= h;
      const auto ep = overlapDistances(p, pair, plus, nullptr);
      const auto em = overlapDistances(p, pair, minus, nullptr);
      for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(gradients[i][c], (ep[i] - em[i]) / (2.0 * h), 1e-7) << i << " " << c;
    }
  }
  EXPECT_GE(positive, 2);
  EXPECT_GE(negative, 2);
}

TEST(Planarisation, AFlatGridIsRecoveredWithoutNotches) {
  std::vector<Segment2> exact;
  PlanarisationProblem p = flatGrid({-1.2, -0.4, 0.3, 1.1}, {-1.0, -0.2, 0.6, 1.3}, 0.15, exact);
  p.widthM = 0.1;
  p.initial = disturbed(exact, 0.1, 7);
  const PlanarisationResult r = planarise(p);
  EXPECT_GT(r.initialNotchEnergyM2, 1e-3);
  EXPECT_LT(r.notchEnergyM2, 1e-14) << r.status;
  EXPECT_LT(*std::max_element(r.notchLengthsM.begin(), r.notchLengthsM.end()), 1e-7);
  EXPECT_LT(r.lengthResidualM, 1e-12);
  EXPECT_TRUE(r.overlappingPairs.empty());
  // Not compared with the flat grid itself: a planar scissor grid keeps its straight members and
  // crossing fractions through a one-parameter motion (its deployment, Section 4.9.1), so any
  // member of that family is a zero-notch layout.
}

// A grid of great-circle arcs between points of a spherical cap's rim: no planar layout keeps both
// the lengths and the crossings (the sphere is not developable), so notches remain, but they are
// far shorter than in the flattened start.
TEST(Planarisation, ASphericalGridKeepsShortNotches) {
  const double radius = 10.0, cap = 0.5;  // m, rad (the rim at polar angle 0.5: ~9.6 m across)
  auto rim = [&](double phi) {
    return Vec3(std::sin(cap) * std::cos(phi), std::sin(cap) * std::sin(phi), std::cos(cap));
  };
  const std::vector<double> offsets{-0.45, -0.15, 0.15, 0.45};  // fractions of the rim radius
  std::vector<std::array<Vec3, 2>> arcs;                        // unit vectors of the ends
  for (double c : offsets) arcs.push_back({rim(M_PI - std::asin(c)), rim(std::asin(c))});
  for (double c : offsets) arcs.push_back({rim(-std::acos(c)), rim(std::acos(c))});
  PlanarisationProblem p;
  for (size_t i = 0; i < arcs.size(); ++i) {
    const double angle = std::acos(arcs[i][0].dot(arcs[i][1]));
    p.members.push_back({radius * angle, i < offsets.size() ? 0 : 1});
    // Start: the rim seen from above, scaled to the cap's width.
    p.initial.push_back({radius * arcs[i][0].head<2>(), radius * arcs[i][1].head<2>()});
  }
  const int g = static_cast<int>(offsets.size());
  for (int i = 0; i < g; ++i) {
    for (int j = g; j < 2 * g; ++j) {
      const Vec3 n1 = arcs[i][0].cross(arcs[i][1]), n2 = arcs[j][0].cross(arcs[j][1]);
      Vec3 q = n1.cross(n2).normalized();
      if (q.z() < 0.0) q = -q;  // the crossing inside the cap
      auto fraction = [&](const std::array<Vec3, 2>& arc) {
        return std::acos(arc[0].dot(q)) / std::acos(arc[0].dot(arc[1]));
      };
      p.crossings.push_back({i, j, fraction(arcs[i]), fraction(arcs[j])});
    }
  }
  for (int i = 0; i + 1 < g; ++i) p.neighbours.push_back({i, i + 1});
  for (int j = g; j + 1 < 2 * g; ++j) p.neighbours.push_back({j + 1, j});
  p.widthM = 0.1;
  const PlanarisationResult r = planarise(p);
  const double spacing = radius * 0.3 * std::sin(cap);  // between neighbouring members, ~1.4 m
  const double longest = *std::max_element(r.notchLengthsM.begin(), r.notchLengthsM.end());
  EXPECT_GT(longest, 1e-4);  // the sphere cannot be flattened
  EXPECT_LT(longest, 0.05 * spacing);
  EXPECT_LT(r.notchEnergyM2, 0.2 * r.initialNotchEnergyM2);
  EXPECT_LT(r.lengthResidualM, 1e-12);
  EXPECT_TRUE(r.overlappingPairs.empty());
}

// Two lamellas of one family 0.1 m apart on the surface, 0.15 m wide: laid out as on the surface
// they overlap by 5 cm; with the constraints of Fig. 4.18 they are moved apart, paid with notches.
TEST(Planarisation, TheOverlapConstraintsSeparateOverlappingLamellas) {
  std::vector<Segment2> exact;
  PlanarisationProblem p = flatGrid({-0.05, 0.05, 1.0}, {-1.0, 0.0, 1.0}, 0.0, exact);
  p.widthM = 0.15;
  p.initial = disturbed(exact, 0.02, 11);
  const std::vector<NeighbourPair> neighbours = p.neighbours;
  auto largestOverlap = [&](const PlanarisationResult& r) {
    const auto e = overlapDistances(p, neighbours[0], flatten(r.endpoints), nullptr);
    return *std::max_element(e.begin(), e.end());
  };
  p.neighbours.clear();  // no fabrication constraints: the flat grid itself, notch-free
  const PlanarisationResult free = planarise(p);
  EXPECT_LT(free.notchEnergyM2, 1e-14);
  EXPECT_NEAR(largestOverlap(free), 0.05, 1e-3);  // the scissor motion may turn it a little
  p.neighbours = neighbours;
  const PlanarisationResult apart = planarise(p);
  EXPECT_TRUE(apart.overlappingPairs.empty()) << apart.status;
  EXPECT_LT(largestOverlap(apart), 1e-9);
  EXPECT_GT(apart.notchEnergyM2, 1e-4);
  EXPECT_LT(apart.lengthResidualM, 1e-12);
}

TEST(Planarisation, BadInputNamesTheElement) {
  std::vector<Segment2> exact;
  PlanarisationProblem p = flatGrid({0.0}, {0.0}, 0.0, exact);
  p.initial = exact;
  p.crossings[0].lambdaG = 1.5;
  try {
    planarise(p);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("crossings[0]"), std::string::npos) << e.what();
  }
  p.crossings[0].lambdaG = 0.5;
  p.members[1].lengthM = -1.0;
  EXPECT_THROW(planarise(p), InvalidInput);
}

}  // namespace
}  // namespace egg::generalised
