#include "core/rods/rod_model.hpp"

#include "core/errors.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>

namespace egg::rods {

namespace {

Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& t) {
  Eigen::Vector3d a = std::abs(t.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - a.dot(t) * t).normalized();
}

}  // namespace

void ModelOptions::validate() const {
  if (!(targetEdgeLengthM >= 0.0))
    throw InvalidInput("ModelOptions.targetEdgeLength_m must be >= 0");
  if (minEdgesPerRod < 2) throw InvalidInput("ModelOptions.minEdgesPerRod must be >= 2");
  if (maxEdgesPerRod < minEdgesPerRod)
    throw InvalidInput("ModelOptions.maxEdgesPerRod must be >= minEdgesPerRod");
  if (!(gravityMPerS2 >= 0.0)) throw InvalidInput("ModelOptions.gravity_m_s2 must be >= 0");
  if (!(frictionMu >= 0.0)) throw InvalidInput("ModelOptions.frictionMu must be >= 0");
  if (!(frictionEpsilon > 0.0 && frictionEpsilon < 0.5))
    throw InvalidInput("ModelOptions.frictionEpsilon must be in (0, 0.5)");
  if (!(connectionWeight > 0.0)) throw InvalidInput("ModelOptions.connectionWeight must be > 0");
  if (!(connectionAngleWeight > 0.0))
    throw InvalidInput("ModelOptions.connectionAngleWeight must be > 0");
  if (!(anchorWeight > 0.0)) throw InvalidInput("ModelOptions.anchorWeight must be > 0");
  if (!(anchorAngleWeight > 0.0)) throw InvalidInput("ModelOptions.anchorAngleWeight must be > 0");
  if (!(fastenedJointWeight > 0.0))
    throw InvalidInput("ModelOptions.fastenedJointWeight must be > 0");
}

RodStiffness stiffnessOf(const Rod& rod) {
  const double w = rod.section.widthM, t = rod.section.thicknessM;
  const double e = rod.material.youngsModulusPa, g = rod.material.shearModulusPa;
  RodStiffness s;
  s.stretching = e * w * t;
  s.bendingWeak = e * w * t * t * t / 12.0;
  s.bendingStrong = e * t * w * w * w / 12.0;
  // Thin-strip torsion constant w t^3 / 3 (the brief's choice); for w/t = 5 it overestimates the
  // exact rectangle value by about 7 %.
  s.twisting = g * w * t * t * t / 3.0;
  return s;
}

