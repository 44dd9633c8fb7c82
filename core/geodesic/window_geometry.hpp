#pragma once
// Internal: the planar geometry of windows shared by the propagation (window_propagation.cpp):
// frame changes between the unfolded edge frames, ray crossings, paired square roots, and the
// trimming of a window against another on the same edge. Inline because the propagation calls
// them for every one of the ~200k windows of a 4k-vertex field.
#include "core/geodesic/window_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace egg::geodesic::detail {

// Rotates frame coordinates into the frame of an edge of the same face: origin `o`, x along the
// unit direction (ux, uy), y = cross(u, X - o), which puts the current face on the y < 0 side.
struct FrameChange {
  double ox, oy, ux, uy;
  void apply(double x, double y, double& nx, double& ny) const {
    const double dx = x - ox, dy = y - oy;
    nx = ux * dx + uy * dy;
    ny = ux * dy - uy * dx;
  }
};

// Where the ray from the source image (sx, sy) through (px, py) crosses y = 0.
inline double rayCrossing(double sx, double sy, double px, double py) {
  return sx + (px - sx) * (-sy) / (py - sy);
}

// Plain sqrt: std::hypot's overflow guards cost more than the rest of the inner loop.
inline double planarLength(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }

// Two planar lengths at once. With SSE2 one sqrtpd does both (IEEE square roots are correctly
// rounded, so the values are bit-identical to planarLength's); the scalar calls cannot be paired by
// the compiler because std::sqrt may set errno.
inline void planarLengths(double dx0, double dy0, double dx1, double dy1, double& l0, double& l1) {
#if defined(__SSE2__)
  const __m128d dx = _mm_set_pd(dx1, dx0), dy = _mm_set_pd(dy1, dy0);
  const __m128d r = _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)));
  l0 = _mm_cvtsd_f64(r);
  l1 = _mm_cvtsd_f64(_mm_unpackhi_pd(r, r));
#else
  l0 = planarLength(dx0, dy0);
  l1 = planarLength(dx1, dy1);
#endif
}

// x, loaded on its own. A child window is written field by field and read back a moment later by
// its pruning; where the compiler pairs the reads of b0 and b1 into one 16-byte load, that load
// spans two 8-byte stores still in the store buffer, cannot be forwarded from them and waits until
// they reach the cache: a stall on every window (measured: the commit that added this).
inline double loadAlone(const double& x) {
  double v = x;
#if defined(__GNUC__) && defined(__SSE2__)
  asm("" : "+x"(v));  // v must now sit in a register of its own: no wider load can produce it
#endif
  return v;
}
inline int loadAlone(const int& x) {
  int v = x;
#if defined(__GNUC__) && defined(__SSE2__)
  asm("" : "+r"(v));
#endif
  return v;
}

// to = from, field by field (loadAlone): `from` is a child window its creator has just written, and
// the plain struct copy's 16-byte loads stalled as prune's did.
inline void copyJustWritten(Window& to, const Window& from) {
  to.halfedge = loadAlone(from.halfedge);
  to.parent = loadAlone(from.parent);
  to.b0 = loadAlone(from.b0);
  to.b1 = loadAlone(from.b1);
  to.sx = loadAlone(from.sx);
  to.sy = loadAlone(from.sy);
  to.sigma = loadAlone(from.sigma);
  to.endVertex[0] = loadAlone(from.endVertex[0]);
  to.endVertex[1] = loadAlone(from.endVertex[1]);
}

