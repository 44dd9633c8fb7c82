// The planar pieces of the window propagation with known answers: the cone of directions a
// shortest path may leave a pseudo-source in, where its rays cross the opposite edge, and the
// paths bent round a window's end or at the vertex on its boundary ray.
#include "core/geodesic/window_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

namespace egg::geodesic::detail {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WindowGeometry, InteriorSaddleAllowsTheExcessConeOppositeTheIncomingDirection) {
  // Angle sum 2 pi + 0.2, path arriving from fan angle 0: allowed [pi, pi + 0.2].
  double lo = 0, hi = 0;
  ASSERT_TRUE(allowedFanInterval(3.0, 3.5, 0.0, 2 * kPi + 0.2, false, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, kPi);
  EXPECT_DOUBLE_EQ(hi, kPi + 0.2);
  EXPECT_FALSE(allowedFanInterval(0.5, 2.0, 0.0, 2 * kPi + 0.2, false, 0.0, lo, hi));
  // The cone wraps around the angle sum: arriving from 4.0, allowed [4 + pi, 4 + pi + 0.2] - total.
  const double total = 2 * kPi + 0.2;
  ASSERT_TRUE(allowedFanInterval(0.0, 1.5, 4.0, total, false, 0.0, lo, hi));
  EXPECT_NEAR(lo, 4.0 + kPi - total, 1e-15);
  EXPECT_NEAR(hi, 4.0 + kPi + 0.2 - total, 1e-15);
}

TEST(WindowGeometry, ReflexBoundaryCornerAllowsBothSidesBeyondPi) {
  // Angle sum 1.5 pi, arriving from 0.25 pi: nothing on the near side (it would need angles below
  // -0.75 pi), and [1.25 pi, 1.5 pi] on the far side.
  double lo = 0, hi = 0;
  ASSERT_TRUE(allowedFanInterval(1.0 * kPi, 1.5 * kPi, 0.25 * kPi, 1.5 * kPi, true, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, 1.25 * kPi);
  EXPECT_DOUBLE_EQ(hi, 1.5 * kPi);
  // Arriving from 1.25 pi the allowed side is [0, 0.25 pi].
  ASSERT_TRUE(allowedFanInterval(0.0, 0.5 * kPi, 1.25 * kPi, 1.5 * kPi, true, 0.0, lo, hi));
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_NEAR(hi, 0.25 * kPi, 1e-15);
}

TEST(WindowGeometry, ConeRaysCrossTheOppositeEdgeWhereTheyShould) {
  // v at (0.5, 0.5) above the edge from B = (0,0) to C = (1,0): the corner at v is 90 degrees and
  // the ray turned 45 degrees from v->B hits the middle; 0 and 90 degrees hit B and C.
  const double corner = kPi / 2;
  const auto [b, c] = coneCrossings(0.5, 0.5, 1.0, corner, 0.0, corner);
  EXPECT_DOUBLE_EQ(b, 0.0);
  EXPECT_DOUBLE_EQ(c, 1.0);
  const auto [m0, m1] = coneCrossings(0.5, 0.5, 1.0, corner, kPi / 4, kPi / 4);
  EXPECT_NEAR(m0, 0.5, 1e-15);
  EXPECT_NEAR(m1, 0.5, 1e-15);
  // 30 degrees from v->B: x = 0.5 - 0.5 tan(15 deg).
  const auto [x, unused] = coneCrossings(0.5, 0.5, 1.0, corner, kPi / 6, corner);
  EXPECT_NEAR(x, 0.5 - 0.5 * std::tan(kPi / 12), 1e-14);
  (void)unused;
  // A needle face keeps the whole edge.
  const auto [n0, n1] = coneCrossings(0.5, 1e-12, 1.0, kPi - 1e-10, 0.1, 0.2);
  EXPECT_EQ(n0, 0.0);
  EXPECT_EQ(n1, 1.0);
}

// A window over [b0, b1] seen from (sx, sy) at sigma, with vertex `endVertex1` on the ray of b1.
Window windowWithEndVertex(double b0, double b1, double sx, double sy, double sigma,
                           int endVertex1) {
  Window w;
  w.b0 = b0;
  w.b1 = b1;
  w.sx = sx;
  w.sy = sy;
  w.sigma = sigma;
  w.endVertex[1] = endVertex1;
  return w;
}

// A window on an edge of length 1, seen from (0, -1) at sigma 0.5, covering [0.2, 0.4]; its end b1
// has the vertex X on its boundary ray, 0.5 from the source image.
struct BentCase {
  Window w = windowWithEndVertex(0.2, 0.4, 0.0, -1.0, 0.5, 7);
  Eigen::Vector2d s{0.0, -1.0}, u, x;
  BentCase() {
    u = (Eigen::Vector2d(0.4, 0.0) - s).normalized();
    x = s + 0.5 * u;
  }
  // A point `length` beyond X, turned clockwise (away from the window, past b1) by `angle`.
  Eigen::Vector2d beyond(double angle, double length) const {
    const double cosine = std::cos(angle), sine = std::sin(angle);
    const Eigen::Vector2d d(cosine * u.x() + sine * u.y(), -sine * u.x() + cosine * u.y());
    return x + length * d;
  }
};

TEST(WindowGeometry, ShadowOfASkippedSaddleIsReachedThroughTheSaddle) {
  const BentCase c;
  const double excess = 4e-4, tolerance = 7e-4;
  const BendVertex skipped{1.0, excess + tolerance};  // d(X) = sigma + 0.5: reached along this ray
  // Within the excess, and within excess + tolerance: exactly d(X) + |X p|.
  bool atVertex = false;
  for (const double angle : {0.5 * excess, excess + 0.9 * tolerance}) {
    const Eigen::Vector2d p = c.beyond(angle, 0.8);
    EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 1.0, &skipped, atVertex), 1.8, 1e-14) << angle;
    EXPECT_TRUE(atVertex);
  }
  // Wider than that the segment might cross other vertices: bent round the window's end instead,
  // sigma + |s end| + |end p|, which is longer.
  const Eigen::Vector2d wide = c.beyond(excess + 1.2 * tolerance, 0.8);
  const Eigen::Vector2d end(0.4, 0.0);
  const double roundTheEnd = 0.5 + (end - c.s).norm() + (wide - end).norm();
  EXPECT_NEAR(pathBentAt(c.w, 1, wide.x(), wide.y(), 1.0, &skipped, atVertex), roundTheEnd, 1e-14);
  EXPECT_FALSE(atVertex);
  EXPECT_GT(roundTheEnd, 1.8);
  // No vertex on the ray, or a pseudo-source there (its own windows cover its shadow): round the
  // end.
  const Eigen::Vector2d p = c.beyond(0.5 * excess, 0.8);
  const double pRoundTheEnd = 0.5 + (end - c.s).norm() + (p - end).norm();
  EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 1.0, nullptr, atVertex), pRoundTheEnd, 1e-14);
  EXPECT_FALSE(atVertex);
  const BendVertex pseudo{1.0, 0.0};  // a pseudo-source's shadow cone is 0
  EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 1.0, &pseudo, atVertex), pRoundTheEnd, 1e-14);
  EXPECT_FALSE(atVertex);
  // Not if the segment from X would cross this edge past its end (beyond a vertex of the face):
  // the edge ends 1e-5 past the window, the segment crosses it ~1e-4 past.
  EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 0.40001, &skipped, atVertex), pRoundTheEnd, 1e-14);
  EXPECT_FALSE(atVertex);
  EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 0.41, &skipped, atVertex), 1.8, 1e-14);
  EXPECT_TRUE(atVertex);
  // Round the end overestimates a point just past the edge by ~(t e)^2 / 2m; through X it is exact.
  EXPECT_GT(pRoundTheEnd - 1.8, 1e-9);
}