RodModel::RodModel(const RodNetwork& network, const ModelOptions& options) : options_(options) {
  validateNetwork(network);
  options.validate();

  // Edge length: a third of the median bolt spacing, so bolts can slide across vertices and the
  // centreline between bolts bends smoothly.
  double targetEdge = options.targetEdgeLengthM;
  if (targetEdge <= 0.0) {
    std::vector<std::vector<double>> positions(network.rods.size());
    for (const auto& c : network.connections) {
      positions[c.rodA].push_back(c.sAM);
      positions[c.rodB].push_back(c.sBM);
    }
    std::vector<double> spacings;
    for (auto& p : positions) {
      std::sort(p.begin(), p.end());
      for (size_t i = 1; i < p.size(); ++i) {
        if (p[i] - p[i - 1] > 1e-9) spacings.push_back(p[i] - p[i - 1]);
      }
    }
    if (!spacings.empty()) {
      std::nth_element(spacings.begin(), spacings.begin() + spacings.size() / 2, spacings.end());
      targetEdge = spacings[spacings.size() / 2] / 3.0;
    } else {
      double longest = 0.0;
      for (const auto& r : network.rods) longest = std::max(longest, r.lengthM);
      targetEdge = longest / 20.0;
    }
  }

  int dof = 0;
  for (const Rod& rod : network.rods) {
    RodData data;
    data.edges = std::clamp(static_cast<int>(std::ceil(rod.lengthM / targetEdge - 1e-9)),
                            options.minEdgesPerRod, options.maxEdgesPerRod);
    data.length = rod.lengthM;
    data.h = rod.lengthM / data.edges;
    data.thickness = rod.section.thicknessM;
    data.layer = rod.layer;
    data.linearDensity = rod.material.densityKgM3 * rod.section.widthM * rod.section.thicknessM;
    data.stiffness = stiffnessOf(rod);
    data.firstVertexDof = dof;
    dof += 3 * (data.edges + 1);
    data.firstThetaDof = dof;
    dof += data.edges;
    rods_.push_back(data);
  }

  auto pointAt = [&](int rod, double s) {
    const RodData& r = rods_[rod];
    RodPoint p;
    p.rod = rod;
    p.edge = std::clamp(static_cast<int>(std::floor(s / r.h)), 0, r.edges - 1);
    p.beta = s / r.h - p.edge;
    return p;
  };

  std::vector<std::array<bool, 2>> startGiven;  // per bolt: lower, upper side start given
  for (const Connection& c : network.connections) {
    const bool aLower = network.rods[c.rodA].layer == 0;
    Bolt bolt;
    auto makeSide = [&](int rod, double s, const Notch& notch, const std::optional<double>& start) {
      BoltSide side;
      const double length = notch.beforeM + notch.afterM;
      if (options.notches && length > 1e-6 * rods_[rod].h) {
        side.notchMin = s - notch.beforeM;
        side.notchMax = s + notch.afterM;
        // Start strictly inside the notch: the log barrier E_n is infinite at its ends.
        const double margin = 0.01 * length;
        s = std::clamp(start.value_or(s), side.notchMin + margin, side.notchMax - margin);
        side.betaDof = dof++;
      }
      side.point = pointAt(rod, s);
      return side;
    };
    BoltSide sideA = makeSide(c.rodA, c.sAM, c.notchA, c.startAM);
    BoltSide sideB = makeSide(c.rodB, c.sBM, c.notchB, c.startBM);
    bolt.aIsLower = aLower;
    bolt.lower = aLower ? sideA : sideB;
    bolt.upper = aLower ? sideB : sideA;
    const bool startA = c.startAM.has_value(), startB = c.startBM.has_value();
    startGiven.push_back({aLower ? startA : startB, aLower ? startB : startA});
    const RodData& ra = rods_[c.rodA];
    const RodData& rb = rods_[c.rodB];
    bolt.offset = 0.5 * (ra.thickness + rb.thickness);
    bolt.positionWeight = options.connectionWeight *
                          std::min(ra.stiffness.stretching / ra.h, rb.stiffness.stretching / rb.h);
    bolt.angleWeight = options.connectionAngleWeight *
                       std::min(ra.stiffness.twisting / ra.h, rb.stiffness.twisting / rb.h);
    bolt.fullPositionWeight = bolt.positionWeight;
    bolt.fullAngleWeight = bolt.angleWeight;
    bolts_.push_back(bolt);
  }
  dofCount_ = dof;

  // Initial state: the guess polylines resampled at the rest arc length (proportionally), moved
  // off the design surface by half a thickness towards the rod's layer.
  state_ = Eigen::VectorXd::Zero(dofCount_);
  for (int r = 0; r < rodCount(); ++r) {
    const Rod& rod = network.rods[r];
    const RodData& data = rods_[r];
    std::vector<double> cumulative(rod.guess.size(), 0.0);
    for (size_t i = 1; i < rod.guess.size(); ++i) {
      cumulative[i] = cumulative[i - 1] + (rod.guess[i] - rod.guess[i - 1]).norm();
    }
    const double side = rod.layer == 0 ? -0.5 : 0.5;
    std::vector<Eigen::Vector3d> normals(data.edges + 1);
    size_t segment = 0;
    for (int i = 0; i <= data.edges; ++i) {
      const double target = cumulative.back() * i / data.edges;
      while (segment + 2 < rod.guess.size() && cumulative[segment + 1] < target) ++segment;
      const double span = cumulative[segment + 1] - cumulative[segment];
      const double f =
          span > 0.0 ? std::clamp((target - cumulative[segment]) / span, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d p = (1.0 - f) * rod.guess[segment] + f * rod.guess[segment + 1];
      normals[i] = ((1.0 - f) * rod.guessNormals[segment].normalized() +
                    f * rod.guessNormals[segment + 1].normalized())
                       .normalized();
      state_.segment<3>(vertexDof(r, i)) = p + side * data.thickness * normals[i];
    }
    for (int j = 0; j < data.edges; ++j) {
      EdgeReference ref;
      ref.tangent = (vertex(r, j + 1) - vertex(r, j)).normalized();
      Eigen::Vector3d n = normals[j] + normals[j + 1];
      n -= n.dot(ref.tangent) * ref.tangent;
      ref.director = n.norm() > 1e-9 ? n.normalized() : anyPerpendicular(ref.tangent);
      references_.push_back(ref);
    }
  }
  edgeReferenceBase_.resize(rods_.size());
  for (int r = 0, base = 0; r < rodCount(); ++r) {
    edgeReferenceBase_[r] = base;
    base += rods_[r].edges;
  }
  // A sliding bolt starts where the two guess curves actually cross within its notch: the guess
  // is the deployed (geodesic) state while the drilled position is the planar one, and the two
  // differ by up to the notch length (Section 2.4.5). Two alternating passes suffice.
  auto pointPosition = [&](const RodPoint& p) {
    return ((1.0 - p.beta) * vertex(p.rod, p.edge) + p.beta * vertex(p.rod, p.edge + 1)).eval();
  };
  // A side whose start is given (Connection::startAM/startBM) stays there.
  for (size_t k = 0; k < bolts_.size(); ++k) {
    Bolt& b = bolts_[k];
    for (int pass = 0; pass < 2; ++pass) {
      for (auto [side, other, given] : {std::tuple{&b.lower, &b.upper, startGiven[k][0]},
                                        std::tuple{&b.upper, &b.lower, startGiven[k][1]}}) {
        if (side->betaDof < 0 || given) continue;
        const Eigen::Vector3d target = pointPosition(other->point);
        const double margin = 0.01 * (side->notchMax - side->notchMin);
        const double from = side->notchMin + margin, to = side->notchMax - margin;
        double best = (side->point.edge + side->point.beta) * rods_[side->point.rod].h;
        double bestDistance = (pointPosition(side->point) - target).norm();
        constexpr int samples = 64;
        for (int k = 0; k <= samples; ++k) {
          const double arc = from + (to - from) * k / samples;
          const double distance = (pointPosition(pointAt(side->point.rod, arc)) - target).norm();
          if (distance < bestDistance) {
            bestDistance = distance;
            best = arc;
          }
        }
        side->point = pointAt(side->point.rod, best);
      }
    }
    for (const BoltSide* s : {&b.lower, &b.upper}) {
      if (s->betaDof >= 0) state_[s->betaDof] = s->point.beta;
    }
  }

  for (const Anchor& a : network.anchors) {
    AnchorData data;
    data.point = pointAt(a.rod, a.sM);
    const Eigen::Vector3d n = a.normal.normalized();
    const double side = network.rods[a.rod].layer == 0 ? -0.5 : 0.5;
    data.target = a.position + side * rods_[a.rod].thickness * n;
    data.targetNormal = n;
    const RodData& r = rods_[a.rod];
    data.positionWeight = options.anchorWeight * r.stiffness.stretching / r.h;
    data.angleWeight = options.anchorAngleWeight * r.stiffness.twisting / r.h;
    data.fullPositionWeight = data.positionWeight;
    data.fullAngleWeight = data.angleWeight;
    anchors_.push_back(data);
  }

  fixed_.assign(dofCount_, false);
  baseConstantGradient_ = Eigen::VectorXd::Zero(dofCount_);
  double heaviest = 0.0, stiffest = 0.0;
  for (int r = 0; r < rodCount(); ++r) {
    const RodData& data = rods_[r];
    heaviest = std::max(heaviest, data.linearDensity * data.length * options.gravityMPerS2);
    stiffest = std::max(stiffest, data.stiffness.bendingWeak / (data.length * data.length));
    energyUnit_ = std::max(energyUnit_, data.stiffness.bendingWeak / data.length);
    if (!options.gravity) continue;
    for (int i = 0; i <= data.edges; ++i) {
      const double mass = data.linearDensity * data.h * ((i == 0 || i == data.edges) ? 0.5 : 1.0);
      baseConstantGradient_[vertexDof(r, i) + 2] += mass * options.gravityMPerS2;
    }
  }
  forceScale_ = std::max(stiffest, options.gravity ? heaviest : 0.0);
  constantGradient_ = baseConstantGradient_;
}

// ---------------------------------------------------------------- accessors, loads

std::vector<Eigen::Vector3d> RodModel::centreline(int rod) const {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < vertexCount(rod); ++i) points.push_back(vertex(rod, i));
  return points;
}

