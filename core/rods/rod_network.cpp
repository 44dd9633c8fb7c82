#include "core/rods/rod_network.hpp"

#include "core/errors.hpp"

#include <cmath>
#include <string>
#include <tuple>

namespace egg::rods {

namespace {

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

void checkPosition(const RodNetwork& network, int rod, double s, const std::string& what) {
  if (rod < 0 || rod >= static_cast<int>(network.rods.size())) {
    throw InvalidInput(what + " refers to rod " + std::to_string(rod) + ", but there are " +
                       std::to_string(network.rods.size()) + " rods");
  }
  const double length = network.rods[rod].lengthM;
  if (!(s >= -1e-9 * length && s <= length * (1.0 + 1e-9))) {
    throw InvalidInput(what + " lies at s = " + std::to_string(s) + " m, outside rod " +
                       std::to_string(rod) + " of length " + std::to_string(length) + " m");
  }
}

}  // namespace

void validateNetwork(const RodNetwork& network) {
  if (network.rods.empty()) throw InvalidInput("rod network: no rods");
  for (size_t r = 0; r < network.rods.size(); ++r) {
    const Rod& rod = network.rods[r];
    const std::string name = "rod " + std::to_string(r);
    if (!(rod.lengthM > 0.0) || !std::isfinite(rod.lengthM))
      throw InvalidInput(name + ": length_m must be > 0");
    if (!(rod.section.widthM > 0.0) || !(rod.section.thicknessM > 0.0)) {
      throw InvalidInput(name + ": section width_m and thickness_m must be > 0");
    }
    if (!(rod.material.youngsModulusPa > 0.0) || !(rod.material.shearModulusPa > 0.0)) {
      throw InvalidInput(name + ": material youngs_modulus_pa and shear_modulus_pa must be > 0");
    }
    if (!(rod.material.densityKgM3 >= 0.0))
      throw InvalidInput(name + ": material density_kg_m3 must be >= 0");
    if (rod.layer != 0 && rod.layer != 1) throw InvalidInput(name + ": layer must be 0 or 1");
    if (rod.guess.size() < 2) throw InvalidInput(name + ": guess needs at least 2 points");
    if (rod.guessNormals.size() != rod.guess.size()) {
      throw InvalidInput(name + ": guessNormals must have one normal per guess point");
    }
    double guessLength = 0.0;
    for (size_t i = 0; i < rod.guess.size(); ++i) {
      if (!finite(rod.guess[i]) || !finite(rod.guessNormals[i]) ||
          rod.guessNormals[i].norm() < 1e-12) {
        throw InvalidInput(name + ": guess point or normal " + std::to_string(i) +
                           " is not finite or zero");
      }
      if (i > 0) guessLength += (rod.guess[i] - rod.guess[i - 1]).norm();
    }
    if (!(guessLength > 0.0)) throw InvalidInput(name + ": guess polyline has zero length");
  }
  for (size_t c = 0; c < network.connections.size(); ++c) {
    const Connection& con = network.connections[c];
    const std::string name = "connection " + std::to_string(c);
    checkPosition(network, con.rodA, con.sAM, name + " (rod a)");
    checkPosition(network, con.rodB, con.sBM, name + " (rod b)");
    if (con.rodA == con.rodB)
      throw InvalidInput(name + ": joins rod " + std::to_string(con.rodA) + " to itself");
    if (network.rods[con.rodA].layer == network.rods[con.rodB].layer) {
      throw InvalidInput(name + ": rods " + std::to_string(con.rodA) + " and " +
                         std::to_string(con.rodB) + " are in the same layer");
    }
    for (const auto& [notch, rod, s] :
         {std::tuple{con.notchA, con.rodA, con.sAM}, std::tuple{con.notchB, con.rodB, con.sBM}}) {
      if (!(notch.beforeM >= 0.0) || !(notch.afterM >= 0.0)) {
        throw InvalidInput(name + ": notch lengths must be >= 0");
      }
      checkPosition(network, rod, s - notch.beforeM, name + " (notch start)");
      checkPosition(network, rod, s + notch.afterM, name + " (notch end)");
    }
    for (const auto& [start, rod, s, notch] :
         {std::tuple{con.startAM, con.rodA, con.sAM, con.notchA},
          std::tuple{con.startBM, con.rodB, con.sBM, con.notchB}}) {
      if (start && !(*start >= s - notch.beforeM - 1e-9 && *start <= s + notch.afterM + 1e-9)) {
        throw InvalidInput(name + ": start position " + std::to_string(*start) +
                           " m lies outside the notch of rod " + std::to_string(rod));
      }
    }
  }
  for (size_t a = 0; a < network.anchors.size(); ++a) {
    const Anchor& anchor = network.anchors[a];
    const std::string name = "anchor " + std::to_string(a);
    checkPosition(network, anchor.rod, anchor.sM, name);
    if (!finite(anchor.position) || !finite(anchor.normal) || anchor.normal.norm() < 1e-12) {
      throw InvalidInput(name + ": position/normal not finite or zero normal");
    }
  }
}

}  // namespace egg::rods