TEST(WindowGeometry, BendingAtAVertexReachedElsewhereBendsShortOfItOnTheRay) {
  // d(X) = 0.9 < sigma + 0.5: a shorter path reached X. The bend is at the point 0.4 along the ray
  // (sigma + 0.4 = d(X)): sigma + 0.4 + |that point - p|, the path the tracer follows.
  const BentCase c;
  const BendVertex reachedElsewhere{0.9, 4e-4 + 7e-4};
  const Eigen::Vector2d p = c.beyond(2e-4, 0.8);
  const Eigen::Vector2d bend = c.s + 0.4 * c.u;
  bool atVertex = false;
  EXPECT_NEAR(pathBentAt(c.w, 1, p.x(), p.y(), 1.0, &reachedElsewhere, atVertex),
              0.9 + (p - bend).norm(), 1e-14);
  EXPECT_TRUE(atVertex);
  double bx = 0, by = 0;
  bendPoint(c.w, 1, 0.9, bx, by);
  EXPECT_NEAR((Eigen::Vector2d(bx, by) - bend).norm(), 0.0, 1e-15);
}

TEST(WindowGeometry, AnEndAtAnEdgeEndpointBendsThereInAnyDirection) {
  // The window reaches the edge's to-vertex B = (1, 0): B -> p is an edge of the face, a real path,
  // whatever the angle and whatever B is.
  const Window w = windowWithEndVertex(0.5, 1.0, 0.3, -2.0, 0.25, 3);
  const double toB = std::hypot(0.7, 2.0);
  const BendVertex b{0.25 + toB, 0.0};  // a convex vertex, even
  bool atVertex = true;
  EXPECT_NEAR(pathBentAt(w, 1, 1.4, 0.9, 1.0, &b, atVertex), 0.25 + toB + std::hypot(0.4, 0.9),
              1e-14);
  EXPECT_FALSE(atVertex);  // round the end, which is B
}

