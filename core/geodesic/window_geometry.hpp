#pragma once
// Internal: the planar geometry of windows shared by the propagation (window_propagation.cpp):
// frame changes between the unfolded edge frames, ray crossings, paired square roots, and the
// trimming of a window against another on the same edge. Inline because the propagation calls
// them for every one of the ~200k windows of a 4k-vertex field.
#include "core/geodesic/window_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
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


inline double windowMinDistance(const Window& w) {
  if (w.sx >= w.b0 && w.sx <= w.b1) return w.sigma - w.sy;
  double d0, d1;
  planarLengths(w.b0 - w.sx, w.sy, w.b1 - w.sx, w.sy, d0, d1);
  return w.sigma + std::min(d0, d1);
}

// Trims `w` where an earlier window `o` on the same halfedge is strictly shorter (the
// Mitchell-Mount-Papadimitriou overlap rule, applied one way). g(x) = (o.sigma + |o.s - x|) -
// (w.sigma + |w.s - x|) changes sign at most twice on the edge; the roots come from squaring
// |o.s - x| - |w.s - x| = w.sigma - o.sigma twice (a quadratic), spurious ones are dropped.
// Returns false if nothing of w is left.
inline bool trimAgainst(Window& w, const Window& o) {
  const double lo = std::max(w.b0, o.b0), hi = std::min(w.b1, o.b1);
  if (!(hi > lo)) return true;
  auto g = [&](double x) {
    double lengthO, lengthW;
    planarLengths(x - o.sx, o.sy, x - w.sx, w.sy, lengthO, lengthW);
    return (o.sigma + lengthO) - (w.sigma + lengthW);
  };
  double cuts[4];
  int count = 0;
  cuts[count++] = lo;
  {
    const double k = w.sigma - o.sigma;
    const double a = 2.0 * (w.sx - o.sx);
    const double c = o.sx * o.sx + o.sy * o.sy - w.sx * w.sx - w.sy * w.sy - k * k;
    const double qa = a * a - 4.0 * k * k;
    const double qb = 2.0 * a * c + 8.0 * k * k * w.sx;
    const double qc = c * c - 4.0 * k * k * (w.sx * w.sx + w.sy * w.sy);
    double roots[2];
    int nroots = 0;
    if (std::abs(qa) > 1e-300) {
      const double disc = qb * qb - 4.0 * qa * qc;
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
      if (roots[i] > lo && roots[i] < hi) cuts[count++] = roots[i];
    }
  }
  cuts[count++] = hi;
  // Sign of g on each piece, from its midpoint; a piece where o is shorter is cut off if it
  // touches an end of w (a middle piece would split w in two, so it stays).
  double newB0 = w.b0, newB1 = w.b1;
  bool dominated[3];  // per piece, evaluated once (two square roots each)
  bool allDominated = true;
  for (int i = 0; i + 1 < count; ++i) {
    dominated[i] = g(0.5 * (cuts[i] + cuts[i + 1])) < 0.0;
    allDominated = allDominated && dominated[i];
  }
  if (allDominated && lo <= w.b0 && hi >= w.b1) return false;
  for (int i = 0; i + 1 < count; ++i) {
    if (!dominated[i]) break;
    if (cuts[i] <= newB0) newB0 = std::max(newB0, cuts[i + 1]);
  }
  for (int i = count - 2; i >= 0; --i) {
    if (!dominated[i]) break;
    if (cuts[i + 1] >= newB1) newB1 = std::min(newB1, cuts[i]);
  }
  w.b0 = newB0;
  w.b1 = newB1;
  return w.b1 > w.b0;
}

}  // namespace egg::geodesic::detail
