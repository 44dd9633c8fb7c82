#include "core/egg/member_trace.hpp"

#include "core/egg/patch_maps.hpp"
#include "core/egg/solve_patch.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg {
namespace {

GridMember innerMember(Family family, double x1, double guess) {
  GridMember m;
  m.family = family;
  m.index = 1;
  m.x1 = x1;
  m.x2 = guess;
  return m;
}

// Root of g on [a, b] by bisection (g changes sign there).
template <class G>
double bisect(const G& g, double a, double b) {
  double ga = g(a);
  for (int k = 0; k < 200 && b - a > 1e-16; ++k) {
    const double m = 0.5 * (a + b), gm = g(m);
    if ((gm > 0) == (ga > 0))
      a = m, ga = gm;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

// A trapezoid patch on a plane, a planar quad 0.15 rad off its corner angle, and the member from
// x1 = 0.37: on a plane the geodesic is the straight segment, so the matched x2 solves
// |start(x1) - end(x2)| = planar distance(x1, x2), whose root bisection finds in closed form.
struct PlaneTrapezoid {
  TriMesh mesh = samples::generateSample("plane", {{"length", 10.0}, {"width", 10.0}}, 0.8);
  std::array<Eigen::Vector3d, 4> c{
      Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {2, 3, 0}, {-2.5, 2.5, 0}};
  Patch patch = makePatch(mesh, c);
  geodesic::DistanceSolver solver{patch.mesh};
  PlanarQuad quad = *planarQuad(patch.sideLengths, patch.innerAngles[0] - 0.15);
  double x1 = 0.37;

  double mismatch(double x2) const {
    const Eigen::Vector3d start = c[0] + x1 * (c[3] - c[0]), end = c[1] + x2 * (c[2] - c[1]);
    return (end - start).norm() - planarDistance(quad, Family::U, x1, x2);
  }
  double root() const {
    return bisect([this](double x2) { return mismatch(x2); }, 0.0, 1.0);
  }
};

double polylineLength(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (size_t k = 1; k < points.size(); ++k) length += (points[k] - points[k - 1]).norm();
  return length;
}

TEST(MemberTrace, PlaneTrapezoidMatchesTheAnalyticRoot) {
  const PlaneTrapezoid t;  // the guess below is 4 cm off the root
  ASSERT_LT(t.mismatch(0.0) * t.mismatch(1.0), 0.0);
  const double root = t.root();
  GridMember m = innerMember(Family::U, t.x1, root + 0.04 / 6.0);
  std::atomic<int> propagations{0};
  traceInnerMember(t.patch, t.solver, t.quad, m, GridOptions{}, propagations);
  EXPECT_NEAR(m.x2, root, 1e-12);
  EXPECT_LE(propagations.load(), 2);  // the guess's strip, at most one retrace
  const double length = polylineLength(m.spatial);
  EXPECT_NEAR(length, planarDistance(t.quad, Family::U, t.x1, m.x2), 1e-10 * length);
  // Straight, from start(x1) to end(x2), every normal +z.
  const Eigen::Vector3d a = t.c[0] + t.x1 * (t.c[3] - t.c[0]),
                        b = t.c[1] + m.x2 * (t.c[2] - t.c[1]);
  EXPECT_NEAR((m.spatial.front() - a).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.spatial.back() - b).norm(), 0.0, 1e-9);
  for (const auto& p : m.spatial)
    EXPECT_NEAR((p - a).cross(b - a).norm() / (b - a).norm(), 0.0, 1e-9);
  ASSERT_EQ(m.normals.size(), m.spatial.size());
  for (const auto& n : m.normals) EXPECT_NEAR(std::abs(n.z()), 1.0, 1e-12);
}

TEST(MemberTrace, FallbackBracketingMatchesTooWhenTheStripIsNotEnough) {
  // One strip trace only and a guess 1.2 m off: the root lies on another boundary edge, so the
  // member is matched by bracketing with exact fields instead, to the same root.
  const PlaneTrapezoid t;
  const double root = t.root();
  GridMember m = innerMember(Family::U, t.x1, root - 0.2);
  GridOptions options;
  options.maxStripTraces = 1;
  std::atomic<int> propagations{0};
  traceInnerMember(t.patch, t.solver, t.quad, m, options, propagations);
  EXPECT_GT(propagations.load(), 2);
  EXPECT_NEAR(m.x2, root, 1e-8);
  const double length = polylineLength(m.spatial);
  EXPECT_NEAR(length, planarDistance(t.quad, Family::U, t.x1, m.x2), 1e-10 * length);
}

TEST(MemberTrace, SphereMemberIsTheShortestGeodesicOfThePlanarLength) {
  // On a curved patch: the matched member's polyline is as long as its planar segment (criterion
  // i, to 1e-10) and as long as the exact geodesic distance between its ends, which an
  // independent propagation measures.
  const TriMesh mesh = samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 7.0}}, 0.6);
  std::array<Eigen::Vector3d, 4> corners;
  const double xy[4][2] = {{-4, -4}, {4.2, -3.8}, {4, 4}, {-3.8, 4.2}};
  for (int k = 0; k < 4; ++k)
    corners[k] = {xy[k][0], xy[k][1], std::sqrt(100.0 - xy[k][0] * xy[k][0] - xy[k][1] * xy[k][1])};
  const Patch patch = makePatch(mesh, corners);
  const geodesic::DistanceSolver solver(patch.mesh);
  const auto quad = *planarQuad(patch.sideLengths,
                                patch.innerAngles[0] - 0.6);  // inside the lower feasible interval
  for (Family family : {Family::U, Family::V}) {
    const double x1 = 0.41;
    const SurfacePoint start = familyBoundaryPoint(patch, family, false, x1);
    // Guess: the sign change of the mismatch on 41 samples of the end side (one field).
    std::vector<SurfacePoint> ends;
    for (int k = 0; k <= 40; ++k)
      ends.push_back(familyBoundaryPoint(patch, family, true, k / 40.0));
    const auto field = solver.distances(start, ends);
    double guess = -1.0;
    for (int k = 0; k < 40 && guess < 0; ++k) {
      const double g0 = field.targetDistances[k] - planarDistance(quad, family, x1, k / 40.0);
      const double g1 =
          field.targetDistances[k + 1] - planarDistance(quad, family, x1, (k + 1) / 40.0);
      if ((g0 > 0) != (g1 > 0)) guess = (k + 0.5) / 40.0;
    }
    ASSERT_GE(guess, 0.0);
    GridMember m = innerMember(family, x1, guess);
    std::atomic<int> propagations{0};
    traceInnerMember(patch, solver, quad, m, GridOptions{}, propagations);
    const double length = polylineLength(m.spatial);
    EXPECT_NEAR(length, planarDistance(quad, family, x1, m.x2), 1e-10 * length);
    EXPECT_NEAR(length, solver.distance(start, familyBoundaryPoint(patch, family, true, m.x2)),
                1e-9 * length);
    EXPECT_NEAR(
        (m.spatial.back() - position(patch.mesh, familyBoundaryPoint(patch, family, true, m.x2)))
            .norm(),
        0.0, 1e-9);
    EXPECT_LE(propagations.load(), 4);
  }
}

