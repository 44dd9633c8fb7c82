#pragma once
// Second-order forward-mode automatic differentiation for the small local stencils of the rod
// energies (at most 16 variables). Every energy term is written once, templated on the scalar;
// evaluated with double it gives the energy (line search), with HyperDual<N> it gives the exact
// gradient and Hessian of the same expression. Why not hand-derived Hessians everywhere: the DER
// bending and twisting Hessians (with parallel-transported reference frames) are long and
// error-prone, and the connection/anchor terms couple frames of two rods. The two hottest
// stencils (bend/twist at every vertex, the bolts) do use closed forms assembled by the chain
// rule from small HyperDual pieces (bend_twist_derivatives.hpp, connection_derivatives.hpp): the
// full HyperDual<8>/<16> evaluations were half of the solver's time; they remain the reference
// the closed forms are tested against.
#include <Eigen/Core>

#include <cmath>

namespace egg::rods {

// Only the lower triangle of h (i >= j) is computed and meaningful: every operation acts on the
// Hessian entrywise, so the lower triangle is closed under them. Read entries through hessian().
template <int N>
struct HyperDual {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  double v = 0.0;
  Vec g = Vec::Zero();
  Mat h = Mat::Zero();
  double hessian(int i, int j) const { return i >= j ? h(i, j) : h(j, i); }

  HyperDual() = default;
  HyperDual(double value) : v(value) {}  // NOLINT: constants promote implicitly
  // The k-th independent variable with the given value.
  static HyperDual variable(double value, int k) {
    HyperDual x(value);
    x.g[k] = 1.0;
    return x;
  }
};

// Chain rule for a scalar function with value f, first derivative d1 and second derivative d2.
template <int N>
inline HyperDual<N> chain(const HyperDual<N>& a, double f, double d1, double d2) {
  HyperDual<N> r;
  r.v = f;
  for (int i = 0; i < N; ++i) r.g[i] = d1 * a.g[i];
  for (int j = 0; j < N; ++j) {
    const double gj = d2 * a.g[j];
    for (int i = j; i < N; ++i) r.h(i, j) = d1 * a.h(i, j) + gj * a.g[i];
  }
  return r;
}

template <int N>
inline HyperDual<N> operator+(const HyperDual<N>& a, const HyperDual<N>& b) {
  HyperDual<N> r;
  r.v = a.v + b.v;
  r.g = a.g + b.g;
  r.h = a.h + b.h;
  return r;
}
template <int N>
inline HyperDual<N> operator-(const HyperDual<N>& a, const HyperDual<N>& b) {
  HyperDual<N> r;
  r.v = a.v - b.v;
  r.g = a.g - b.g;
  r.h = a.h - b.h;
  return r;
}
template <int N>
inline HyperDual<N> operator-(const HyperDual<N>& a) {
  HyperDual<N> r;
  r.v = -a.v;
  r.g = -a.g;
  r.h = -a.h;
  return r;
}
template <int N>
inline HyperDual<N> operator*(const HyperDual<N>& a, const HyperDual<N>& b) {
  // Written as plain loops: one pass over the Hessian instead of Eigen temporaries per term.
  HyperDual<N> r;
  r.v = a.v * b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.v * b.g[i] + b.v * a.g[i];
  for (int j = 0; j < N; ++j) {
    const double aj = a.g[j], bj = b.g[j];
    for (int i = j; i < N; ++i)
      r.h(i, j) = a.v * b.h(i, j) + b.v * a.h(i, j) + a.g[i] * bj + b.g[i] * aj;
  }
  return r;
}
template <int N>
inline HyperDual<N> operator*(double s, const HyperDual<N>& a) {
  HyperDual<N> r;
  r.v = s * a.v;
  r.g = s * a.g;
  r.h = s * a.h;
  return r;
}
template <int N>
inline HyperDual<N> operator*(const HyperDual<N>& a, double s) {
  return s * a;
}
template <int N>
inline HyperDual<N> operator+(const HyperDual<N>& a, double s) {
  HyperDual<N> r = a;
  r.v += s;
  return r;
}
template <int N>
inline HyperDual<N> operator+(double s, const HyperDual<N>& a) {
  return a + s;
}
template <int N>
inline HyperDual<N> operator-(const HyperDual<N>& a, double s) {
  return a + (-s);
}
template <int N>
inline HyperDual<N> operator-(double s, const HyperDual<N>& a) {
  return (-a) + s;
}
template <int N>
inline HyperDual<N> inverse(const HyperDual<N>& a) {
  const double i = 1.0 / a.v;
  return chain(a, i, -i * i, 2.0 * i * i * i);
}
template <int N>
inline HyperDual<N> operator/(const HyperDual<N>& a, const HyperDual<N>& b) {
  return a * inverse(b);
}
template <int N>
inline HyperDual<N> operator/(const HyperDual<N>& a, double s) {
  return (1.0 / s) * a;
}
template <int N>
inline HyperDual<N> operator/(double s, const HyperDual<N>& a) {
  return s * inverse(a);
}

template <int N>
inline HyperDual<N> sqrt(const HyperDual<N>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}
template <int N>
inline HyperDual<N> log(const HyperDual<N>& a) {
  return chain(a, std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
}
template <int N>
inline HyperDual<N> sin(const HyperDual<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, s, c, -s);
}
template <int N>
inline HyperDual<N> cos(const HyperDual<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, c, -s, -c);
}
// atan2(y, x) with its exact first and second partial derivatives.
template <int N>
inline HyperDual<N> atan2(const HyperDual<N>& y, const HyperDual<N>& x) {
  const double r2 = x.v * x.v + y.v * y.v;
  const double fy = x.v / r2, fx = -y.v / r2;
  const double r4 = r2 * r2;
  const double fyy = -2.0 * x.v * y.v / r4, fxx = 2.0 * x.v * y.v / r4,
               fxy = (y.v * y.v - x.v * x.v) / r4;
  HyperDual<N> r;
  r.v = std::atan2(y.v, x.v);
  for (int i = 0; i < N; ++i) r.g[i] = fy * y.g[i] + fx * x.g[i];
  for (int j = 0; j < N; ++j) {
    const double yj = y.g[j], xj = x.g[j];
    for (int i = j; i < N; ++i) {
      r.h(i, j) = fy * y.h(i, j) + fx * x.h(i, j) + fyy * y.g[i] * yj + fxx * x.g[i] * xj +
                  fxy * (y.g[i] * xj + x.g[i] * yj);
    }
  }
  return r;
}

