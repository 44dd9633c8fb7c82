#pragma once
// The energy terms of the grid (Section 2.5, E = E_r + E_q + E_a + E_n + E_p), each written once
// over a generic scalar S: double for values, HyperDual<N> for exact gradients and Hessians.
// Discrete elastic rods after Bergou et al. 2008/2010: centreline vertices x_i, one material
// angle theta_j per edge measured from a reference director that is parallel-transported in time
// (from the previous accepted iterate), curvature binormal 2 e0 x e1 / (|e0||e1| + e0.e1) at
// interior vertices, twist = signed angle between the space-parallel-transported material
// normal of one edge and that of the next.
//
// Material frame of an edge: m1 = lamella normal (thickness direction), m2 = t x m1 (width
// direction). Bending towards m1 turns the tangent about m2 (weak axis, EI = E w t^3/12),
// bending towards m2 turns it about m1 (strong axis, E t w^3/12).
#include "core/rods/hyper_dual.hpp"

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace egg::rods {

// Time-parallel reference of one edge: its unit tangent and unit reference director at the last
// accepted iterate. The material normal is m1 = cos(theta) u + sin(theta) (t x u) where u is the
// director transported to the current tangent.
struct EdgeReference {
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
  Eigen::Vector3d director = Eigen::Vector3d::UnitZ();
};

struct RodStiffness {
  double stretching = 0.0;     // EA, N
  double bendingWeak = 0.0;    // E w t^3 / 12, N m^2
  double bendingStrong = 0.0;  // E t w^3 / 12, N m^2
  double twisting = 0.0;       // G J, J = w t^3 / 3, N m^2
};

template <class S>
struct Frame {
  V3<S> tangent, normal, side;  // t, m1, m2
};

// Rotation taking unit vector `from` to unit vector `to` about their common perpendicular,
// applied to u (Rodrigues: c u + v x u + (v.u) v / (1 + c), v = from x to, c = from.to).
// Singular only for opposite vectors; callers keep 1 + c away from 0.
template <class S>
inline V3<S> parallelTransport(const V3<S>& from, const V3<S>& to, const V3<S>& u) {
  const S c = dot(from, to);
  const V3<S> v = cross(from, to);
  return c * u + cross(v, u) + (dot(v, u) / (c + 1.0)) * v;
}

// The material frame of an edge; `director`, when given, receives the time-parallel-transported
// reference director u (theta = 0), which the closed-form twist derivatives need.
template <class S>
inline Frame<S> materialFrame(const V3<S>& edge, const S& theta, const EdgeReference& reference,
                              V3<S>* director = nullptr) {
  using std::cos;
  using std::sin;
  const S length = norm(edge);
  const V3<S> t = (1.0 / length) * edge;
  const V3<S> u =
      parallelTransport(constant<S>(reference.tangent), t, constant<S>(reference.director));
  if (director != nullptr) *director = u;
  const V3<S> v = cross(t, u);
  const S c = cos(theta), s = sin(theta);
  return {t, c * u + s * v, c * v - s * u};
}

// Stretching of one edge of rest length h: 1/2 EA (|e|/h - 1)^2 h.
template <class S>
inline S stretchingEnergy(const V3<S>& x0, const V3<S>& x1, double stiffness, double restLength) {
  const S strain = norm(x1 - x0) * (1.0 / restLength) - 1.0;
  return (0.5 * stiffness * restLength) * (strain * strain);
}

// Bending and twisting at the interior vertex x1 between edges (x0,x1) and (x1,x2), with the
// vertex's Voronoi rest length l = (h0 + h1)/2. Straight rest state: zero rest curvature/twist.
// The same from the two edge vectors e0 = x1 - x0, e1 = x2 - x1 (the energy depends on the
// vertices only through them; the Hessian pass differentiates with respect to 8 instead of 11
// variables).
template <class S>
inline S bendTwistEnergyOfEdges(const V3<S>& e0, const V3<S>& e1, const Frame<S>& f0,
                                const Frame<S>& f1, const RodStiffness& stiffness,
                                double voronoiLength) {
  using std::atan2;
  const S denominator = norm(e0) * norm(e1) + dot(e0, e1);
  const V3<S> curvatureBinormal = (2.0 / denominator) * cross(e0, e1);
  const S weak0 = dot(curvatureBinormal, f0.side), weak1 = dot(curvatureBinormal, f1.side);
  const S strong0 = dot(curvatureBinormal, f0.normal), strong1 = dot(curvatureBinormal, f1.normal);
  // Average of the two edges' material curvatures (Bergou et al. 2008, eq. 4).
  const S bending =
      (0.25 / voronoiLength) * (stiffness.bendingWeak * (weak0 * weak0 + weak1 * weak1) +
                                stiffness.bendingStrong * (strong0 * strong0 + strong1 * strong1));
  const V3<S> carried = parallelTransport(f0.tangent, f1.tangent, f0.normal);
  const S twist = atan2(dot(cross(carried, f1.normal), f1.tangent), dot(carried, f1.normal));
  return bending + (0.5 * stiffness.twisting / voronoiLength) * (twist * twist);
}

template <class S>
inline S bendTwistEnergy(const V3<S>& x0, const V3<S>& x1, const V3<S>& x2, const Frame<S>& f0,
                         const Frame<S>& f1, const RodStiffness& stiffness, double voronoiLength) {
  return bendTwistEnergyOfEdges(x1 - x0, x2 - x1, f0, f1, stiffness, voronoiLength);
}

template <class S>
inline S bendTwistEnergy(const V3<S>& x0, const V3<S>& x1, const V3<S>& x2, const S& theta0,
                         const S& theta1, const EdgeReference& reference0,
                         const EdgeReference& reference1, const RodStiffness& stiffness,
                         double voronoiLength) {
  return bendTwistEnergy(x0, x1, x2, materialFrame(x1 - x0, theta0, reference0),
                         materialFrame(x2 - x1, theta1, reference1), stiffness, voronoiLength);
}

// E_q (Section 2.5) for one bolt: the lower rod g at q_g = (1-b_g) x0 + b_g x1 on its edge, the
// upper rod h likewise; the upper centreline sits `offset` (= (t_g + t_h)/2) along each rod's
// material normal, and the normals agree (rotation about the common normal stays free). The
// angle term uses |m_g - m_h|^2 = 4 sin^2(angle/2), smooth where the angle itself is not.
template <class S>
inline S connectionEnergy(const V3<S>& g0, const V3<S>& g1, const V3<S>& mg, const S& betaG,
                          const V3<S>& h0, const V3<S>& h1, const V3<S>& mh, const S& betaH,
                          double offset, double positionWeight, double angleWeight) {
  const V3<S> qg = (1.0 - betaG) * g0 + betaG * g1;
  const V3<S> qh = (1.0 - betaH) * h0 + betaH * h1;
  const V3<S> fromG = qg - qh + offset * mg;
  const V3<S> fromH = qh - qg - offset * mh;
  return positionWeight * (squaredNorm(fromG) + squaredNorm(fromH)) +
         angleWeight * squaredNorm(mg - mh);
}

template <class S>
inline S connectionEnergy(const V3<S>& g0, const V3<S>& g1, const S& thetaG, const S& betaG,
                          const EdgeReference& referenceG, const V3<S>& h0, const V3<S>& h1,
                          const S& thetaH, const S& betaH, const EdgeReference& referenceH,
                          double offset, double positionWeight, double angleWeight) {
  return connectionEnergy(g0, g1, materialFrame(g1 - g0, thetaG, referenceG).normal, betaG, h0, h1,
                          materialFrame(h1 - h0, thetaH, referenceH).normal, betaH, offset,
                          positionWeight, angleWeight);
}

// A fastened bolt (thesis 5.1, "fastening the connections of members after deployment ultimately
// fixes interior grid angles"): the crossing angle of the two edges that hold it is held at its
// value when it was fastened, by a rotational spring on the unit tangents' cosine and signed sine
// about `axis` (the joint's normal when it was fastened), weight * ((cos - cos0)^2 + (sin -
// sin0)^2) ~ weight * (alpha - alpha0)^2 for small changes, the same stiffness at any crossing
// angle. The sine is signed, not |e_g x e_h|: the norm has a cusp where the two lamellas are
// parallel (the bolts joining two patches' boundary lamellas), which made those stencils strongly
// indefinite and Newton shift-bound (issue 36).
template <class S>
inline S fastenedJointEnergy(const V3<S>& g0, const V3<S>& g1, const V3<S>& h0, const V3<S>& h1,
                             double cos0, double sin0, const Eigen::Vector3d& axis, double weight) {
  using std::sqrt;
  const V3<S> eg = g1 - g0, eh = h1 - h0;
  const S scale = 1.0 / sqrt(squaredNorm(eg) * squaredNorm(eh));
  const S c = dot(eg, eh) * scale;
  const S sn = dot(cross(eg, eh), constant<S>(axis)) * scale;
  return weight * ((c - cos0) * (c - cos0) + (sn - sin0) * (sn - sin0));
}

// E_a (Section 2.5): a rod point held at `target` with its material normal along `targetNormal`.
template <class S>
inline S anchorEnergy(const V3<S>& x0, const V3<S>& x1, const V3<S>& m, double beta,
                      const Eigen::Vector3d& target, const Eigen::Vector3d& targetNormal,
                      double positionWeight, double angleWeight) {
  const V3<S> q = (1.0 - beta) * x0 + beta * x1;
  return positionWeight * squaredNorm(q - constant<S>(target)) +
         angleWeight * squaredNorm(m - constant<S>(targetNormal));
}

template <class S>
inline S anchorEnergy(const V3<S>& x0, const V3<S>& x1, const S& theta, double beta,
                      const EdgeReference& reference, const Eigen::Vector3d& target,
                      const Eigen::Vector3d& targetNormal, double positionWeight,
                      double angleWeight) {
  return anchorEnergy(x0, x1, materialFrame(x1 - x0, theta, reference).normal, beta, target,
                      targetNormal, positionWeight, angleWeight);
}

// One side of a sliding bolt, at barycentric beta on the edge starting at rest arc length
// edgeStart (rest edge length h). E_p (pseudo-friction, keeps beta within (-eps, 1+eps) during one
// iteration) and E_n (notch limits, a barrier (log(d)/10)^2 in the rest distance d, in edge
// lengths, to a notch end closer than one edge). The thesis activates E_n only on the edge that
// holds the notch end; "closer than one edge length" is the same barrier made independent of
// where the vertices fall. Both are multiplied by `unit` (J; see RodModel::sliderParameters).
// Returns +inf outside the feasible range (the line search backs off).
struct SliderParameters {
  double edgeStart = 0.0;   // rest arc length of the current edge's first vertex, m
  double edgeLength = 0.0;  // rest edge length h, m
  double notchMin = 0.0;    // rest arc length of the notch ends, m
  double notchMax = 0.0;
  double mu = 0.1;
  double epsilon = 1e-4;
  double unit = 1.0;  // J
};

template <class S>
inline S sliderEnergy(const S& beta, const SliderParameters& p) {
  using std::log;
  const double b = value(beta);
  const double s = p.edgeStart + b * p.edgeLength;
  if (!(p.epsilon + b > 0.0) || !(p.epsilon + 1.0 - b > 0.0) || !(s > p.notchMin) ||
      !(s < p.notchMax)) {
    return S(std::numeric_limits<double>::infinity());
  }
  const S lowFriction = p.mu * log(beta + p.epsilon);
  const S highFriction = p.mu * log(1.0 + p.epsilon - beta);
  S energy = lowFriction * lowFriction + highFriction * highFriction;
  const double distanceLow = (s - p.notchMin) / p.edgeLength;
  if (distanceLow < 1.0) {
    const S limit = 0.1 * log(beta + (p.edgeStart - p.notchMin) / p.edgeLength);
    energy = energy + limit * limit;
  }
  const double distanceHigh = (p.notchMax - s) / p.edgeLength;
  if (distanceHigh < 1.0) {
    const S limit = 0.1 * log((p.notchMax - p.edgeStart) / p.edgeLength - beta);
    energy = energy + limit * limit;
  }
  return p.unit * energy;
}

// Potential of a moment M about a fixed unit axis acting on the last edge (x0, x1): -M phi, with
// phi the edge's rotation about the axis, unwrapped from the previous iterate's angle and
// direction (so full turns count). Test load for the rolled-up circle.
template <class S>
inline S endMomentPotential(const V3<S>& x0, const V3<S>& x1, const Eigen::Vector3d& axis,
                            double moment, const Eigen::Vector3d& previousDirection,
                            double previousAngle) {
  using std::atan2;
  const V3<S> d = x1 - x0;
  const V3<S> p = constant<S>(previousDirection), a = constant<S>(axis);
  const V3<S> dIn = d - dot(d, a) * a;  // in-plane part
  const S angle = atan2(dot(cross(p, dIn), a), dot(p, dIn)) + previousAngle;
  return -moment * angle;
}

}  // namespace egg::rods