Eigen::Vector3d RodModel::edgeNormal(int rod, int edge) const {
  const V3<double> e = constant<double>(vertex(rod, edge + 1) - vertex(rod, edge));
  const Frame<double> f =
      materialFrame(e, state_[thetaDof(rod, edge)], references_[edgeReferenceBase_[rod] + edge]);
  return {f.normal.x, f.normal.y, f.normal.z};
}

Eigen::Vector3d RodModel::vertexNormal(int rod, int vertex) const {
  const int edges = rods_[rod].edges;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  if (vertex > 0) n += edgeNormal(rod, vertex - 1);
  if (vertex < edges) n += edgeNormal(rod, vertex);
  return n.normalized();
}

double RodModel::boltPosition(int connection, int side) const {
  const Bolt& b = bolts_[connection];
  const BoltSide& s = (side == 0) == b.aIsLower ? b.lower : b.upper;
  return (s.point.edge + beta(state_, s)) * rods_[s.point.rod].h;
}

Eigen::Vector3d RodModel::contactPoint(int rod, int vertex) const {
  const double side = rods_[rod].layer == 0 ? -0.5 : 0.5;
  return this->vertex(rod, vertex) - side * rods_[rod].thickness * vertexNormal(rod, vertex);
}

int RodModel::slidingSideCount() const {
  int n = 0;
  for (const Bolt& b : bolts_) n += (b.lower.betaDof >= 0) + (b.upper.betaDof >= 0);
  return n;
}

