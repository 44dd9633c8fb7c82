// Closed-form bending/twisting derivatives (Section 2.5): see bend_twist_derivatives.hpp.
#include "core/rods/bend_twist_derivatives.hpp"

#include <cmath>

namespace egg::rods {

namespace {

using D3 = HyperDual<3>;
using D4 = HyperDual<4>;
using D6 = HyperDual<6>;
using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;

// sum_k sign_k a_k * b_k in one pass (a_k of e0, b_k of e1).
template <int K>
D6 bilinearSum(const D3* const (&a)[K], const D3* const (&b)[K], const double (&sign)[K]) {
  D6 r;
  for (int k = 0; k < K; ++k) {
    const D3& x = *a[k];
    const D3& y = *b[k];
    const double s = sign[k];
    r.v += s * x.v * y.v;
    for (int p = 0; p < 3; ++p) {
      r.g[p] += s * y.v * x.g[p];
      r.g[3 + p] += s * x.v * y.g[p];
      for (int q = 0; q <= p; ++q) {
        r.h(p, q) += s * y.v * x.h(p, q);
        r.h(3 + p, 3 + q) += s * x.v * y.h(p, q);
      }
      for (int q = 0; q < 3; ++q) r.h(3 + p, q) += s * y.g[p] * x.g[q];
    }
  }
  return r;
}

D6 bilinearDot(const V3<D3>& a, const V3<D3>& b) {
  return bilinearSum<3>({&a.x, &a.y, &a.z}, {&b.x, &b.y, &b.z}, {1.0, 1.0, 1.0});
}

// (a x b)_i for a of e0, b of e1.
V3<D6> bilinearCross(const V3<D3>& a, const V3<D3>& b) {
  return {bilinearSum<2>({&a.y, &a.z}, {&b.z, &b.y}, {1.0, -1.0}),
          bilinearSum<2>({&a.z, &a.x}, {&b.x, &b.z}, {1.0, -1.0}),
          bilinearSum<2>({&a.x, &a.y}, {&b.y, &b.x}, {1.0, -1.0})};
}

}  // namespace

// The tangent, transported director u and v = t x u depend on the edge vector only: they are
// differentiated with 3 variables, and the angle enters in closed form: m1 = cos(theta) u +
// sin(theta) v, m2 = cos(theta) v - sin(theta) u, so d m1/d theta = m2, d m2/d theta = -m1 and
// the second derivatives in theta are -m1, -m2 (the same expressions as materialFrame).
EdgeFrameDerivatives edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta,
                                          const EdgeReference& reference) {
  const V3<D3> e{D3::variable(edge.x(), 0), D3::variable(edge.y(), 1), D3::variable(edge.z(), 2)};
  const D3 length = norm(e);
  const V3<D3> t = (1.0 / length) * e;
  const V3<D3> u =
      parallelTransport(constant<D3>(reference.tangent), t, constant<D3>(reference.director));
  const V3<D3> v = cross(t, u);
  const double c = std::cos(theta), s = std::sin(theta);
  // An edge-vector-only quantity as a function of (e, theta).
  auto lift = [](const D3& a) {
    D4 r(a.v);
    for (int p = 0; p < 3; ++p) {
      r.g[p] = a.g[p];
      for (int q = 0; q <= p; ++q) r.h(p, q) = a.h(p, q);
    }
    return r;
  };
  // cu * a + cv * b whose theta derivative is du * a + dv * b and second theta derivative
  // -(cu * a + cv * b) (a rotation by theta).
  auto turned = [](const D3& a, const D3& b, double cu, double cv, double du, double dv) {
    D4 r(cu * a.v + cv * b.v);
    for (int p = 0; p < 3; ++p) {
      r.g[p] = cu * a.g[p] + cv * b.g[p];
      for (int q = 0; q <= p; ++q) r.h(p, q) = cu * a.h(p, q) + cv * b.h(p, q);
      r.h(3, p) = du * a.g[p] + dv * b.g[p];
    }
    r.g[3] = du * a.v + dv * b.v;
    r.h(3, 3) = -r.v;
    return r;
  };
  EdgeFrameDerivatives out;
  out.frame.tangent = {lift(t.x), lift(t.y), lift(t.z)};
  out.tangent = t;
  out.director = u;
  out.binormal = v;
  out.frame.normal = {turned(u.x, v.x, c, s, -s, c), turned(u.y, v.y, c, s, -s, c),
                      turned(u.z, v.z, c, s, -s, c)};
  out.frame.side = {turned(v.x, u.x, c, -s, -s, -c), turned(v.y, u.y, c, -s, -s, -c),
                    turned(v.z, u.z, c, -s, -s, -c)};
  return out;
}