// The directions in which a shortest path may leave a pseudo-source vertex v through one face of
// its fan, the face spanning fan angles [a0, a1] (counter-clockwise around v). A path through v is
// locally shortest only if it leaves at least pi of surface angle on each side
// (Mitchell-Mount-Papadimitriou, Lemma 3.4): seen from the direction back along the path
// (`backAngle`), interior vertices allow the cone [pi, total - pi] (modulo the angle sum `total`),
// boundary vertices the directions at least pi away on the surface side. The allowed set within
// the face is returned as one interval [lo, hi] (the hull of its pieces, a superset, so nothing
// exact is lost); false if it is empty. `tol` widens it against rounding of the angles.
inline bool allowedFanInterval(double a0, double a1, double backAngle, double total, bool boundary,
                               double tol, double& lo, double& hi) {
  constexpr double pi = std::numbers::pi;
  lo = std::numeric_limits<double>::infinity();
  hi = -std::numeric_limits<double>::infinity();
  auto include = [&](double from, double to) {
    from = std::max(from, a0);
    to = std::min(to, a1);
    if (from <= to) {
      lo = std::min(lo, from);
      hi = std::max(hi, to);
    }
  };
  if (boundary) {
    include(a0, backAngle - pi + tol);
    include(backAngle + pi - tol, a1);
  } else {
    // A cone of width total - 2 pi (the excess) opposite the incoming direction.
    const double c0 = backAngle + pi - tol, c1 = backAngle + total - pi + tol;
    for (const double shift : {-total, 0.0, total}) include(c0 + shift, c1 + shift);
  }
  return lo <= hi;
}

// The angle, counter-clockwise around the vertex at p from the start of its face fan `fan` (the
// outgoing halfedges of its faces in order), of the 3D direction `dir` lying in one of those faces;
// -1 if it lies in none. The face is the one whose corner angle equals the sum of the angles from
// `dir` to its two edges, up to rounding; the best match is taken.
inline double fanAngleOf(const MeshTables& t, const std::vector<int>& fan, const Eigen::Vector3d& p,
                         const Eigen::Vector3d& dir) {
  double cumulative = 0.0, best = -1.0, bestMismatch = std::numeric_limits<double>::infinity();
  for (int h : fan) {
    const Eigen::Vector3d ex = t.positions[t.he[h].toVertex] - p;
    const Eigen::Vector3d ey = t.positions[t.he[t.he[h].next].toVertex] - p;
    const double corner = std::atan2(t.he[h].oppositeY, t.he[h].oppositeX);
    const double ax = std::atan2(ex.cross(dir).norm(), ex.dot(dir));
    const double ay = std::atan2(ey.cross(dir).norm(), ey.dot(dir));
    const double mismatch = std::abs(ax + ay - corner);
    if (mismatch < bestMismatch) {
      bestMismatch = mismatch;
      best = cumulative + std::min(ax, corner);
    }
    cumulative += corner;
  }
  return bestMismatch < 1e-6 ? best : -1.0;
}

// Where the rays from v turned psi0 and psi1 (0 <= psi0 <= psi1 <= corner, measured from v->B)
// cross the edge B->C opposite v, as distances from B; v sits at (ox, oy), oy > 0, in the frame of
// that edge (B at the origin, C at (length, 0)) and `corner` is the face's angle at v. A needle
// face (v almost on the edge) would squeeze the whole cone into a sliver about as wide as its
// height, which the window width floor could drop: there the whole edge is returned.
inline std::pair<double, double> coneCrossings(double ox, double oy, double length, double corner,
                                               double psi0, double psi1) {
  if (oy < 1e-8 * length) return {0.0, length};
  auto crossing = [&](double psi) {
    if (psi <= 0.0) return 0.0;
    if (psi >= corner) return length;
    const double c = std::cos(psi), s = std::sin(psi);
    const double dx = s * oy - c * ox, dy = -s * ox - c * oy;  // v->B turned by psi
    if (!(dy < 0.0)) return length;
    return std::clamp(ox - oy / dy * dx, 0.0, length);
  };
  return {crossing(psi0), crossing(psi1)};
}