void RodModel::fixVertex(int rod, int vertex, bool x, bool y, bool z) {
  const int d = vertexDof(rod, vertex);
  if (x) fixed_[d] = true;
  if (y) fixed_[d + 1] = true;
  if (z) fixed_[d + 2] = true;
}

void RodModel::fixTwist(int rod, int edge) { fixed_[thetaDof(rod, edge)] = true; }

void RodModel::fastenBolts() {
  for (Bolt& b : bolts_) {
    for (const BoltSide* s : {&b.lower, &b.upper})
      if (s->betaDof >= 0) fixed_[s->betaDof] = true;
    const Eigen::Vector3d eg = (vertex(b.lower.point.rod, b.lower.point.edge + 1) -
                                vertex(b.lower.point.rod, b.lower.point.edge))
                                   .normalized();
    const Eigen::Vector3d eh = (vertex(b.upper.point.rod, b.upper.point.edge + 1) -
                                vertex(b.upper.point.rod, b.upper.point.edge))
                                   .normalized();
    // The axis of the signed sine: the lower lamella's normal at the bolt, along e_g x e_h up to
    // the small tilt between the two lamellas, and defined where they are parallel.
    b.fastenedAxis = edgeNormal(b.lower.point.rod, b.lower.point.edge);
    b.fastenedCos = eg.dot(eh);
    b.fastenedSin = eg.cross(eh).dot(b.fastenedAxis);
    const RodData& lower = rods_[b.lower.point.rod];
    const RodData& upper = rods_[b.upper.point.rod];
    const double softer =
        std::min(lower.stiffness.bendingStrong / lower.h, upper.stiffness.bendingStrong / upper.h);
    // E ~ weight (alpha - alpha0)^2 is a spring of stiffness 2 weight.
    b.fastenedWeight = 0.5 * options_.fastenedJointWeight * softer;
  }
  fastened_ = true;
}