TEST(WindowGeometry, EndVerticesFollowTheEdgeEndpointsAndAreLostWhereAnEndMoves) {
  MeshTables::Halfedge e{};
  e.length = 2.0;
  e.fromVertex = 10;
  e.toVertex = 11;
  Window w;
  w.endVertex[0] = 5;  // inherited from the parent
  w.endVertex[1] = 6;
  w.b0 = 0.3;
  w.b1 = 2.0 - 1e-12;  // at the endpoint up to rounding
  markEndVertices(w, 0.3, 1.5, e);
  EXPECT_EQ(w.endVertex[0], 5);   // unchanged interior end keeps the parent's ray vertex
  EXPECT_EQ(w.endVertex[1], 11);  // at the to-vertex
  w.b0 = 0.0;
  w.b1 = 1.2;
  markEndVertices(w, 0.0, 1.7, e);
  EXPECT_EQ(w.endVertex[0], 10);  // at the from-vertex
  EXPECT_EQ(w.endVertex[1], -1);  // trimmed: no vertex on the new end's ray
}

Window edgeWindow(double sx, double sy, double sigma, double b0, double b1) {
  Window w;
  w.halfedge = 0;
  w.sx = sx;
  w.sy = sy;
  w.sigma = sigma;
  w.b0 = b0;
  w.b1 = b1;
  return w;
}

TEST(WindowGeometry, TrimPairCutsEachWindowWhereTheOtherIsShorter) {
  // Mirror images (0,-1) and (2,-1) over the edge [0, 2]: equally far at x = 1, each shorter on
  // its own side.
  Window w = edgeWindow(0.0, -1.0, 0.0, 0.0, 2.0), o = edgeWindow(2.0, -1.0, 0.0, 0.0, 2.0);
  bool wLeft, oLeft;
  trimPair(w, o, wLeft, oLeft);
  ASSERT_TRUE(wLeft && oLeft);
  EXPECT_NEAR(w.b0, 0.0, 1e-15);
  EXPECT_NEAR(w.b1, 1.0, 1e-12);
  EXPECT_NEAR(o.b0, 1.0, 1e-12);
  EXPECT_NEAR(o.b1, 2.0, 1e-15);
  // The same cuts as trimming one way, then the other against the untrimmed first.
  Window w1 = edgeWindow(0.0, -1.0, 0.0, 0.0, 2.0), o1 = edgeWindow(2.0, -1.0, 0.0, 0.0, 2.0);
  const Window w1Before = w1;
  ASSERT_TRUE(trimAgainst(w1, o1));
  ASSERT_TRUE(trimAgainst(o1, w1Before));
  EXPECT_EQ(w1.b1, w.b1);
  EXPECT_EQ(o1.b0, o.b0);
}

