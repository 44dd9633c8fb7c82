#pragma once
// Closed-form gradient and Hessian of the stretching energy of one edge (rod_energies.hpp
// stretchingEnergy, Section 2.5) over its two vertices (x0, x1). With e = x1 - x0, t = e / |e|
// and the strain eps = |e| / h - 1, E = k h eps^2 / 2, so dE/de = k eps t and
// d2E/de2 = (k / h) t t^T + (k eps / |e|) (I - t t^T); x0 enters with the opposite sign. In the
// derivative pass this replaces a HyperDual<6> evaluation whose initialisation alone (six
// 44-entry duals zeroed and copied per edge) cost more than the arithmetic.
// The local Hessian has eigenvalues 2k/h (along t, the vertices moving apart), 2k eps/|e| (twice,
// across t) and 0 (rigid translations): its nearest positive semidefinite matrix, which the
// projected Newton fallback needs (rod_solver.hpp), only drops the transverse term of a
// compressed edge (eps < 0), with no eigendecomposition.
#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace egg::rods {

struct StretchingDerivatives {
  double energy = 0.0;
  Eigen::Matrix<double, 6, 1> gradient;  // over (x0, x1)
  Eigen::Matrix<double, 6, 6> hessian;   // symmetric, both triangles filled
};

// `projected`: the Hessian's nearest positive semidefinite matrix instead (see above).

inline StretchingDerivatives stretchingDerivatives(const Eigen::Vector3d& x0,
                                                   const Eigen::Vector3d& x1, double stiffness,
                                                   double restLength, bool projected = false) {
  const Eigen::Vector3d e = x1 - x0;
  const double length = e.norm();
  const Eigen::Vector3d t = e / length;
  const double strain = length / restLength - 1.0;
  StretchingDerivatives d;
  d.energy = 0.5 * stiffness * restLength * strain * strain;
  const Eigen::Vector3d g = (stiffness * strain) * t;
  d.gradient << -g, g;
  const Eigen::Matrix3d tt = t * t.transpose();
  const double transverse = stiffness * strain / length;
  const Eigen::Matrix3d k =
      (stiffness / restLength) * tt +
      (projected ? std::max(transverse, 0.0) : transverse) * (Eigen::Matrix3d::Identity() - tt);
  d.hessian << k, -k, -k, k;
  return d;
}

}  // namespace egg::rods
