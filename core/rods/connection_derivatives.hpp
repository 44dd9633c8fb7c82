#pragma once
// Closed-form gradient and Hessian of the connection energy E_q of one bolt (Section 2.5; the
// energy is connectionEnergy in rod_energies.hpp) over its 16 variables
// (g0, g1, theta_g, beta_g, h0, h1, theta_h, beta_h), from the precomputed edge frames.
// E_q = w (|r1|^2 + |r2|^2) + a |r3|^2 with r1 = q_g - q_h + t m_g, r2 = q_h - q_g - t m_h,
// r3 = m_g - m_h: gradient 2 sum weight J^T r, Hessian 2 sum weight (J^T J + sum_i r_i Hess r_i),
// where the bolt points q = (1 - beta) x0 + beta x1 are bilinear (Hess: d^2 q_i / d beta d x1_i =
// 1, d^2 q_i / d beta d x0_i = -1) and the normals m carry their edge's 4-variable derivatives.
// The HyperDual<16> evaluation of the same energy stays the reference in the tests.
#include "core/rods/bend_twist_derivatives.hpp"

#include <Eigen/Core>

namespace egg::rods {

struct ConnectionDerivatives {
  double energy = 0.0;
  Eigen::Matrix<double, 16, 1> gradient;
  Eigen::Matrix<double, 16, 16> hessian;  // symmetric, both triangles filled
};

// g0, g1 (h0, h1): the vertices of the lower (upper) rod's edge holding the bolt, fg (fh) that
// edge's frame derivatives (edge vector g1 - g0), betaG (betaH) the bolt's barycentric coordinate.
ConnectionDerivatives connectionDerivatives(const Eigen::Vector3d& g0, const Eigen::Vector3d& g1,
                                            const EdgeFrameDerivatives& fg, double betaG,
                                            const Eigen::Vector3d& h0, const Eigen::Vector3d& h1,
                                            const EdgeFrameDerivatives& fh, double betaH,
                                            double offset, double positionWeight,
                                            double angleWeight);

}  // namespace egg::rods
