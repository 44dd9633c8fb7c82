// Closed-form connection derivatives (Section 2.5): see connection_derivatives.hpp.
#include "core/rods/connection_derivatives.hpp"

namespace egg::rods {

namespace {

using Vec16 = Eigen::Matrix<double, 16, 1>;
using Mat16 = Eigen::Matrix<double, 16, 16>;

// Local indices of one side: its edge's first vertex, second vertex, angle and beta.
struct Side {
  int start, end, theta, beta;
};
constexpr Side kLower{0, 3, 6, 7};
constexpr Side kUpper{8, 11, 14, 15};

// Gradient over the stencil of an edge quantity a(e, theta), e = x_end - x_start.
Vec16 edgeGradient(const HyperDual<4>& a, const Side& side) {
  Vec16 g = Vec16::Zero();
  for (int p = 0; p < 3; ++p) {
    g[side.start + p] = -a.g[p];
    g[side.end + p] = a.g[p];
  }
  g[side.theta] = a.g[3];
  return g;
}

// H += weight * Hess a over the stencil.
void addEdgeHessian(Mat16& H, const HyperDual<4>& a, const Side& side, double weight) {
  int index[7];
  double sign[7];
  int variable[7];
  for (int p = 0; p < 3; ++p) {
    index[p] = side.start + p, sign[p] = -1.0, variable[p] = p;
    index[3 + p] = side.end + p, sign[3 + p] = 1.0, variable[3 + p] = p;
  }
  index[6] = side.theta, sign[6] = 1.0, variable[6] = 3;
  for (int k = 0; k < 7; ++k) {
    for (int l = 0; l < 7; ++l) {
      H(index[k], index[l]) += weight * sign[k] * sign[l] * a.hessian(variable[k], variable[l]);
    }
  }
}

}  // namespace

ConnectionDerivatives connectionDerivatives(const Eigen::Vector3d& g0, const Eigen::Vector3d& g1,
                                            const EdgeFrameDerivatives& fg, double betaG,
                                            const Eigen::Vector3d& h0, const Eigen::Vector3d& h1,
                                            const EdgeFrameDerivatives& fh, double betaH,
                                            double offset, double positionWeight,
                                            double angleWeight) {
  const HyperDual<4>* mg[3] = {&fg.frame.normal.x, &fg.frame.normal.y, &fg.frame.normal.z};
  const HyperDual<4>* mh[3] = {&fh.frame.normal.x, &fh.frame.normal.y, &fh.frame.normal.z};
  const Eigen::Vector3d qg = (1.0 - betaG) * g0 + betaG * g1;
  const Eigen::Vector3d qh = (1.0 - betaH) * h0 + betaH * h1;
  const double w = positionWeight, a = angleWeight;

  ConnectionDerivatives out;
  Vec16& g = out.gradient;
  Mat16& H = out.hessian;
  g.setZero();
  H.setZero();
  double energy = 0.0;
  for (int i = 0; i < 3; ++i) {
    // Gradient of d_i = qg_i - qh_i.
    Vec16 jd = Vec16::Zero();
    jd[kLower.start + i] = 1.0 - betaG;
    jd[kLower.end + i] = betaG;
    jd[kLower.beta] = g1[i] - g0[i];
    jd[kUpper.start + i] = -(1.0 - betaH);
    jd[kUpper.end + i] = -betaH;
    jd[kUpper.beta] = -(h1[i] - h0[i]);
    const Vec16 jmg = edgeGradient(*mg[i], kLower), jmh = edgeGradient(*mh[i], kUpper);
    const double d = qg[i] - qh[i];
    const double r1 = d + offset * mg[i]->v, r2 = -d - offset * mh[i]->v, r3 = mg[i]->v - mh[i]->v;
    energy += w * (r1 * r1 + r2 * r2) + a * r3 * r3;
    const Vec16 j1 = jd + offset * jmg, j2 = -jd - offset * jmh, j3 = jmg - jmh;
    g += (2.0 * w * r1) * j1 + (2.0 * w * r2) * j2 + (2.0 * a * r3) * j3;
    H.noalias() +=
        (2.0 * w) * (j1 * j1.transpose() + j2 * j2.transpose()) + (2.0 * a) * (j3 * j3.transpose());
    // Second derivatives of the residuals: the bolt points' beta-x terms, and the normals.
    const double onD = 2.0 * w * (r1 - r2);  // weight of Hess d_i
    const double pairs[4][3] = {{double(kLower.beta), double(kLower.start + i), -onD},
                                {double(kLower.beta), double(kLower.end + i), onD},
                                {double(kUpper.beta), double(kUpper.start + i), onD},
                                {double(kUpper.beta), double(kUpper.end + i), -onD}};
    for (const auto& [row, col, value] : pairs) {
      H(int(row), int(col)) += value;
      H(int(col), int(row)) += value;
    }
    addEdgeHessian(H, *mg[i], kLower, 2.0 * w * offset * r1 + 2.0 * a * r3);
    addEdgeHessian(H, *mh[i], kUpper, -2.0 * w * offset * r2 - 2.0 * a * r3);
  }
  out.energy = energy;
  return out;
}

}  // namespace egg::rods