// A quantity differentiated with respect to an edge (edge vector e = x_end - x_start and its
// material angle theta: 4 variables) lifted into a stencil whose variables include x_start,
// x_end (3 each, at local indices start.., end..) and theta (at local index thetaIndex).
// Computing edge frames once per edge with 4 variables and lifting them is several times cheaper
// than differentiating the frames inside every stencil.
template <int N>
inline HyperDual<N> liftEdgeQuantity(const HyperDual<4>& a, int start, int end, int thetaIndex) {
  HyperDual<N> r(a.v);
  int index[4][2];
  double sign[4][2];
  int count[4];
  for (int k = 0; k < 3; ++k) {
    index[k][0] = start + k;
    sign[k][0] = -1.0;
    index[k][1] = end + k;
    sign[k][1] = 1.0;
    count[k] = 2;
  }
  index[3][0] = thetaIndex;
  sign[3][0] = 1.0;
  count[3] = 1;
  for (int p = 0; p < 4; ++p) {
    for (int i = 0; i < count[p]; ++i) {
      r.g[index[p][i]] += sign[p][i] * a.g[p];
      for (int q = 0; q < 4; ++q) {
        for (int j = 0; j < count[q]; ++j) {
          const int row = index[p][i], col = index[q][j];
          if (row >= col) r.h(row, col) += sign[p][i] * sign[q][j] * a.hessian(p, q);
        }
      }
    }
  }
  return r;
}

inline double value(double a) { return a; }
template <int N>
inline double value(const HyperDual<N>& a) {
  return a.v;
}

// A 3-vector over any scalar (Eigen's fixed vectors need NumTraits for custom scalars; this is
// all the energies need).
template <class S>
struct V3 {
  S x, y, z;
};
template <class S>
inline V3<S> constant(const Eigen::Vector3d& v) {
  return {S(v.x()), S(v.y()), S(v.z())};
}
template <class S>
inline V3<S> operator+(const V3<S>& a, const V3<S>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class S>
inline V3<S> operator-(const V3<S>& a, const V3<S>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class S, class T>
inline V3<S> operator*(const T& s, const V3<S>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class S>
inline S dot(const V3<S>& a, const V3<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class S>
inline V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Fused forms for HyperDual: one pass over the Hessian's lower triangle instead of a temporary
// per product and per sum (the bending stencils spend most of their time in dot and cross).
template <int N>
inline HyperDual<N> dot(const V3<HyperDual<N>>& a, const V3<HyperDual<N>>& b) {
  const HyperDual<N>* as[3] = {&a.x, &a.y, &a.z};
  const HyperDual<N>* bs[3] = {&b.x, &b.y, &b.z};
  HyperDual<N> r;
  r.v = a.x.v * b.x.v + a.y.v * b.y.v + a.z.v * b.z.v;
  for (int i = 0; i < N; ++i) {
    r.g[i] = a.x.v * b.x.g[i] + b.x.v * a.x.g[i] + a.y.v * b.y.g[i] + b.y.v * a.y.g[i] +
             a.z.v * b.z.g[i] + b.z.v * a.z.g[i];
  }
  for (int j = 0; j < N; ++j) {
    for (int i = j; i < N; ++i) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        const HyperDual<N>& ak = *as[k];
        const HyperDual<N>& bk = *bs[k];
        sum += ak.v * bk.h(i, j) + bk.v * ak.h(i, j) + ak.g[i] * bk.g[j] + bk.g[i] * ak.g[j];
      }
      r.h(i, j) = sum;
    }
  }
  return r;
}
// a * b - c * d in one pass.
template <int N>
inline HyperDual<N> productDifference(const HyperDual<N>& a, const HyperDual<N>& b,
                                      const HyperDual<N>& c, const HyperDual<N>& d) {
  HyperDual<N> r;
  r.v = a.v * b.v - c.v * d.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.v * b.g[i] + b.v * a.g[i] - c.v * d.g[i] - d.v * c.g[i];
  for (int j = 0; j < N; ++j) {
    const double aj = a.g[j], bj = b.g[j], cj = c.g[j], dj = d.g[j];
    for (int i = j; i < N; ++i) {
      r.h(i, j) = a.v * b.h(i, j) + b.v * a.h(i, j) + a.g[i] * bj + b.g[i] * aj -
                  (c.v * d.h(i, j) + d.v * c.h(i, j) + c.g[i] * dj + d.g[i] * cj);
    }
  }
  return r;
}
template <int N>
inline V3<HyperDual<N>> cross(const V3<HyperDual<N>>& a, const V3<HyperDual<N>>& b) {
  return {productDifference(a.y, b.z, a.z, b.y), productDifference(a.z, b.x, a.x, b.z),
          productDifference(a.x, b.y, a.y, b.x)};
}
template <class S>
inline S squaredNorm(const V3<S>& a) {
  return dot(a, a);
}
template <class S>
inline S norm(const V3<S>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

}  // namespace egg::rods