BendTwistDerivatives bendTwistDerivatives(const EdgeFrameDerivatives& f0,
                                          const EdgeFrameDerivatives& f1,
                                          const RodStiffness& stiffness, double voronoiLength,
                                          bool gaussNewton) {
  // Curvature binormal and reference twist over (e0, e1), from bilinear products.
  const V3<D3>&t0 = f0.tangent, &u0 = f0.director, &w0 = f0.binormal;
  const V3<D3>&t1 = f1.tangent, &u1 = f1.director, &w1 = f1.binormal;
  const D6 c = bilinearDot(t0, t1);
  const D6 inverse1c = inverse(c + 1.0);
  const D6 twiceInverse = 2.0 * inverse1c;
  const V3<D6> v = bilinearCross(t0, t1);
  const V3<D6> kb{twiceInverse * v.x, twiceInverse * v.y, twiceInverse * v.z};
  const D6 u0u1 = bilinearDot(u0, u1), u0w1 = bilinearDot(u0, w1);
  const D6 t1u0 = bilinearDot(u0, t1), t0u1 = bilinearDot(t0, u1);
  const D6 t1w0 = bilinearDot(w0, t1), t0w1 = bilinearDot(t0, w1);
  const D6 x = productDifference(c, u0u1, t1u0, t0u1) - (t1w0 * t0w1) * inverse1c;
  const D6 y = productDifference(t1u0, t0w1, c, u0w1) - (t1w0 * t0u1) * inverse1c;
  const D6 reference = atan2(y, x);

  BendTwistDerivatives out;
  Vec8& g = out.gradient;
  Mat8& H = out.hessian;
  g.setZero();
  H.setZero();
  const D6* kbc[3] = {&kb.x, &kb.y, &kb.z};

  // Bending: the four material curvatures, weighted as in bendTwistEnergyOfEdges.
  const double scale = 0.25 / voronoiLength;
  struct Term {
    const V3<D4>* a;
    int edge;
    double c;
  };
  const Term terms[4] = {{&f0.frame.side, 0, scale * stiffness.bendingWeak},
                         {&f1.frame.side, 1, scale * stiffness.bendingWeak},
                         {&f0.frame.normal, 0, scale * stiffness.bendingStrong},
                         {&f1.frame.normal, 1, scale * stiffness.bendingStrong}};
  double lambda[3] = {0.0, 0.0, 0.0};  // sum over terms of 2 c w a: weights of Hess kb
  double bending = 0.0;
  for (const Term& term : terms) {
    const D4* ac[3] = {&term.a->x, &term.a->y, &term.a->z};
    const int at[4] = {3 * term.edge, 3 * term.edge + 1, 3 * term.edge + 2, 6 + term.edge};
    double w = 0.0;
    Vec8 gw = Vec8::Zero();
    for (int i = 0; i < 3; ++i) {
      w += kbc[i]->v * ac[i]->v;
      for (int k = 0; k < 6; ++k) gw[k] += kbc[i]->g[k] * ac[i]->v;
      for (int p = 0; p < 4; ++p) gw[at[p]] += kbc[i]->v * ac[i]->g[p];
    }
    bending += term.c * w * w;
    const double s = 2.0 * term.c * w;
    g += s * gw;
    H.noalias() += (2.0 * term.c) * gw * gw.transpose();
    if (gaussNewton) continue;
    for (int i = 0; i < 3; ++i) {
      lambda[i] += s * ac[i]->v;
      const double sk = s * kbc[i]->v;
      for (int p = 0; p < 4; ++p) {
        for (int q = 0; q < 4; ++q) H(at[p], at[q]) += sk * ac[i]->hessian(p, q);
        // Mixed terms grad kb_i grad a_i^T and their transpose.
        const double sa = s * ac[i]->g[p];
        for (int k = 0; k < 6; ++k) {
          H(k, at[p]) += sa * kbc[i]->g[k];
          H(at[p], k) += sa * kbc[i]->g[k];
        }
      }
    }
  }
  for (int i = 0; i < 3 && !gaussNewton; ++i) {
    for (int k = 0; k < 6; ++k) {
      for (int l = 0; l < 6; ++l) H(k, l) += lambda[i] * kbc[i]->hessian(k, l);
    }
  }

  // Twisting. Its value as bendTwistEnergyOfEdges computes it (the signed angle in (-pi, pi]);
  // its derivatives from the reference twist.
  const V3<double> m0{f0.frame.normal.x.v, f0.frame.normal.y.v, f0.frame.normal.z.v};
  const V3<double> m1{f1.frame.normal.x.v, f1.frame.normal.y.v, f1.frame.normal.z.v};
  const V3<double> tangent0{f0.frame.tangent.x.v, f0.frame.tangent.y.v, f0.frame.tangent.z.v};
  const V3<double> tangent1{f1.frame.tangent.x.v, f1.frame.tangent.y.v, f1.frame.tangent.z.v};
  const V3<double> carriedNormal = parallelTransport(tangent0, tangent1, m0);
  const double twist = std::atan2(dot(cross(carriedNormal, m1), tangent1), dot(carriedNormal, m1));
  const double k = stiffness.twisting / voronoiLength;
  Vec8 gt;
  for (int i = 0; i < 6; ++i) gt[i] = reference.g[i];
  gt[6] = -1.0;
  gt[7] = 1.0;
  g += (k * twist) * gt;
  H.noalias() += k * gt * gt.transpose();
  for (int i = 0; i < 6 && !gaussNewton; ++i) {
    for (int j = 0; j < 6; ++j) H(i, j) += (k * twist) * reference.hessian(i, j);
  }
  out.energy = bending + 0.5 * k * twist * twist;
  return out;
}