void RodModel::setVertex(int rod, int vertex, const Eigen::Vector3d& p) {
  Eigen::VectorXd z = state_;
  z.segment<3>(vertexDof(rod, vertex)) = p;
  accept(z);
}

void RodModel::addPointLoad(int rod, int vertex, const Eigen::Vector3d& force) {
  pointLoads_.push_back({vertexDof(rod, vertex), force});
  baseConstantGradient_.segment<3>(vertexDof(rod, vertex)) -= force;
  constantGradient_ = loadFactor_ * baseConstantGradient_;
  forceScale_ = std::max(forceScale_, force.norm());
}

void RodModel::setLoadFactor(double factor) {
  loadFactor_ = factor;
  constantGradient_ = factor * baseConstantGradient_;
}

void RodModel::addEndMoment(int rod, const Eigen::Vector3d& axis, double moment) {
  EndMoment m;
  m.rod = rod;
  m.axis = axis.normalized();
  m.moment = moment;
  const int n = rods_[rod].edges;
  Eigen::Vector3d d = vertex(rod, n) - vertex(rod, n - 1);
  d -= d.dot(m.axis) * m.axis;
  m.direction = d.normalized();
  endMoments_.push_back(m);
  forceScale_ = std::max(forceScale_, std::abs(moment) / rods_[rod].length);
}

int RodModel::accept(const Eigen::VectorXd& z) {
  state_ = z;
  for (int r = 0; r < rodCount(); ++r) {
    for (int j = 0; j < rods_[r].edges; ++j) {
      EdgeReference& ref = references_[edgeReferenceBase_[r] + j];
      const Eigen::Vector3d t = (vertex(r, j + 1) - vertex(r, j)).normalized();
      const V3<double> u = parallelTransport(constant<double>(ref.tangent), constant<double>(t),
                                             constant<double>(ref.director));
      Eigen::Vector3d director(u.x, u.y, u.z);
      director -= director.dot(t) * t;  // remove round-off drift
      ref.tangent = t;
      ref.director = director.normalized();
    }
  }
  for (EndMoment& m : endMoments_) {
    const int n = rods_[m.rod].edges;
    const V3<double> x0 = constant<double>(vertex(m.rod, n - 1)),
                     x1 = constant<double>(vertex(m.rod, n));
    const double potential = endMomentPotential(x0, x1, m.axis, 1.0, m.direction, m.angle);
    m.angle = -potential;
    Eigen::Vector3d d = vertex(m.rod, n) - vertex(m.rod, n - 1);
    d -= d.dot(m.axis) * m.axis;
    m.direction = d.normalized();
  }
  // Reprojection (Section 2.5): a bolt that left its edge continues on the neighbouring edge at
  // the same rest arc length.
  int switches = 0;
  for (Bolt& b : bolts_) {
    for (BoltSide* s : {&b.lower, &b.upper}) {
      if (s->betaDof < 0) continue;
      const RodData& r = rods_[s->point.rod];
      const double beta0 = state_[s->betaDof];
      if (beta0 >= 0.0 && beta0 <= 1.0) continue;
      const double arc = (s->point.edge + beta0) * r.h;
      const int edge = std::clamp(static_cast<int>(std::floor(arc / r.h)), 0, r.edges - 1);
      if (edge == s->point.edge) continue;
      s->point.edge = edge;
      state_[s->betaDof] = arc / r.h - edge;
      ++switches;
    }
  }
  return switches;
}

}  // namespace egg::rods
