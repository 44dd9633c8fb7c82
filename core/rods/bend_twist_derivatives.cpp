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

// The two bending terms of edge E (its variables: e_E at 3E, theta_E at 6 + E) with w = kb.a:
// gradient 2 c w grad w; Hessian 2 c (grad w grad w^T + w Hess w), where Hess w = sum_i (a_i Hess
// kb_i + kb_i Hess a_i + grad kb_i grad a_i^T + grad a_i grad kb_i^T). The a_i Hess kb_i parts of
// all four terms are summed by the caller (lambda); the rest is gathered over the edge's two terms
// before it is added (one 6x4 product for the mixed parts instead of one per term). E is a
// template parameter so that every index is a constant.
template <int E>
void bendEdge(const Frame<D4>& frame, double weak, double strong, const Eigen::Vector3d& kbv,
              const Eigen::Matrix<double, 3, 6>& kbJ, bool gaussNewton, double& bending,
              Eigen::Vector3d& lambda, Vec8& g, Mat8& H) {
  Eigen::Matrix<double, 3, 4> mixed = Eigen::Matrix<double, 3, 4>::Zero();  // sum s grad a
  Eigen::Matrix4d own = Eigen::Matrix4d::Zero();                            // sum s kb_i Hess a_i
  for (int term = 0; term < 2; ++term) {
    const V3<D4>& a = term == 0 ? frame.side : frame.normal;
    const double c = term == 0 ? weak : strong;
    const D4* ac[3] = {&a.x, &a.y, &a.z};
    Eigen::Vector3d av;
    Eigen::Matrix<double, 3, 4> aJ;
    for (int i = 0; i < 3; ++i) {
      av[i] = ac[i]->v;
      aJ.row(i) = ac[i]->g.transpose();
    }
    const double w = kbv.dot(av);
    Vec8 gw;
    gw.head<6>().noalias() = kbJ.transpose() * av;
    const Eigen::Vector4d ga = aJ.transpose() * kbv;
    gw.segment<3>(3 * E) += ga.head<3>();
    gw[6 + E] = ga[3];
    gw[7 - E] = 0.0;
    bending += c * w * w;
    const double s = 2.0 * c * w;
    g += s * gw;
    H.noalias() += (2.0 * c) * gw * gw.transpose();
    if (gaussNewton) continue;
    lambda += s * av;
    mixed += s * aJ;
    for (int i = 0; i < 3; ++i) {
      const double sk = s * kbv[i];
      for (int p = 0; p < 4; ++p)
        for (int q = 0; q <= p; ++q) own(p, q) += sk * ac[i]->h(p, q);
    }
  }
  if (gaussNewton) return;
  own.triangularView<Eigen::StrictlyUpper>() = own.transpose();
  const Eigen::Matrix<double, 6, 4> cross = kbJ.transpose() * mixed;  // sum s grad kb_i grad a_i^T
  H.block<6, 3>(0, 3 * E) += cross.leftCols<3>();
  H.block<3, 6>(3 * E, 0) += cross.leftCols<3>().transpose();
  H.block<6, 1>(0, 6 + E) += cross.col(3);
  H.block<1, 6>(6 + E, 0) += cross.col(3).transpose();
  H.block<3, 3>(3 * E, 3 * E) += own.topLeftCorner<3, 3>();
  H.block<3, 1>(3 * E, 6 + E) += own.block<3, 1>(0, 3);
  H.block<1, 3>(6 + E, 3 * E) += own.block<1, 3>(3, 0);
  H(6 + E, 6 + E) += own(3, 3);
}

}  // namespace

// The tangent, transported director u and v = t x u depend on the edge vector only: they are
// differentiated with 3 variables, and the angle enters in closed form: m1 = cos(theta) u +
// sin(theta) v, m2 = cos(theta) v - sin(theta) u, so d m1/d theta = m2, d m2/d theta = -m1 and
// the second derivatives in theta are -m1, -m2 (the same expressions as materialFrame).
EdgeFrameDerivatives edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta,
                                          const EdgeReference& reference) {
  EdgeFrameDerivatives out;
  edgeFrameDerivatives(edge, theta, reference, out);
  return out;
}

void edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta, const EdgeReference& reference,
                          EdgeFrameDerivatives& out) {
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
  out.frame.tangent = {lift(t.x), lift(t.y), lift(t.z)};
  out.tangent = t;
  out.director = u;
  out.binormal = v;
  out.frame.normal = {turned(u.x, v.x, c, s, -s, c), turned(u.y, v.y, c, s, -s, c),
                      turned(u.z, v.z, c, s, -s, c)};
  out.frame.side = {turned(v.x, u.x, c, -s, -s, -c), turned(v.y, u.y, c, -s, -s, -c),
                    turned(v.z, u.z, c, -s, -s, -c)};
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
  Eigen::Vector3d kbv;
  Eigen::Matrix<double, 3, 6> kbJ;  // gradient of kb over (e0, e1), one row per component
  for (int i = 0; i < 3; ++i) {
    kbv[i] = kbc[i]->v;
    kbJ.row(i) = kbc[i]->g.transpose();
  }

  // Bending: the four material curvatures w = kb.a, weighted as in bendTwistEnergyOfEdges, two
  // per edge (a = m2 with the weak stiffness, a = m1 with the strong one).
  const double scale = 0.25 / voronoiLength;
  Eigen::Vector3d lambda =
      Eigen::Vector3d::Zero();  // sum over terms of 2 c w a: weights of Hess kb
  double bending = 0.0;
  bendEdge<0>(f0.frame, scale * stiffness.bendingWeak, scale * stiffness.bendingStrong, kbv, kbJ,
              gaussNewton, bending, lambda, g, H);
  bendEdge<1>(f1.frame, scale * stiffness.bendingWeak, scale * stiffness.bendingStrong, kbv, kbJ,
              gaussNewton, bending, lambda, g, H);
  if (!gaussNewton) {
    for (int k = 0; k < 6; ++k) {
      for (int l = 0; l <= k; ++l) {
        const double h =
            lambda[0] * kbc[0]->h(k, l) + lambda[1] * kbc[1]->h(k, l) + lambda[2] * kbc[2]->h(k, l);
        H(k, l) += h;
        if (l != k) H(l, k) += h;
      }
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
  // A maps (x0, x1, x2, theta0, theta1) to (e0, e1, theta0, theta1): x0 enters e0 with -1, x1
  // e0 with +1 and e1 with -1, x2 e1 with +1. Applied as block differences, first to the
  // columns (T = H A, 8 x 11), then to the rows (A^T T).
  const Mat8& h = d.hessian;
  Eigen::Matrix<double, 8, 11> t;
  t.middleCols<3>(0) = -h.leftCols<3>();
  t.middleCols<3>(3) = h.leftCols<3>() - h.middleCols<3>(3);
  t.middleCols<3>(6) = h.middleCols<3>(3);
  t.rightCols<2>() = h.rightCols<2>();
  BendTwistVertexDerivatives out;
  out.energy = d.energy;
  out.hessian.middleRows<3>(0) = -t.topRows<3>();
  out.hessian.middleRows<3>(3) = t.topRows<3>() - t.middleRows<3>(3);
  out.hessian.middleRows<3>(6) = t.middleRows<3>(3);
  out.hessian.bottomRows<2>() = t.bottomRows<2>();
  out.gradient.segment<3>(0) = -d.gradient.head<3>();
  out.gradient.segment<3>(3) = d.gradient.head<3>() - d.gradient.segment<3>(3);
  out.gradient.segment<3>(6) = d.gradient.segment<3>(3);
  out.gradient.tail<2>() = d.gradient.tail<2>();
  return out;
}

}  // namespace egg::rods
