#include "assembly/flat_grid.hpp"

#include "core/errors.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace egg::assembly {

namespace {

// The planar layout in 3D with the plane's y axis along `mirror` (+1 or -1).
Eigen::Vector3d embed(const Eigen::Vector2d& p, double mirror) {
  return {p.x(), mirror * p.y(), 0.0};
}

struct Placement {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double rms = 0.0;
};

// The proper rotation and translation taking `from` closest to `to` (Kabsch).
Placement fit(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) a += from[i], b += to[i];
  a /= static_cast<double>(from.size());
  b /= static_cast<double>(to.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) h += (from[i] - a) * (to[i] - b).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  Placement p;
  p.rotation = svd.matrixV() * d * svd.matrixU().transpose();
  p.translation = b - p.rotation * a;
  double sum = 0.0;
  for (size_t i = 0; i < from.size(); ++i)
    sum += (p.rotation * from[i] + p.translation - to[i]).squaredNorm();
  p.rms = std::sqrt(sum / static_cast<double>(from.size()));
  return p;
}

}  // namespace

FlatGrid flatGrid(const EggGrid& grid, const rods::RodNetwork& deployed) {
  const size_t uCount = grid.u.size(), rodCount = uCount + grid.v.size();
  if (deployed.rods.size() != rodCount || deployed.connections.size() != grid.connections.size())
    throw InvalidInput("flat grid: the rod network has " + std::to_string(deployed.rods.size()) +
                       " rods and " + std::to_string(deployed.connections.size()) +
                       " bolts, the grid " + std::to_string(rodCount) + " members and " +
                       std::to_string(grid.connections.size()) + " connections");
  if (grid.connections.size() < 3)
    throw InvalidInput("flat grid: fewer than 3 connections to place the flat grid by");
  const auto member = [&](size_t r) -> const GridMember& {
    return r < uCount ? grid.u[r] : grid.v[r - uCount];
  };
  // Place the layout both ways up; keep the one whose layer 1 side (the side the lamella normals
  // point to, rod_network.hpp) faces the deployed normals, then the better fit.
  std::vector<Eigen::Vector3d> spatial;
  Eigen::Vector3d meanNormal = Eigen::Vector3d::Zero();
  for (const GridConnection& c : grid.connections) {
    spatial.push_back(c.spatial);
    meanNormal += c.normal;
  }
  // Which way the planar u and v directions turn, seen from the layer 1 side, must survive the
  // deployment (it is continuous): compare with the deployed members' directions at the bolts.
  double planarTurn = 0.0, spatialTurn = 0.0;
  for (const GridConnection& c : grid.connections) {
    const GridMember& u = grid.u[c.memberU];
    const GridMember& v = grid.v[c.memberV];
    const Eigen::Vector2d du = u.planarEnd - u.planarStart, dv = v.planarEnd - v.planarStart;
    planarTurn += du.x() * dv.y() - du.y() * dv.x();
    if (u.spatial.size() >= 2 && v.spatial.size() >= 2) {
      const auto direction = [&](const GridMember& m) {
        size_t best = 0;
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < m.spatial.size(); ++i) {
          const double d = (m.spatial[i] - c.spatial).squaredNorm();
          if (d < nearest) nearest = d, best = i;
        }
        const size_t i0 = best == 0 ? 0 : best - 1, i1 = std::min(best + 1, m.spatial.size() - 1);
        return (m.spatial[i1] - m.spatial[i0]).normalized().eval();
      };
      spatialTurn += c.normal.dot(direction(u).cross(direction(v)));
    }
  }
  const double handedness = (planarTurn >= 0.0) == (spatialTurn >= 0.0) ? 1.0 : -1.0;
  FlatGrid result;
  Placement best;
  Eigen::Vector3d bestNormal = Eigen::Vector3d::UnitZ();
  double bestMirror = 1.0;
  bool found = false;
  for (const double mirror : {1.0, -1.0}) {
    std::vector<Eigen::Vector3d> planar;
    for (const GridConnection& c : grid.connections) planar.push_back(embed(c.planar, mirror));
    const Placement p = fit(planar, spatial);
    // The layout's normal with the planar turn seen positive is +z when not mirrored.
    const Eigen::Vector3d normal = p.rotation * Eigen::Vector3d(0.0, 0.0, mirror * handedness);
    const bool faces = normal.dot(meanNormal) > 0.0;
    if (!faces) continue;
    if (!found || p.rms < best.rms)
      best = p, bestNormal = normal, bestMirror = mirror, found = true;
  }
  if (!found)
    throw InvalidInput(
        "flat grid: no placement of the planar grid keeps its layers on the "
        "sides of the deployed normals");
  result.placementRmsM = best.rms;
  result.network = deployed;
  const auto place = [&](const Eigen::Vector2d& p) {
    return (best.rotation * embed(p, bestMirror) + best.translation).eval();
  };
  for (size_t r = 0; r < rodCount; ++r) {
    const GridMember& m = member(r);
    rods::Rod& rod = result.network.rods[r];
    rod.guess = {place(m.planarStart), place(m.planarEnd)};
    rod.guessNormals = {bestNormal, bestNormal};
  }
  const auto pointOn = [&](int r, double s) {
    const rods::Rod& rod = result.network.rods[r];
    const double f = rod.lengthM > 0.0 ? s / rod.lengthM : 0.0;
    return (rod.guess[0] + f * (rod.guess[1] - rod.guess[0])).eval();
  };
  for (size_t k = 0; k < result.network.connections.size(); ++k) {
    rods::Connection& c = result.network.connections[k];
    c.startAM = c.sAM;
    c.startBM = c.sBM;
    const double misfit = (pointOn(c.rodA, c.sAM) - pointOn(c.rodB, c.sBM)).norm();
    if (misfit > result.boltMisfitMaxM)
      result.boltMisfitMaxM = misfit, result.boltMisfitMaxConnection = static_cast<int>(k);
  }
  for (size_t a = 0; a < deployed.anchors.size(); ++a) {
    const rods::Anchor& anchor = deployed.anchors[a];
    const rods::Rod& rod = result.network.rods[anchor.rod];
    const double f = rod.lengthM > 0.0 ? anchor.sM / rod.lengthM : 0.0;
    const Eigen::Vector3d p = rod.guess[0] + f * (rod.guess[1] - rod.guess[0]);
    result.network.anchors[a].position = p;
    result.network.anchors[a].normal = bestNormal;
    result.flat.positions.push_back(p);
    result.flat.normals.push_back(bestNormal);
    result.deployed.positions.push_back(anchor.position);
    result.deployed.normals.push_back(anchor.normal.normalized());
  }
  return result;
}

}  // namespace egg::assembly
