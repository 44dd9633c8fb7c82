// What the deployment stage (deployment.hpp) reads off a RodModel between solves: supports moved,
// their reactions, the forces on notch ends, crossing angles and the rods' strains.
#include "core/errors.hpp"
#include "core/rods/rod_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace egg::rods {

void RodModel::setAnchor(int anchor, const Eigen::Vector3d& position,
                         const Eigen::Vector3d& normal) {
  if (anchor < 0 || anchor >= anchorCount())
    throw InvalidInput("setAnchor: anchor " + std::to_string(anchor) + " of " +
                       std::to_string(anchorCount()));
  if (!(normal.norm() > 0.0) || !position.allFinite())
    throw InvalidInput("setAnchor: anchor " + std::to_string(anchor) +
                       " needs a finite position and a non-zero normal");
  AnchorData& a = anchors_[anchor];
  const Eigen::Vector3d n = normal.normalized();
  const RodData& r = rods_[a.point.rod];
  const double side = r.layer == 0 ? -0.5 : 0.5;
  a.target = position + side * r.thickness * n;
  a.targetNormal = n;
}

void RodModel::setAnchorActive(int anchor, bool active) {
  AnchorData& a = anchors_.at(anchor);
  a.positionWeight = active ? a.fullPositionWeight : 0.0;
  a.angleWeight = active ? a.fullAngleWeight : 0.0;
}

void RodModel::setAnchorWeight(int anchor, double factor) {
  if (anchor < 0 || anchor >= anchorCount() || !(factor >= 0.0 && factor <= 1.0))
    throw InvalidInput("setAnchorWeight: anchor " + std::to_string(anchor) + " of " +
                       std::to_string(anchorCount()) + ", factor " + std::to_string(factor) +
                       " (0..1)");
  AnchorData& a = anchors_[anchor];
  a.positionWeight = factor * a.fullPositionWeight;
  a.angleWeight = factor * a.fullAngleWeight;
}

void RodModel::setBoltWeight(int connection, double factor) {
  if (connection < 0 || connection >= boltCount() || !(factor >= 0.0 && factor <= 1.0))
    throw InvalidInput("setBoltWeight: connection " + std::to_string(connection) + " of " +
                       std::to_string(boltCount()) + ", factor " + std::to_string(factor) +
                       " (0..1)");
  Bolt& b = bolts_[connection];
  b.positionWeight = factor * b.fullPositionWeight;
  b.angleWeight = factor * b.fullAngleWeight;
}

Eigen::Vector3d RodModel::boltGap(int connection) const {
  const Bolt& b = bolts_.at(connection);
  const auto point = [&](const BoltSide& s) {
    const double t = beta(state_, s);  // a sliding bolt's coordinate is an unknown
    return ((1.0 - t) * vertex(s.point.rod, s.point.edge) +
            t * vertex(s.point.rod, s.point.edge + 1))
        .eval();
  };
  // E_q's residuals r1 = d + o m_lower, r2 = -d - o m_upper (connection_derivatives.cpp), d the
  // lower point less the upper: their half difference is the gap, upper from lower.
  const Eigen::Vector3d normals = edgeNormal(b.lower.point.rod, b.lower.point.edge) +
                                  edgeNormal(b.upper.point.rod, b.upper.point.edge);
  return point(b.upper) - point(b.lower) - 0.5 * b.offset * normals;
}

Eigen::Vector3d RodModel::boltForce(int connection) const {
  // dE/dq_lower = 2 w (r1 - r2) = -4 w gap.
  return 4.0 * stiffFactor_ * bolts_.at(connection).positionWeight * boltGap(connection);
}

void RodModel::anchorPlace(int anchor, Eigen::Vector3d& position, Eigen::Vector3d& normal) const {
  const AnchorData& a = anchors_.at(anchor);
  const Eigen::Vector3d q = (1.0 - a.point.beta) * vertex(a.point.rod, a.point.edge) +
                            a.point.beta * vertex(a.point.rod, a.point.edge + 1);
  normal = edgeNormal(a.point.rod, a.point.edge);
  const RodData& r = rods_[a.point.rod];
  const double side = r.layer == 0 ? -0.5 : 0.5;
  position = q - side * r.thickness * normal;
}

