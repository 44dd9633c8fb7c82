// Problem 3.3 on one chain: known optima, gradients by finite differences, originals, spacing.
#include "propagation/chain_problem.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::propagation {
namespace {

ChainProblem chainOf(const std::vector<const SideMap*>& maps, int members) {
  ChainProblem p;
  p.maps = maps;
  p.boundaries.assign(maps.size() + 1, ChainBoundary{});
  p.members = members;
  return p;
}

TEST(ChainProblem, IdentityMapsGiveEquidistantMembers) {
  const PiecewiseLinearMap identity;
  const auto problem = chainOf({&identity, &identity, &identity}, 6);
  const auto s = solveChain(problem);
  ASSERT_EQ(s.positions.size(), 4u);
  for (const auto& boundary : s.positions)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(boundary[j], j / 5.0, 1e-12);
  EXPECT_NEAR(s.evennessAfter, 4 * 5 * 0.04, 1e-12);  // 4 boundaries x 5 gaps of 1/5
  EXPECT_LE(s.evennessAfter, s.evennessBefore + 1e-15);
}

// F_1 = F_3 kinked at (0.5, 0.4), F_2 its inverse; one free member t. Past the kink the positions
// are affine, p_i = a_i t + b_i with a = (1, 1.2, 1, 1.2), b = (0, -0.2, 0, -0.2), and
// J(t) = sum (2 p_i^2 - 2 p_i + 1) is least at t = -sum (4 b_i - 2) a_i / (4 sum a_i^2) = 10.72
// / 19.52; below the kink J's own minimum (t = 3.6 / 6.56) lies past 0.5, so that is the optimum.
TEST(ChainProblem, ThreePatchesWithKnownPiecewiseLinearF) {
  const PiecewiseLinearMap f({{0, 0}, {0.5, 0.4}, {1, 1}});
  const auto g = f.inverted();
  const auto problem = chainOf({&f, &g, &f}, 3);
  const auto s = solveChain(problem);
  EXPECT_TRUE(s.optimised) << s.status;
  EXPECT_NEAR(s.start[1], 10.72 / 19.52, 1e-8);
  EXPECT_NEAR(s.positions[1][1], 1.2 * s.start[1] - 0.2, 1e-12);
  EXPECT_NEAR(s.positions[2][1], s.start[1], 1e-12);
  EXPECT_DOUBLE_EQ(s.startBefore[1], 0.5);  // plain: equidistant on the first side
  EXPECT_LT(s.evennessAfter, s.evennessBefore);
}

TEST(ChainProblem, GradientMatchesFiniteDifferences) {
  const PiecewiseLinearMap f({{0, 0}, {0.3, 0.2}, {0.7, 0.75}, {1, 1}});
  const PiecewiseLinearMap h({{0, 0}, {0.45, 0.6}, {1, 1}});
  const auto g = f.inverted();
  auto problem = chainOf({&f, &h, &g}, 5);
  problem.boundaries[2].weight = 2.5;
  const std::vector<double> start{0.0, 0.21, 0.43, 0.77, 1.0};  // away from every kink
  std::vector<double> gradient;
  chainObjective(problem, start, &gradient);
  for (int j = 1; j < 4; ++j) {
    const double step = 1e-7;
    auto plus = start, minus = start;
    plus[j] += step;
    minus[j] -= step;
    const double fd = (chainObjective(problem, plus) - chainObjective(problem, minus)) / (2 * step);
    EXPECT_NEAR(gradient[j], fd, 1e-7 * std::max(1.0, std::abs(fd))) << j;
  }
}

TEST(ChainProblem, AnOriginalMemberIsKept) {
  // A T-junction on boundary 2 puts a member at 0.3 there (Fig. 3.8): it stays, the others move.
  const PiecewiseLinearMap f({{0, 0}, {0.5, 0.35}, {1, 1}});
  auto problem = chainOf({&f, &f, &f}, 6);
  problem.originals.push_back({2, 0.3});
  const auto s = solveChain(problem);
  int fixedInside = 0;
  for (size_t j = 1; j + 1 < s.fixed.size(); ++j) fixedInside += s.fixed[j];
  ASSERT_EQ(fixedInside, 1);
  bool kept = false;
  for (double p : s.positions[2]) kept = kept || std::abs(p - 0.3) < 1e-12;
  EXPECT_TRUE(kept);
  EXPECT_LE(s.evennessAfter, s.evennessBefore);
  // More originals than members cannot be placed.
  problem.members = 2;
  EXPECT_THROW(solveChain(problem), InvalidInput);
}

TEST(ChainProblem, MinimumSpacingHoldsOnEveryBoundary) {
  // A strongly compressing map would crowd the members on boundary 1; a footprint of 0.15 there
  // pushes them apart at the cost of evenness elsewhere.
  const PiecewiseLinearMap f({{0, 0}, {0.6, 0.2}, {1, 1}});
  auto problem = chainOf({&f}, 5);
  problem.boundaries[1].minGap = 0.15;
  const auto s = solveChain(problem);
  for (size_t i = 0; i < s.positions.size(); ++i)
    for (size_t j = 1; j < s.positions[i].size(); ++j)
      EXPECT_GE(s.positions[i][j] - s.positions[i][j - 1], problem.boundaries[i].minGap - 1e-9)
          << i << " " << j;
}

TEST(ChainProblem, AClosedRangeGetsNoFreeMember) {
  // A neighbour across a T-junction has put its members at 0.2 and 0.5 on boundary 1 and owns
  // [0, 0.5] there (Fig. 3.8): no member of ours may be added inside. F = 0.625 x up to the kink
  // (0.8, 0.5), 2.5 x - 1.5 after it; pulled back, the originals lie at 0.32 and 0.8 on boundary 0,
  // and both free members (6 - 4 fixed) go into the one open gap (0.8, 1). There F is affine, so
  // the squared gaps on both boundaries are least with the free members at thirds of the gap.
  const PiecewiseLinearMap f({{0, 0}, {0.8, 0.5}, {1, 1}});
  auto problem = chainOf({&f}, 6);
  problem.originals = {{1, 0.2}, {1, 0.5}};
  problem.closed = {{1, 0.0, 0.5}};
  std::vector<bool> closedGaps;
  const auto fixed = fixedStarts(problem, &closedGaps);
  ASSERT_EQ(fixed.size(), 4u);
  EXPECT_NEAR(fixed[1], 0.32, 1e-15);
  EXPECT_NEAR(fixed[2], 0.8, 1e-15);
  EXPECT_EQ(closedGaps, (std::vector<bool>{true, true, false}));
  std::vector<bool> isFixed;
  const auto start = plainStart(problem, &isFixed);
  ASSERT_EQ(start.size(), 6u);
  EXPECT_EQ(isFixed, (std::vector<bool>{true, true, true, false, false, true}));
  EXPECT_NEAR(start[3], 0.8 + 0.2 / 3, 1e-15);
  EXPECT_NEAR(start[4], 0.8 + 0.4 / 3, 1e-15);
  const auto s = solveChain(problem);
  EXPECT_NEAR(s.start[3], 0.8 + 0.2 / 3, 1e-7);
  EXPECT_NEAR(s.start[4], 0.8 + 0.4 / 3, 1e-7);
  int insideClosed = 0;
  for (double t : s.positions[1]) insideClosed += t > 1e-12 && t < 0.5 - 1e-12;
  EXPECT_EQ(insideClosed, 1);  // the original at 0.2 alone
  EXPECT_DOUBLE_EQ(s.positions[1][1], 0.2);
  EXPECT_DOUBLE_EQ(s.positions[1][2], 0.5);
  // Free members but every gap closed, or a range the wrong way round: bad input.
  problem.closed = {{1, 0.0, 1.0}};
  problem.originals = {{1, 0.5}};
  problem.members = 4;
  EXPECT_THROW(plainStart(problem), InvalidInput);
  problem.closed = {{1, 0.6, 0.4}};
  EXPECT_THROW(plainStart(problem), InvalidInput);
}

TEST(ChainProblem, AFootprintTooLargeForItsBoundaryIsCappedAtEqualSpacing) {
  // Two gaps of at least 0.6 on boundary 1 cannot fit in [0, 1]: the footprint is capped at the
  // equal spacing 0.5 there, which F (slopes 0.4 then 1.6, kink at (0.5, 0.2)) meets at one
  // start only, F(t) = 1.6 t - 0.6 = 0.5: t = 0.6875. Evenness improves on the plain t = 0.5:
  // J = t^2 + (1 - t)^2 + F^2 + (1 - F)^2 goes from 1.18 to 1.0703125.
  const PiecewiseLinearMap f({{0, 0}, {0.5, 0.2}, {1, 1}});
  auto problem = chainOf({&f}, 3);
  problem.boundaries[1].minGap = 0.6;
  const auto s = solveChain(problem);
  EXPECT_TRUE(s.optimised) << s.status;
  EXPECT_NE(s.status.find("capped"), std::string::npos) << s.status;
  EXPECT_NEAR(s.start[1], 0.6875, 1e-7) << s.status;
  EXPECT_NEAR(s.positions[1][1], 0.5, 1e-7);
  EXPECT_NEAR(s.evennessBefore, 1.18, 1e-12);
  EXPECT_NEAR(s.evennessAfter, 1.0703125, 1e-6);
}

TEST(ChainProblem, RejectsBadProblems) {
  const PiecewiseLinearMap identity;
  auto problem = chainOf({&identity}, 4);
  problem.boundaries.pop_back();
  EXPECT_THROW(solveChain(problem), InvalidInput);
  problem = chainOf({&identity}, 1);
  EXPECT_THROW(solveChain(problem), InvalidInput);
  problem = chainOf({nullptr}, 4);
  EXPECT_THROW(solveChain(problem), InvalidInput);
}

}  // namespace
}  // namespace egg::propagation