TEST(WindowGeometry, TrimPairDropsAWindowShorterNowhereAndLeavesTheOtherWhole) {
  // o's image (1,-0.5) is nearer every point of the edge than w's (1,-1), and o covers w.
  Window w = edgeWindow(1.0, -1.0, 0.0, 0.5, 1.5), o = edgeWindow(1.0, -0.5, 0.0, 0.0, 2.0);
  bool wLeft, oLeft;
  trimPair(w, o, wLeft, oLeft);
  EXPECT_FALSE(wLeft);
  EXPECT_TRUE(oLeft);
  EXPECT_EQ(o.b0, 0.0);
  EXPECT_EQ(o.b1, 2.0);
  // With sigma 0.6 on o, w is shorter everywhere (0.6 + sqrt(d^2 + 0.25) > sqrt(d^2 + 1)): o goes.
  Window w2 = edgeWindow(1.0, -1.0, 0.0, 0.0, 2.0), o2 = edgeWindow(1.0, -0.5, 0.6, 0.5, 1.5);
  trimPair(w2, o2, wLeft, oLeft);
  EXPECT_TRUE(wLeft);
  EXPECT_FALSE(oLeft);
  EXPECT_EQ(w2.b0, 0.0);
  EXPECT_EQ(w2.b1, 2.0);
  // Disjoint windows are left alone.
  Window a = edgeWindow(0.0, -1.0, 0.0, 0.0, 0.5), b = edgeWindow(2.0, -1.0, 0.0, 0.6, 2.0);
  trimPair(a, b, wLeft, oLeft);
  EXPECT_TRUE(wLeft && oLeft);
  EXPECT_EQ(a.b1, 0.5);
  EXPECT_EQ(b.b0, 0.6);
}

// propagateWindow waits with the second square root of a bend round an end until sigma + |s - end|
// + py, with a margin of 1e-12, is below the vertex's distance: the bent length computed in full
// must never fall below that bound, or a relaxation that would have been taken is skipped. Random
// windows and points, near-degenerate ones included (the point almost on the edge or straight
// above the end, the end almost under the source image, lengths over twelve orders of magnitude).
TEST(WindowGeometry, ABendRoundAnEndIsNeverBelowTheBoundThatDefersIt) {
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int nearDegenerate = 0;
  for (int i = 0; i < 200000; ++i) {
    const double scale = std::pow(10.0, -6.0 + 12.0 * unit(random));
    Window w;
    w.b0 = scale * unit(random);
    w.b1 = w.b0 + scale * unit(random);
    w.sx = i % 3 == 0 ? w.b1 * (1.0 + 1e-15 * unit(random)) : scale * (4.0 * unit(random) - 2.0);
    w.sy = -scale * (i % 5 == 0 ? 1e-9 * unit(random) : unit(random)) - 1e-300;
    w.sigma = i % 2 ? 0.0 : scale * 10.0 * unit(random);
    const int side = i % 2;
    const double end = side ? w.b1 : w.b0;
    // One in four straight above the end, where |end - p| = py and the bound is tight.
    const double px =
        i % 4 == 1 ? end + scale * 1e-9 * unit(random) : scale * (4.0 * unit(random) - 2.0);
    const double py = scale * (i % 7 == 0 ? 1e-10 * unit(random) : unit(random));
    bool atVertex = true;
    const double bent = pathBentAt(w, side, px, py, 4.0 * scale, nullptr, atVertex);
    EXPECT_FALSE(atVertex);
    const double bound = (w.sigma + distanceToEnd(w, side) + py) * (1.0 - 1e-12);
    ASSERT_GE(bent, bound) << "window " << i;
    if (bent < bound * (1.0 + 2e-12)) ++nearDegenerate;
  }
  EXPECT_GT(nearDegenerate, 1000);  // the bound is tight there: the margin is what is tested
}

// copyJustWritten must copy every field (a field added to Window and left out would be lost).
TEST(WindowGeometry, CopyJustWrittenCopiesEveryField) {
  Window from;
  from.halfedge = 7;
  from.parent = Window::fromVertex(11);
  from.b0 = 0.125;
  from.b1 = 0.75;
  from.sx = -1.5;
  from.sy = -2.25;
  from.sigma = 3.5;
  from.endVertex[0] = 13;
  from.endVertex[1] = 17;
  Window to;
  copyJustWritten(to, from);
  EXPECT_EQ(std::memcmp(&to, &from, sizeof(Window)), 0);
}

// distanceGapBound and rayTurnBoundSquared (DistanceSolverOptions::imageMergeTolerance) are bounds:
// never below the gap and the ray angle sampled densely over the interval, for random image pairs,
// wide intervals (where the curvature term matters) and narrow ones. Known answers: one image with
// its sigma raised by c has the gap c (up to the curvature term, W^2 / 8 of it) and no turn; an
// image on the edge's line with its foot inside has a kink and no bound.
Window imageAt(double sx, double sy, double sigma) {
  Window w;
  w.sx = sx;
  w.sy = sy;
  w.sigma = sigma;
  return w;
}