Eigen::Vector3d RodModel::anchorForce(int anchor) const {
  const AnchorData& a = anchors_.at(anchor);
  const Eigen::Vector3d q = (1.0 - a.point.beta) * vertex(a.point.rod, a.point.edge) +
                            a.point.beta * vertex(a.point.rod, a.point.edge + 1);
  return -2.0 * stiffFactor_ * a.positionWeight * (q - a.target);
}

double RodModel::notchEndForce(int connection, int side) const {
  const Bolt& b = bolts_.at(connection);
  const BoltSide& s = (side == 0) == b.aIsLower ? b.lower : b.upper;
  if (s.betaDof < 0) return 0.0;
  // E_n = unit (0.1 ln d)^2 within one edge of an end, d the distance in edges
  // (sliderEnergy, rod_energies.hpp): dE/dd = 0.02 unit ln(d) / d, a force of that over h. A notch
  // shorter than two edges holds the bolt within one edge of both ends: the force on the bolt is
  // the difference of the two barriers' pushes (each alone grows without bound as d -> 0 and would
  // report a centred bolt in a 1 mm notch as pressing with kilonewtons).
  const SliderParameters p = sliderParameters(s);
  const double at = (s.point.edge + state_[s.betaDof]) * p.edgeLength;
  const auto push = [&](double d) {
    return d < 1.0 && d > 0.0 ? -0.02 * p.unit * std::log(d) / d / p.edgeLength : 0.0;
  };
  return std::abs(push((at - p.notchMin) / p.edgeLength) - push((p.notchMax - at) / p.edgeLength));
}

double RodModel::crossingAngle(int connection) const {
  const Bolt& b = bolts_.at(connection);
  const auto tangent = [&](const BoltSide& s) {
    return (vertex(s.point.rod, s.point.edge + 1) - vertex(s.point.rod, s.point.edge)).normalized();
  };
  const double c = std::clamp(tangent(b.lower).dot(tangent(b.upper)), -1.0, 1.0);
  return std::acos(c);
}

std::vector<RodModel::VertexStrain> RodModel::vertexStrains(int rod) const {
  const RodData& r = rods_.at(rod);
  std::vector<VertexStrain> strains;
  const auto frameOfEdge = [&](int edge) {
    const V3<double> e = constant<double>(vertex(rod, edge + 1) - vertex(rod, edge));
    return materialFrame(e, state_[thetaDof(rod, edge)],
                         references_[edgeReferenceBase_[rod] + edge]);
  };
  for (int i = 1; i < r.edges; ++i) {
    const Eigen::Vector3d e0 = vertex(rod, i) - vertex(rod, i - 1);
    const Eigen::Vector3d e1 = vertex(rod, i + 1) - vertex(rod, i);
    const Eigen::Vector3d kb = 2.0 * e0.cross(e1) / (e0.norm() * e1.norm() + e0.dot(e1));
    const Frame<double> f0 = frameOfEdge(i - 1), f1 = frameOfEdge(i);
    const auto toEigen = [](const V3<double>& v) { return Eigen::Vector3d(v.x, v.y, v.z); };
    const Eigen::Vector3d side0 = toEigen(f0.side), side1 = toEigen(f1.side);
    const Eigen::Vector3d normal0 = toEigen(f0.normal), normal1 = toEigen(f1.normal);
    const Eigen::Vector3d t0 = toEigen(f0.tangent), t1 = toEigen(f1.tangent);
    // The same twist as bendTwistEnergyOfEdges: the first edge's normal carried to the second's
    // tangent, its angle to the second's normal about that tangent.
    const Eigen::Vector3d v = t0.cross(t1);
    const double c = t0.dot(t1);
    const Eigen::Vector3d carried =
        c * normal0 + v.cross(normal0) + (v.dot(normal0) / (c + 1.0)) * v;
    const double twist = std::atan2(carried.cross(normal1).dot(t1), carried.dot(normal1));
    const double voronoi = r.h;  // uniform rest edges: (h + h) / 2
    VertexStrain s;
    s.weakCurvature = 0.5 * (kb.dot(side0) + kb.dot(side1)) / voronoi;
    s.strongCurvature = 0.5 * (kb.dot(normal0) + kb.dot(normal1)) / voronoi;
    s.twistRate = twist / voronoi;
    strains.push_back(s);
  }
  return strains;
}

}  // namespace egg::rods
