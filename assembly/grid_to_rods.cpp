#include "assembly/grid_to_rods.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace egg::assembly {
namespace {

rods::Rod rodOf(const GridMember& member, const GridToRodsOptions& options, int layer) {
  rods::Rod rod;
  // The lamella is cut straight at its planar length; criterion (i) makes that equal to the
  // geodesic's length on the surface up to the grid's tolerance.
  rod.lengthM = member.planarLength;
  rod.section = options.section;
  rod.material.youngsModulusPa = options.material.youngsModulusPa;
  rod.material.shearModulusPa = options.material.shearModulusPa;
  rod.material.densityKgM3 = options.material.densityKgM3;
  rod.layer = layer;
  rod.guess = member.spatial;  // the traced geodesic: the deployment's initial guess
  rod.guessNormals = member.normals;
  return rod;
}

// The notch of one rod at a bolt: the bolt sits at s_bar in the cut lamella and should end at s
// on the surface, so the hole is elongated by |l| towards the sign of l = s - s_bar.
rods::Notch notchOf(double notchLength, bool enabled) {
  rods::Notch notch;
  if (!enabled) return notch;
  if (notchLength > 0.0) notch.afterM = notchLength;
  if (notchLength < 0.0) notch.beforeM = -notchLength;
  return notch;
}

double clampToRod(double s, double length) { return std::clamp(s, 0.0, length); }

// A support holding the connection where the design surface puts it (Section 2.4.6), on its u rod.
rods::Anchor anchorAt(const GridConnection& c, const rods::RodNetwork& network) {
  rods::Anchor anchor;
  anchor.rod = c.memberU;
  anchor.sM = clampToRod(c.sBarU, network.rods[anchor.rod].lengthM);
  anchor.position = c.spatial;
  anchor.normal = c.normal.normalized();
  return anchor;
}

}  // namespace

rods::RodNetwork rodNetworkFromGrid(const EggGrid& grid, const GridToRodsOptions& options) {
  rods::RodNetwork network;
  const int uCount = static_cast<int>(grid.u.size());
  const int uLayer = options.swapLayers ? 1 : 0;
  for (const auto& m : grid.u) network.rods.push_back(rodOf(m, options, uLayer));
  for (const auto& m : grid.v) network.rods.push_back(rodOf(m, options, 1 - uLayer));
  for (const auto& c : grid.connections) {
    rods::Connection bolt;
    bolt.rodA = c.memberU;
    bolt.rodB = uCount + c.memberV;
    const double lengthA = network.rods[bolt.rodA].lengthM;
    const double lengthB = network.rods[bolt.rodB].lengthM;
    bolt.sAM = clampToRod(c.sBarU, lengthA);
    bolt.sBM = clampToRod(c.sBarV, lengthB);
    // A notch cannot run past the lamella's end.
    bolt.notchA = notchOf(c.notchU, options.notches && !c.onBoundary);
    bolt.notchB = notchOf(c.notchV, options.notches && !c.onBoundary);
    bolt.notchA.afterM = std::min(bolt.notchA.afterM, lengthA - bolt.sAM);
    bolt.notchA.beforeM = std::min(bolt.notchA.beforeM, bolt.sAM);
    bolt.notchB.afterM = std::min(bolt.notchB.afterM, lengthB - bolt.sBM);
    bolt.notchB.beforeM = std::min(bolt.notchB.beforeM, bolt.sBM);
    network.connections.push_back(bolt);
  }
  for (const auto& a : grid.anchors) {
    network.anchors.push_back(anchorAt(grid.connections.at(a.connection), network));
  }
  return network;
}

rods::RodNetwork holdEverySide(rods::RodNetwork network, const EggGrid& grid) {
  std::vector<char> anchored(grid.connections.size(), 0);
  for (const auto& a : grid.anchors) anchored.at(a.connection) = 1;
  for (size_t c = 0; c < grid.connections.size(); ++c) {
    const GridConnection& connection = grid.connections[c];
    if (!connection.onBoundary || anchored[c]) continue;
    network.anchors.push_back(anchorAt(connection, network));
  }
  return network;
}

}  // namespace egg::assembly