TEST(WindowGeometry, GapAndTurnBoundsAreNeverBelowTheSampledValues) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> x(-1.0, 2.0), y(-2.0, -0.01), sigma(0.0, 0.5),
      unit(0.0, 1.0);
  int tight = 0;
  for (int k = 0; k < 4000; ++k) {
    const Window a = imageAt(x(rng), y(rng), sigma(rng));
    // Half the pairs are near images: b a small rotation of a about a point on the edge.
    Window b = imageAt(x(rng), y(rng), sigma(rng));
    if (k % 2) {
      const double turn = 1e-3 * unit(rng), px = unit(rng), c = std::cos(turn), s = std::sin(turn);
      b = imageAt(px + c * (a.sx - px) - s * a.sy, s * (a.sx - px) + c * a.sy, a.sigma);
    }
    const double x0 = unit(rng), x1 = x0 + (k % 4 < 2 ? 1.0 : 1e-3) * unit(rng);
    double gap = 0.0, sine = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double t = x0 + (x1 - x0) * i / 400.0;
      const double ra = std::hypot(t - a.sx, a.sy), rb = std::hypot(t - b.sx, b.sy);
      gap = std::max(gap, std::abs(a.sigma + ra - b.sigma - rb));
      sine = std::max(sine, std::abs((t - a.sx) * b.sy - a.sy * (t - b.sx)) / (ra * rb));
    }
    const double gapBound = distanceGapBound(a, b, x0, x1),
                 turnBound = std::sqrt(rayTurnBoundSquared(a, b));
    ASSERT_GE(gapBound, gap * (1.0 - 1e-12) - 1e-15) << k;
    ASSERT_GE(turnBound, sine * (1.0 - 1e-12) - 1e-15) << k;
    if (gapBound <= 1.5 * gap + 1e-12) ++tight;
  }
  EXPECT_GT(tight, 1000);  // a bound, but not a loose one: within 1.5x of the gap on many pairs
}

TEST(WindowGeometry, GapBoundKnownAnswers) {
  const Window a = imageAt(0.3, -1.0, 0.2), raised = imageAt(0.3, -1.0, 0.2 + 1e-6);
  EXPECT_NEAR(distanceGapBound(a, raised, 0.4, 0.401), 1e-6, 1e-10);  // + the curvature term, 4e-11
  EXPECT_DOUBLE_EQ(rayTurnBoundSquared(a, raised), 0.0);
  const Window onTheLine = imageAt(0.5, 0.0, 0.0);
  EXPECT_EQ(distanceGapBound(onTheLine, a, 0.0, 1.0), kInfinity);
  // Merging: the union takes the wider window's image, only within both bounds.
  Window w = imageAt(0.3, -1.0, 0.2), wider = imageAt(0.3, -1.0, 0.2 + 1e-7);
  w.b0 = 0.40;
  w.b1 = 0.41;
  wider.b0 = 0.41;
  wider.b1 = 0.9;
  double b0In = w.b0, b1In = w.b1;
  Window merged = w;
  ASSERT_TRUE(absorbNearImage(merged, wider, 2e-6, 1.0, b0In, b1In));
  EXPECT_EQ(merged.sigma, wider.sigma);
  EXPECT_EQ(merged.b0, 0.40);
  EXPECT_EQ(merged.b1, 0.9);
  // A sliver whose function meets a far image's where they touch: the gap is within the
  // tolerance, but the rays are 76 degrees apart, so downstream the two part ways (the turn test).
  Window sliver = imageAt(0.3, -1.0, 0.2);
  sliver.b0 = 0.41 - 1e-9;
  sliver.b1 = 0.41;
  Window far = imageAt(5.0, -1.0, 0.2 + std::hypot(0.11, 1.0) - std::hypot(0.41 - 5.0, 1.0));
  far.b0 = 0.41;
  far.b1 = 0.9;
  ASSERT_LT(distanceGapBound(sliver, far, sliver.b0, sliver.b1), 2e-6);
  Window unchanged = sliver;
  EXPECT_FALSE(absorbNearImage(unchanged, far, 2e-6, 1.0, b0In, b1In));
  w = sliver;
  EXPECT_EQ(unchanged.sx, w.sx);
  EXPECT_EQ(unchanged.b1, w.b1);
}

}  // namespace
}  // namespace egg::geodesic::detail
