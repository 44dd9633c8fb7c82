#pragma once
// Shared by the energy and derivative tests: a random time-parallel reference frame near an edge,
// so that the reference twist and the transported director are exercised away from identity.
#include "core/rods/rod_energies.hpp"

#include <Eigen/Core>

#include <random>

namespace egg::rods::testing {

inline EdgeReference referenceNear(const Eigen::Vector3d& edge, std::mt19937& rng,
                                   double spread = 0.2) {
  std::normal_distribution<double> noise(0.0, spread);
  EdgeReference r;
  r.tangent =
      (edge.normalized() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).normalized();
  Eigen::Vector3d d(noise(rng), noise(rng), 1.0);
  d -= d.dot(r.tangent) * r.tangent;
  r.director = d.normalized();
  return r;
}

}  // namespace egg::rods::testing