// The vertices on a window's boundary rays (Window::endVertex), once it is pruned and trimmed: an
// end at an endpoint of the edge `e` has that vertex on its ray; an end that pruning or trimming
// moved (from b0In, b1In) has none; any other end keeps its parent's (the same ray, unfolded).
// Within rounding of an endpoint counts as at it: pruning against the endpoint's own distance,
// found along this very ray, moves an end by a few ulps.
inline void markEndVertices(Window& w, double b0In, double b1In, const MeshTables::Halfedge& e) {
  const double near = 1e-9 * e.length;
  if (w.b0 <= near)
    w.endVertex[0] = e.fromVertex;
  else if (w.b0 != b0In)
    w.endVertex[0] = -1;
  if (w.b1 >= e.length - near)
    w.endVertex[1] = e.toVertex;
  else if (w.b1 != b1In)
    w.endVertex[1] = -1;
}

// Two windows of one source image and sigma (to `same`, a length) carry one distance function,
// sigma + |s - x|: where they touch, they are one window (addFrontWindow: why merging is exact).
inline bool sameSourceImage(const Window& a, const Window& b, double same) {
  return std::abs(a.sx - b.sx) <= same && std::abs(a.sy - b.sy) <= same &&
         std::abs(a.sigma - b.sigma) <= same;
}

// An upper bound on |f_a(x) - f_b(x)| over [x0, x1], f = sigma + |s - x| (DistanceSolverOptions::
// imageMergeTolerance). Exact at the two ends; between them the gap's deviation from the larger
// end is bounded by its curvature: f'' = sy^2 / r^3 lies between its values at the interval's
// nearest and farthest points from s, so |g''| <= m and |g| <= max(|g(x0)|, |g(x1)|) + m W^2 / 8.
// Windows that touch after trimming agree at their shared end, so for a thin one the bound is
// about its width times the angle between the two images' rays.
inline double distanceGapBound(const Window& a, const Window& b, double x0, double x1) {
  double ra0, ra1, rb0, rb1;
  planarLengths(x0 - a.sx, a.sy, x1 - a.sx, a.sy, ra0, ra1);
  planarLengths(x0 - b.sx, b.sy, x1 - b.sx, b.sy, rb0, rb1);
  const double atEnds =
      std::max(std::abs(a.sigma + ra0 - b.sigma - rb0), std::abs(a.sigma + ra1 - b.sigma - rb1));
  auto curvatureRange = [x0, x1](const Window& w, double r0, double r1, double& lo, double& hi) {
    const double nearest = (w.sx >= x0 && w.sx <= x1) ? std::abs(w.sy) : std::min(r0, r1);
    const double farthest = std::max(r0, r1);
    lo = w.sy * w.sy / (farthest * farthest * farthest);
    hi = w.sy * w.sy / (nearest * nearest * nearest);
  };
  double aLo, aHi, bLo, bHi;
  curvatureRange(a, ra0, ra1, aLo, aHi);
  curvatureRange(b, rb0, rb1, bLo, bHi);
  // An image on the edge's line with its foot inside (sy = 0): a kink, no curvature bound (0/0).
  if (!(aHi < kInfinity) || !(bHi < kInfinity)) return kInfinity;
  const double curvature = std::max(aHi - bLo, bHi - aLo);
  const double width = x1 - x0;
  return atEnds + 0.125 * curvature * width * width;
}

// w takes over the union of itself and a touching window of its source image, with that window's
// end vertices where it reaches further; b0In, b1In (markEndVertices) follow the grown ends.
inline void absorbSameImage(Window& w, const Window& other, double& b0In, double& b1In) {
  if (other.b0 < w.b0) {
    w.b0 = b0In = other.b0;
    w.endVertex[0] = other.endVertex[0];
  }
  if (other.b1 > w.b1) {
    w.b1 = b1In = other.b1;
    w.endVertex[1] = other.endVertex[1];
  }
}