TEST(MemberTrace, BenchBumpMembersAreMatchedInTheirStrips) {
  // The 2k-vertex bench bump (egg bench grid): one u member's traced geodesic bends at a vertex
  // whose path point carried 4e-13 of rounding in its weights, read as an edge crossing, so no
  // strip could be unfolded and the member fell back to bracketing with full fields (at 3.4k
  // vertices a v member retraced to the same strip end again and again: the trace goes round a
  // vertex ~2e-5 m longer than its strip polyline). Both are matched in their strips now.
  const double density = (2000 - 141) / 0.861, edge = std::sqrt(50.0 / (0.866 * density));
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, edge);
  EggOptions options;
  options.members.lamellaWidthM = 0.1;
  options.members.spacingFactor = 6.0;
  const auto r =
      solveEgg(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, options);
  int inner = 0, bracketed = 0;
  for (const auto* family : {&r.grid.u, &r.grid.v})
    for (const auto& m : *family) {
      if (m.boundary) continue;
      ++inner;
      bracketed += m.bracketed ? 1 : 0;
      EXPECT_NEAR(polylineLength(m.spatial), m.planarLength, 1e-10 * m.planarLength) << m.index;
    }
  EXPECT_EQ(inner, 10);
  EXPECT_EQ(bracketed, 0);
  EXPECT_LE(r.grid.propagations,
            2 * inner);  // directed traces only: the guess and one retrace each
}

}  // namespace
}  // namespace egg
