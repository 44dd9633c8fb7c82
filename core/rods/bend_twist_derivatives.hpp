#pragma once
// Closed-form gradient and Hessian of the bending and twisting energy of one interior vertex
// (Section 2.5; the energy is bendTwistEnergyOfEdges in rod_energies.hpp) over its 8 variables
// (e0, e1, theta0, theta1), assembled by the chain rule from per-edge frame derivatives.
//
// Bending: with the curvature binormal kb = 2 t0 x t1 / (1 + t0.t1) (= 2 e0 x e1 /
// (|e0||e1| + e0.e1)) and the four material curvatures w = kb.a (a = m1, m2 of either edge),
// E_b = sum c w^2, so grad E_b = sum 2 c w grad w and the Hessian is
// sum 2 c (grad w grad w^T + w Hess w) with Hess w = sum_i (a_i Hess kb_i + kb_i Hess a_i +
// grad kb_i grad a_i^T + grad a_i grad kb_i^T): kb depends on (e0, e1) only, a on one edge's
// (e, theta) only.
// Twisting: the material normal of an edge is its transported director u turned by theta about
// the tangent, and the space-parallel transport P from t0 to t1 is a rotation, so the signed
// angle from P m1_0 to m1_1 about t1 is theta1 - theta0 + r(e0, e1) (modulo 2 pi), where r is the
// same angle between P u0 and u1 (the reference twist). The twist therefore has gradient
// (grad r, -1, 1) and a Hessian that lives in the (e0, e1) block only.
// With t.u = 0 and |t| = 1 (identities of the functions, not only of their values), kb and r
// reduce to products of one quantity of e0 and one of e1 (bilinear: cheap exact derivatives):
// with c = t0.t1, w = t x u,
//   r = atan2(Y, X), X = c (u0.u1) - (t1.u0)(t0.u1) - (t1.w0)(t0.w1) / (1 + c),
//                    Y = -c (u0.w1) + (t1.u0)(t0.w1) - (t1.w0)(t0.u1) / (1 + c)
// (expanding P u0 = c u0 + v x u0 + (v.u0) v / (1 + c), v = t0 x t1, against u1 and t1 x u1).
// Only those few scalars are differentiated with HyperDual<6>; every other product is a small
// dense operation. The HyperDual<8> evaluation of the same energy stays the reference in the
// tests.
#include "core/rods/rod_energies.hpp"

#include <Eigen/Core>

namespace egg::rods {

// Material frame and transported reference director of one edge, differentiated with respect to
// (edge vector e, material angle theta): 4 variables, in that order.
struct EdgeFrameDerivatives {
  Frame<HyperDual<4>> frame;
  // Tangent t, transported reference director u and t x u: functions of the edge vector alone.
  V3<HyperDual<3>> tangent, director, binormal;
};

EdgeFrameDerivatives edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta,
                                          const EdgeReference& reference);
// The same written into `out` (the derivative pass keeps one per edge: no copy of its ~300
// numbers).
void edgeFrameDerivatives(const Eigen::Vector3d& edge, double theta, const EdgeReference& reference,
                          EdgeFrameDerivatives& out);

struct BendTwistDerivatives {
  double energy = 0.0;
  Eigen::Matrix<double, 8, 1> gradient;  // over (e0, e1, theta0, theta1)
  Eigen::Matrix<double, 8, 8> hessian;   // symmetric, both triangles filled
};

// f0, f1: the frames of the edges before and after the vertex (e0 = x1 - x0, e1 = x2 - x1),
// from edgeFrameDerivatives.
// `gaussNewton`: the Hessian without the curvatures' and the twist's own second derivatives,
// sum 2 c grad w grad w^T + k grad tw grad tw^T: positive semidefinite by construction (the
// projected Newton fallback's, rod_solver.hpp).
BendTwistDerivatives bendTwistDerivatives(const EdgeFrameDerivatives& f0,
                                          const EdgeFrameDerivatives& f1,
                                          const RodStiffness& stiffness, double voronoiLength,
                                          bool gaussNewton = false);

// The same over the stencil's unknowns (x0, x1, x2, theta0, theta1) with e0 = x1 - x0 and
// e1 = x2 - x1: gradient A^T g and Hessian A^T H A for the constant map A. Assembling these 11
// variables gives 66 Hessian entries per vertex instead of the ~130 overlapping ones of the
// 8-variable form.
struct BendTwistVertexDerivatives {
  double energy = 0.0;
  Eigen::Matrix<double, 11, 1> gradient;
  Eigen::Matrix<double, 11, 11> hessian;  // symmetric, both triangles filled
};
BendTwistVertexDerivatives onVertices(const BendTwistDerivatives& d);

}  // namespace egg::rods