// The square of an upper bound on the sine of the angle between the rays of images a and b
// through any point of the edge: |s_a - s_b| over the nearer image's distance from the edge's line
// (law of sines; no point of the edge is nearer). No square root: it is asked of every pair of
// touching windows, and most pairs fail it.
inline double rayTurnBoundSquared(const Window& a, const Window& b) {
  const double dx = a.sx - b.sx, dy = a.sy - b.sy;
  return (dx * dx + dy * dy) / std::min(a.sy * a.sy, b.sy * b.sy);
}

// As absorbSameImage for two images whose distance functions differ by at most `tolerance` x
// `length` over the narrower window's interval (distanceGapBound), with rays no more than
// sqrt(2 tolerance) apart (rayTurnBoundSquared): the union takes the wider window's image. Beyond
// the edge, a point on the narrower window's ray at distance t is then offered a value off by
// at most the gap plus t (1 - cos turn) <= 2 t x tolerance more (1 - cos = sin^2 / (1 + cos)):
// the relative error stays of the order of the tolerance however far the front runs. Without the
// turn test a narrow window close to its image (a pseudo-source's, a wide fan) would hand its whole
// fan to a far image's thin sliver: measured 0.5 relative and unreached vertices on a grid with
// boundary-corner sources. Returns false, and changes nothing, if either may be larger.
inline bool absorbNearImage(Window& w, const Window& other, double tolerance, double length,
                            double& b0In, double& b1In) {
  if (!(rayTurnBoundSquared(w, other) <= 2.0 * tolerance)) return false;
  const bool keepOther = other.b1 - other.b0 > w.b1 - w.b0;
  const Window& narrower = keepOther ? w : other;
  if (!(distanceGapBound(w, other, narrower.b0, narrower.b1) <= tolerance * length)) return false;
  if (keepOther) {
    w.sx = other.sx;
    w.sy = other.sy;
    w.sigma = other.sigma;
    w.parent = other.parent;
  }
  absorbSameImage(w, other, b0In, b1In);
  return true;
}

// The vertex a window end's boundary ray runs through (Window::endVertex): its distance so far and
// the widest bend behind it that pathBentAt takes (MeshTables::shadowCone; 0 = none).
struct BendVertex {
  double distance;
  double shadowCone;
};

// The length of a path to (px, py) (frame of w's edge, in the face w enters) whose ray from the
// source image misses the window past end `side` (0: before b0, 1: beyond b1): bent round that
// end, or at the vertex X on the end's boundary ray (`x`, nullptr if none).
//
// Bending at X is what makes skipping near-flat saddles (DistanceSolverOptions::
// saddleAngleTolerance) accurate: a skipped saddle X with excess e leaves behind it a shadow wedge
// of angle e that no window enters, and the points in it are reached only through X. Bending at
// the window's end instead - on an edge perhaps many faces past X - overestimates a point at
// distance m past that end by about (t e)^2 / 2m (t = |X end|): large for a vertex just past an
// edge, and such a vertex, if a pseudo-source, hands the error on. Measured on a 6 x 6 m patch of
// a steep bump at 3.9k vertices, side-to-side distances at tolerance 7e-4: 1.7e-4 relative error
// bending at ends, 1.1e-6 bending at X.
//
// X's place on the ray is d(X) - sigma from the source image (bendPoint); should X have been
// reached by a shorter path than this window's (rare), that is a point short of X on the ray. The
// segment from there to p is a real path while it stays in the faces the ray crossed, so X is used
// only when p lies within X's shadow cone (MeshTables::shadowCone) of the ray's direction. The
// value is then not always an upper bound: a segment passing another skipped saddle on its far
// side is shorter than any surface path, by a second-order amount (measured down to -6.7e-6
// relative on a wavy surface; exact mode, with no cones, never bends at X).
inline void bendPoint(const Window& w, int side, double distanceToX, double& bx, double& by) {
  const double end = side ? w.b1 : w.b0;
  const double ex = end - w.sx, ey = -w.sy;
  const double toEnd = planarLength(ex, ey);
  const double f = toEnd > 0.0 ? std::clamp(distanceToX - w.sigma, 0.0, toEnd) / toEnd : 1.0;
  bx = w.sx + f * ex;
  by = w.sy + f * ey;
}