BendTwistVertexDerivatives onVertices(const BendTwistDerivatives& d) {
  // Column a of the map: the stencil variables that unknown a enters, with their signs
  // (x0: -e0; x1: +e0, -e1; x2: +e1; thetas: themselves).
  int count[11], variable[11][2];
  double sign[11][2];
  for (int k = 0; k < 3; ++k) {
    count[k] = 1, variable[k][0] = k, sign[k][0] = -1.0;
    count[3 + k] = 2, variable[3 + k][0] = k, sign[3 + k][0] = 1.0, variable[3 + k][1] = 3 + k,
              sign[3 + k][1] = -1.0;
    count[6 + k] = 1, variable[6 + k][0] = 3 + k, sign[6 + k][0] = 1.0;
  }
  count[9] = 1, variable[9][0] = 6, sign[9][0] = 1.0;
  count[10] = 1, variable[10][0] = 7, sign[10][0] = 1.0;
  BendTwistVertexDerivatives out;
  out.energy = d.energy;
  for (int a = 0; a < 11; ++a) {
    double g = 0.0;
    for (int p = 0; p < count[a]; ++p) g += sign[a][p] * d.gradient[variable[a][p]];
    out.gradient[a] = g;
    for (int b = 0; b <= a; ++b) {
      double h = 0.0;
      for (int p = 0; p < count[a]; ++p) {
        for (int q = 0; q < count[b]; ++q)
          h += sign[a][p] * sign[b][q] * d.hessian(variable[a][p], variable[b][q]);
      }
      out.hessian(a, b) = h;
      out.hessian(b, a) = h;
    }
  }
  return out;
}

}  // namespace egg::rods
