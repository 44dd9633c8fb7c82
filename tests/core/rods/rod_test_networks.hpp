#pragma once
// Small rod networks shared by the rod model tests: straight rods, two rods crossing at a bolt,
// and a small bolted vault.
#include "core/rods/rod_model.hpp"
#include "core/rods/rod_network.hpp"
#include "core/rods/sample_grids.hpp"

#include <Eigen/Core>

namespace egg::rods::testing {

inline Rod straight(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int layer) {
  Rod rod;
  rod.lengthM = (to - from).norm();
  rod.section = {0.02, 0.002};
  rod.material = {10.0e9, 3.8e9, 600.0};
  rod.layer = layer;
  rod.guess = {from, to};
  rod.guessNormals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
  return rod;
}

// Rod 0 along x from the origin (layer 0), rod 1 along y through x = crossing (layer 1), one bolt
// at the crossing drilled at sA along rod 0.
inline RodNetwork crossing(double sA, double crossingX, Notch notchA) {
  RodNetwork network;
  network.rods.push_back(straight({0, 0, 0}, {1, 0, 0}, 0));
  network.rods.push_back(straight({crossingX, -0.5, 0}, {crossingX, 0.5, 0}, 1));
  Connection c;
  c.rodA = 0;
  c.sAM = sA;
  c.rodB = 1;
  c.sBM = 0.5;
  c.notchA = notchA;
  network.connections.push_back(c);
  return network;
}

inline ModelOptions edges(int n) {
  ModelOptions options;
  options.minEdgesPerRod = n;
  options.maxEdgesPerRod = n;
  return options;
}

// A 3 x 3 m cylindrical vault of 50 x 5 mm lamellas at 0.75 m, notched (cylinderGrid's default
// notch fraction).
inline SampleGrid smallVault() {
  CylinderGridParameters parameters;
  parameters.radiusM = 3.0;
  parameters.halfAngleRad = 0.6;
  parameters.lengthM = 3.0;
  parameters.spacingM = 0.75;
  parameters.section = {0.05, 0.005};
  parameters.meshEdgeM = 0.05;  // chordal error 0.05^2 / (8 R) = 0.1 mm, well below t/2
  return cylinderGrid(parameters);
}

}  // namespace egg::rods::testing