// |s - end| of end `side` of w (0: b0, 1: b1).
inline double distanceToEnd(const Window& w, int side) {
  return planarLength((side ? w.b1 : w.b0) - w.sx, w.sy);
}

// Sets atVertex when the path bends at X rather than round the end.
// The segment must also cross w's own edge within it (edgeLength): a point next to a vertex of the
// face could otherwise be reached past that vertex, which no surface path does (measured before
// this check: a traced path 5.7e-5 longer than the distance on a 5.8k-vertex steep bump).
inline double pathBentAt(const Window& w, int side, double px, double py, double edgeLength,
                         const BendVertex* x, bool& atVertex) {
  const double end = side ? w.b1 : w.b0;
  atVertex = false;
  if (x && x->shadowCone > 0.0) {
    double bx, by;
    bendPoint(w, side, x->distance, bx, by);
    const double ex = end - w.sx, ey = -w.sy;
    const double vx = px - bx, vy = py - by;
    const double along = ex * vx + ey * vy, across = ex * vy - ey * vx;
    const double crossing = by < 0.0 ? rayCrossing(bx, by, px, py) : bx;
    if (along > 0.0 && across * across <= x->shadowCone * x->shadowCone * along * along &&
        crossing >= 0.0 && crossing <= edgeLength) {
      atVertex = true;
      return x->distance + planarLength(vx, vy);
    }
  }
  return w.sigma + distanceToEnd(w, side) + planarLength(px - end, py);
}

// The nearest distance a window offers on its edge, given |s - b0| and |s - b1| (its ends'
// distances from the image): at the foot of the image if it lies within, else at the nearer end.
inline double windowMinDistance(const Window& w, double toB0, double toB1) {
  return w.sx >= w.b0 && w.sx <= w.b1 ? w.sigma - w.sy : w.sigma + std::min(toB0, toB1);
}

inline double windowMinDistance(const Window& w) {
  if (w.sx >= w.b0 && w.sx <= w.b1) return w.sigma - w.sy;
  double d0, d1;
  planarLengths(w.b0 - w.sx, w.sy, w.b1 - w.sx, w.sy, d0, d1);
  return windowMinDistance(w, d0, d1);
}

// Where two windows on the same halfedge compare: g(x) = (o.sigma + |o.s - x|) - (w.sigma +
// |w.s - x|) changes sign at most twice on the edge; the roots come from squaring |o.s - x| -
// |w.s - x| = w.sigma - o.sigma twice (a quadratic), spurious ones are dropped. The overlap
// [cuts[0], cuts[count - 1]] is cut there into count - 1 pieces, and sign[i] is the sign of g on
// piece i (from its midpoint). False if the windows do not overlap.
struct OverlapPieces {
  double cuts[4];
  int count = 0;
  double sign[3];
};

