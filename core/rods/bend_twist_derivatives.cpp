// Closed-form bending/twisting derivatives (Section 2.5): see bend_twist_derivatives.hpp.
#include "core/rods/bend_twist_derivatives.hpp"

#include <cmath>

namespace egg::rods {

namespace {

using D4 = HyperDual<4>;
using D6 = HyperDual<6>;
using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;

// An edge quantity that depends on the edge vector only (tangent, director) as a function of
// (e0, e1): its edge vector's variables start at `offset` (0 for e0, 3 for e1).
V3<D6> onEdgeVector(const V3<D4>& a, int offset) {
  auto lift = [&](const D4& q) {
    D6 r(q.v);
    for (int p = 0; p < 3; ++p) {
      r.g[offset + p] = q.g[p];
      for (int s = 0; s <= p; ++s) r.h(offset + p, offset + s) = q.h(p, s);
    }
    return r;
  };
  return {lift(a.x), lift(a.y), lift(a.z)};
}

}  // namespace

// The tangent, transported director u and v = t x u depend on the edge vector only: they are
// differentiated with 3 variables, and the angle enters in closed form: m1 = cos(theta) u +
// sin(theta) v, m2 = cos(theta) v - sin(theta) u, so d m1/d theta = m2, d m2/d theta = -m1 and
// the second derivatives in theta are -m1, -m2 (the same expressions as materialFrame).
EdgeFrameDerivatives edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta, const EdgeReference& reference) {
  using D3 = HyperDual<3>;
  const V3<D3> e{D3::variable(edge.x(), 0), D3::variable(edge.y(), 1), D3::variable(edge.z(), 2)};
  const D3 length = norm(e);
  const V3<D3> t = (1.0 / length) * e;
  const V3<D3> u = parallelTransport(constant<D3>(reference.tangent), t, constant<D3>(reference.director));
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
  out.director = {lift(u.x), lift(u.y), lift(u.z)};
  out.frame.normal = {turned(u.x, v.x, c, s, -s, c), turned(u.y, v.y, c, s, -s, c), turned(u.z, v.z, c, s, -s, c)};
  out.frame.side = {turned(v.x, u.x, c, -s, -s, -c), turned(v.y, u.y, c, -s, -s, -c),
                    turned(v.z, u.z, c, -s, -s, -c)};
  return out;
}

BendTwistDerivatives bendTwistDerivatives(const EdgeFrameDerivatives& f0, const EdgeFrameDerivatives& f1,
                                          const RodStiffness& stiffness, double voronoiLength) {
  // Curvature binormal and reference twist over (e0, e1).
  const V3<D6> t0 = onEdgeVector(f0.frame.tangent, 0), t1 = onEdgeVector(f1.frame.tangent, 3);
  const V3<D6> u0 = onEdgeVector(f0.director, 0), u1 = onEdgeVector(f1.director, 3);
  const D6 c = dot(t0, t1);
  const V3<D6> v = cross(t0, t1);
  const D6 inverse1c = inverse(c + 1.0);
  const D6 twiceInverse = 2.0 * inverse1c;
  const V3<D6> kb{twiceInverse * v.x, twiceInverse * v.y, twiceInverse * v.z};
  // P u0 = c u0 + v x u0 + (v.u0) v / (1 + c), as in parallelTransport.
  const D6 vu = dot(v, u0) * inverse1c;
  const V3<D6> vxu = cross(v, u0);
  const V3<D6> carried{c * u0.x + vxu.x + vu * v.x, c * u0.y + vxu.y + vu * v.y, c * u0.z + vxu.z + vu * v.z};
  const D6 reference = atan2(dot(cross(carried, u1), t1), dot(carried, u1));

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
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 6; ++k) {
      for (int l = 0; l < 6; ++l) H(k, l) += lambda[i] * kbc[i]->hessian(k, l);
    }
  }

  // Twisting. Its value as bendTwistEnergyOfEdges computes it (the signed angle in (-pi, pi]);
  // its derivatives from the reference twist.
  const V3<double> m0{f0.frame.normal.x.v, f0.frame.normal.y.v, f0.frame.normal.z.v};
  const V3<double> m1{f1.frame.normal.x.v, f1.frame.normal.y.v, f1.frame.normal.z.v};
  const V3<double> tangent0{t0.x.v, t0.y.v, t0.z.v}, tangent1{t1.x.v, t1.y.v, t1.z.v};
  const V3<double> carriedNormal = parallelTransport(tangent0, tangent1, m0);
  const double twist = std::atan2(dot(cross(carriedNormal, m1), tangent1), dot(carriedNormal, m1));
  const double k = stiffness.twisting / voronoiLength;
  Vec8 gt;
  for (int i = 0; i < 6; ++i) gt[i] = reference.g[i];
  gt[6] = -1.0;
  gt[7] = 1.0;
  g += (k * twist) * gt;
  H.noalias() += k * gt * gt.transpose();
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) H(i, j) += (k * twist) * reference.hessian(i, j);
  }
  out.energy = bending + 0.5 * k * twist * twist;
  return out;
}

}  // namespace egg::rods