inline bool comparePieces(const Window& w, const Window& o, OverlapPieces& p) {
  const double lo = std::max(w.b0, o.b0), hi = std::min(w.b1, o.b1);
  if (!(hi > lo)) return false;
  auto g = [&](double x) {
    double lengthO, lengthW;
    planarLengths(x - o.sx, o.sy, x - w.sx, w.sy, lengthO, lengthW);
    return (o.sigma + lengthO) - (w.sigma + lengthW);
  };
  p.count = 0;
  p.cuts[p.count++] = lo;
  {
    const double k = w.sigma - o.sigma;
    const double a = 2.0 * (w.sx - o.sx);
    const double c = o.sx * o.sx + o.sy * o.sy - w.sx * w.sx - w.sy * w.sy - k * k;
    const double qa = a * a - 4.0 * k * k;
    const double qb = 2.0 * a * c + 8.0 * k * k * w.sx;
    const double qc = c * c - 4.0 * k * k * (w.sx * w.sx + w.sy * w.sy);
    double roots[2];
    int nroots = 0;
    if (k == 0.0) {
      // Equal sigmas (every window of the source, or of one pseudo-source): |o.s - x| = |w.s - x|
      // is linear, a x + c = 0. Squared twice it is (a x + c)^2 = 0, whose discriminant, zero in
      // exact arithmetic, rounds below zero about half the time: the root was lost, and the one
      // piece left, of mixed sign, was cut by its midpoint's (measured: 7e-6 too long at the far
      // side of a sphere from a source on an edge, with both-way trimming).
      if (a != 0.0) roots[nroots++] = -c / a;
    } else if (std::abs(qa) > 1e-300) {
      double disc = qb * qb - 4.0 * qa * qc;
      // A double root rounded below zero: kept (a spurious cut only splits a piece in two).
      if (disc < 0.0 && disc > -1e-12 * qb * qb) disc = 0.0;
      if (disc >= 0.0) {
        const double sq = std::sqrt(disc);
        roots[nroots++] = (-qb - sq) / (2.0 * qa);
        roots[nroots++] = (-qb + sq) / (2.0 * qa);
      }
    } else if (std::abs(qb) > 1e-300) {
      roots[nroots++] = -qc / qb;
    }
    if (nroots == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
    for (int i = 0; i < nroots; ++i) {
      if (roots[i] > lo && roots[i] < hi) p.cuts[p.count++] = roots[i];
    }
  }
  p.cuts[p.count++] = hi;
  for (int i = 0; i + 1 < p.count; ++i)
    p.sign[i] = g(0.5 * (p.cuts[i] + p.cuts[i + 1]));  // two square roots each
  return true;
}

// Cuts off `x` the pieces where the other window is strictly shorter (dominated: sign < 0 when x
// is the comparePieces' w, > 0 when it is o), if they touch an end of x (a middle piece would split
// x in two, so it stays). Returns false if nothing of x is left.
inline bool cutDominated(Window& x, const OverlapPieces& p, double orientation) {
  bool dominated[3];
  bool allDominated = true;
  for (int i = 0; i + 1 < p.count; ++i) {
    dominated[i] = orientation * p.sign[i] < 0.0;
    allDominated = allDominated && dominated[i];
  }
  if (allDominated && p.cuts[0] <= x.b0 && p.cuts[p.count - 1] >= x.b1) return false;
  double newB0 = x.b0, newB1 = x.b1;
  for (int i = 0; i + 1 < p.count; ++i) {
    if (!dominated[i]) break;
    if (p.cuts[i] <= newB0) newB0 = std::max(newB0, p.cuts[i + 1]);
  }
  for (int i = p.count - 2; i >= 0; --i) {
    if (!dominated[i]) break;
    if (p.cuts[i + 1] >= newB1) newB1 = std::min(newB1, p.cuts[i]);
  }
  x.b0 = newB0;
  x.b1 = newB1;
  return x.b1 > x.b0;
}

// Trims `w` where an earlier window `o` on the same halfedge is strictly shorter (the
// Mitchell-Mount-Papadimitriou overlap rule, applied one way). Returns false if nothing of w is
// left.
inline bool trimAgainst(Window& w, const Window& o) {
  OverlapPieces p;
  if (!comparePieces(w, o, p)) return true;
  return cutDominated(w, p, 1.0);
}

// Both ways at once (front mode): w where o is shorter, o where w is shorter - the same roots and
// signs, so the pair costs what one trim does. Returns whether each is left.
inline void trimPair(Window& w, Window& o, bool& wLeft, bool& oLeft) {
  OverlapPieces p;
  wLeft = oLeft = true;
  if (!comparePieces(w, o, p)) return;
  wLeft = cutDominated(w, p, 1.0);
  oLeft = cutDominated(o, p, -1.0);
}

}  // namespace egg::geodesic::detail
