#pragma once
// The discretised grid: every rod as a polyline with uniform rest edges, one material angle per
// edge, one barycentric coordinate per sliding bolt side; the energy E = E_r + E_q + E_a + E_n +
// E_p (+ gravity and test loads) over that vector of unknowns, with its exact gradient and
// sparse Hessian (Section 2.5). The solver (rod_solver.hpp) minimises it.
#include "core/rods/bend_twist_derivatives.hpp"
#include "core/rods/rod_energies.hpp"
#include "core/rods/rod_network.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace egg::rods {

struct ModelOptions {
  double targetEdgeLengthM =
      0.0;                 // rest edge length; 0 = automatic (a third of the typical bolt spacing)
  int minEdgesPerRod = 6;  // lower bound on edges per rod
  int maxEdgesPerRod = 400;     // upper bound on edges per rod
  bool notches = true;          // false: every bolt is a plain hole (the RMS1 run of Section 2.6.2)
  bool gravity = false;         // self-weight from density (Section 3.5.2), along -z
  double gravityMPerS2 = 9.81;  // gravitational acceleration
  double frictionMu = 0.1;      // mu of E_p (Section 2.5)
  double frictionEpsilon =
      1e-4;  // epsilon of E_p: how far past an edge end a bolt may move per iteration
  double connectionWeight = 1.0;       // lambda_q1 in units of EA/h of the softer rod
  double connectionAngleWeight = 1.0;  // lambda_q2 in units of GJ/h of the softer rod
  double anchorWeight = 10.0;          // lambda_a1 in units of EA/h
  double anchorAngleWeight = 10.0;     // lambda_a2 in units of GJ/h
  // Rotational stiffness of a fastened bolt (fastenBolts), in units of E I_strong / h of the
  // softer rod: the joint is as stiff in its plane as one edge of the lamella.
  double fastenedJointWeight = 1.0;
  void validate() const;  // throws InvalidInput naming the field
};

// Which Hessian RodModel::derivatives assembles: the exact one; one with the penalty
// constraints' stencils (bolts, fastened joints, anchors) replaced by their nearest positive
// semidefinite matrices (projected Newton), the rods' own bending, twisting and stretching kept
// exact; or one with every stencil semidefinite: stretching and the constraints projected, bending
// and twisting by their Gauss-Newton Hessian (bend_twist_derivatives.hpp). The last two are the
// solver's fallbacks where the exact Hessian is indefinite (rod_solver.cpp).
enum class HessianTerms { Exact, ProjectedConstraints, ProjectedAll };

// The buffers of RodModel::derivatives, kept by the caller between calls so that a Newton run
// allocates them once (on the Yas's joined structure, fresh buffers at every iteration cost a
// fifth of the run in page faults, issue 36). The Hessian is the triplets of all parts in order.
struct DerivativeBuffers {
  std::vector<EdgeFrameDerivatives> frames;                   // per edge
  std::vector<Eigen::VectorXd> gradients;                     // per part
  std::vector<std::vector<Eigen::Triplet<double>>> triplets;  // per part: lower triangle
  std::vector<double> energies;                               // per part
};

// Stiffness of a rod from its section and material (thin rectangular strip).
RodStiffness stiffnessOf(const Rod& rod);

// A point on a rod: edge index and barycentric coordinate on it.
struct RodPoint {
  int rod = -1;
  int edge = 0;
  double beta = 0.0;
};

class RodModel {
 public:
  RodModel(const RodNetwork& network, const ModelOptions& options);

  // ---- discretisation and unknowns ----
  int rodCount() const { return static_cast<int>(rods_.size()); }
  int vertexCount(int rod) const { return rods_[rod].edges + 1; }
  double restEdgeLength(int rod) const { return rods_[rod].h; }
  int dofCount() const { return dofCount_; }
  int vertexDof(int rod, int vertex) const { return rods_[rod].firstVertexDof + 3 * vertex; }
  int thetaDof(int rod, int edge) const { return rods_[rod].firstThetaDof + edge; }
  const Eigen::VectorXd& state() const { return state_; }
  const std::vector<bool>& fixed() const { return fixed_; }
  const RodStiffness& stiffness(int rod) const { return rods_[rod].stiffness; }

  Eigen::Vector3d vertex(int rod, int i) const { return state_.segment<3>(vertexDof(rod, i)); }
  std::vector<Eigen::Vector3d> centreline(int rod) const;
  // Material normal (m1) of an edge, and averaged at a vertex.
  Eigen::Vector3d edgeNormal(int rod, int edge) const;
  Eigen::Vector3d vertexNormal(int rod, int vertex) const;
  // Current rest arc length (m) of a bolt along rod a (side 0) or rod b (side 1) of its connection.
  double boltPosition(int connection, int side) const;
  // The point of a vertex's lamella face that touches the other layer: the centreline moved half
  // a thickness back towards the design surface. It lies on the surface when the grid fits.
  Eigen::Vector3d contactPoint(int rod, int vertex) const;
  int boltCount() const { return static_cast<int>(bolts_.size()); }
  int slidingSideCount() const;

  // ---- boundary conditions and loads for analytic cases (tests, stress cases) ----
  void fixVertex(int rod, int vertex, bool x = true, bool y = true, bool z = true);
  void fixTwist(int rod, int edge);
  void setVertex(int rod, int vertex, const Eigen::Vector3d& p);
  void addPointLoad(int rod, int vertex, const Eigen::Vector3d& force);
  // Moment about `axis` on the rod's last edge (potential -M * rotation angle, unwrapped).
  void addEndMoment(int rod, const Eigen::Vector3d& axis, double moment);
  // Fastens every bolt where it is now (the deployed grid is bolted tight before it carries load,
  // thesis 5.1): no more sliding in the notches (the bolts' beta unknowns are fixed) and
  // the crossing angles held by a rotational spring (fastenedJointEnergy, rod_energies.hpp).
  void fastenBolts();
  bool boltsFastened() const { return fastened_; }
  // Multiplies gravity, point loads and end moments (load stepping for large deformations).
  void setLoadFactor(double factor);
  double loadFactor() const { return loadFactor_; }
  // Multiplies the stiff terms (stretching, bolt and anchor position penalties) by `factor` <= 1:
  // the solver's continuation path (rod_solver.cpp) starts soft and ends at 1.
  void setStiffTermsFactor(double factor) { stiffFactor_ = factor; }
  double stiffTermsFactor() const { return stiffFactor_; }

  // ---- deployment (deployment.hpp): supports moved between solves, and what a crew measures ----
  int anchorCount() const { return static_cast<int>(anchors_.size()); }
  // Moves anchor k (network order) to hold its rod point at `position` on the contact surface with
  // the lamella normal along `normal`, placed as the constructor places it (half a thickness off
  // for the rod's layer). Throws InvalidInput for a bad index or a zero normal.
  void setAnchor(int anchor, const Eigen::Vector3d& position, const Eigen::Vector3d& normal);
  // A support that is off holds nothing (its penalty weights are zero, its stencil stays, so the
  // Hessian's pattern does not change); on again, it holds with its full weights.
  void setAnchorActive(int anchor, bool active);
  // A support or bolt held with `factor` (0..1) of its full penalty weights: the joining of
  // deployed patches (deployment.hpp) tightens the joints between patches and lets go of the
  // temporary supports gradually, as a crew's clamps and jacks do. Throws InvalidInput for a bad
  // index or a factor outside [0, 1].
  void setAnchorWeight(int anchor, double factor);
  void setBoltWeight(int connection, double factor);
  // How far a bolt's two lamellas are from where it holds them (m): the bolt point on the upper
  // lamella from the one on the lower, less the layers' offset along their normals (the residual
  // of E_q, Section 2.5; zero when the joint is closed). The force the bolt then applies to the
  // lower lamella (N), -dE_q/dq at its point.
  Eigen::Vector3d boltGap(int connection) const;
  Eigen::Vector3d boltForce(int connection) const;
  // Where anchor k's rod point is now, as a support would hold it: the point on the contact surface
  // (half a thickness back from the centreline) and the lamella normal there.
  void anchorPlace(int anchor, Eigen::Vector3d& position, Eigen::Vector3d& normal) const;
  // The force (N) the support applies to the rod at the current state: the position penalty's pull
  // -dE_a/dq (at an equilibrium, the constraint's reaction).
  Eigen::Vector3d anchorForce(int anchor) const;
  // Force (N) with which a sliding bolt side (0: the connection's rod a, 1: rod b) presses on a
  // notch end: the notch barrier E_n's derivative along the rod, both ends' pushes together. 0 for
  // a plain hole or a bolt farther than one edge from both ends.
  double notchEndForce(int connection, int side) const;
  // Angle (rad, 0..pi) between the two rods' tangents at a bolt.
  double crossingAngle(int connection) const;
  struct VertexStrain {
    double weakCurvature = 0.0;    // 1/m, about the lamella's weak axis (normal curvature)
    double strongCurvature = 0.0;  // 1/m, in the lamella's plane (geodesic curvature)
    double twistRate = 0.0;        // rad/m
  };
  // At every interior vertex of a rod, the material curvatures and twist the bending and twisting
  // energies use (rod_energies.hpp), divided by the vertex's Voronoi length.
  std::vector<VertexStrain> vertexStrains(int rod) const;

  // ---- energy ----
  // Total energy at unknowns z with the current reference frames and bolt edges; +inf where z is
  // outside the domain (a bolt past its notch or edge, an edge flipped against its reference).
  double energy(const Eigen::VectorXd& z) const;
  // Internal energy (rods + constraints) and external potential separately, at z.
  void energyParts(const Eigen::VectorXd& z, double& internal, double& external) const;
  // The external potential alone (gravity, point loads, end moments): cheap, no stencil pass.
  double externalPotential(const Eigen::VectorXd& z) const;
  // Energy, gradient (size dofCount) and Hessian triplets (lower triangle, row >= col) at z, on
  // `threads` threads.
  double derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient,
                     std::vector<Eigen::Triplet<double>>& hessian, int threads = 1,
                     HessianTerms terms = HessianTerms::Exact) const;
  // The same into reusable buffers: the Hessian triplets are buffers.triplets' parts, in order
  // (the same triplets, in the same order, as the call above returns).
  double derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient,
                     DerivativeBuffers& buffers, int threads, HessianTerms terms) const;
  // Largest step fraction in (0, 1] that keeps every sliding bolt strictly inside its edge range.
  double maxStep(const Eigen::VectorXd& z, const Eigen::VectorXd& direction) const;
  // Accepts z as the new state: transports reference frames in time, moves bolts that left their
  // edge to the neighbouring edge (reprojection, Section 2.5). Returns the number of bolt sides
  // that changed edge.
  int accept(const Eigen::VectorXd& z);

  // A characteristic force (N) for convergence tests: largest EI_weak / L^2 over rods, weight
  // of the heaviest rod and largest point load.
  double forceScale() const { return forceScale_; }
  // A characteristic energy (J): largest EI_weak / L over rods. Floors the solver's relative
  // tolerance where the equilibrium energy itself is zero (a rod resting on its anchors).
  double energyUnit() const { return energyUnit_; }

 private:
  struct RodData {
    int edges = 0;
    double h = 0.0;  // rest edge length
    double length = 0.0;
    double thickness = 0.0;
    int layer = 0;
    double linearDensity = 0.0;  // kg/m
    RodStiffness stiffness;
    int firstVertexDof = 0;
    int firstThetaDof = 0;
  };
  struct BoltSide {
    RodPoint point;
    int betaDof = -1;  // -1: plain hole, the bolt stays where it was drilled
    double notchMin = 0.0, notchMax = 0.0;
  };
  struct Bolt {
    BoltSide lower, upper;  // rod in layer 0, rod in layer 1
    bool aIsLower = true;   // the connection's rod a is the lower one
    double offset = 0.0;    // (t_lower + t_upper)/2
    double positionWeight = 0.0, angleWeight = 0.0;
    double fullPositionWeight = 0.0, fullAngleWeight = 0.0;  // setBoltWeight's factor 1
    double fastenedWeight = 0.0;                             // 0 until fastenBolts()
    double fastenedCos = 0.0, fastenedSin = 0.0;             // sine about fastenedAxis
    Eigen::Vector3d fastenedAxis = Eigen::Vector3d::UnitZ();
  };
  struct AnchorData {
    RodPoint point;
    Eigen::Vector3d target, targetNormal;
    double positionWeight = 0.0, angleWeight = 0.0;
    double fullPositionWeight = 0.0, fullAngleWeight = 0.0;  // while active (setAnchorActive)
  };
  struct PointLoad {
    int dof;
    Eigen::Vector3d force;
  };
  struct EndMoment {
    int rod;
    Eigen::Vector3d axis;
    double moment;
    Eigen::Vector3d direction;  // in-plane direction of the last edge at the last accepted state
    double angle = 0.0;         // its unwrapped angle
  };

  double beta(const Eigen::VectorXd& z, const BoltSide& side) const {
    return side.betaDof >= 0 ? z[side.betaDof] : side.point.beta;
  }
  SliderParameters sliderParameters(const BoltSide& side) const;
  // Material frame of every edge differentiated w.r.t. (edge vector, theta), for the Hessian pass
  // (EdgeFrameDerivatives: bend_twist_derivatives.hpp).
  void frameDerivatives(const Eigen::VectorXd& z, int threads,
                        std::vector<EdgeFrameDerivatives>& frames) const;
  template <class Visitor>
  void forEachStencil(const Eigen::VectorXd& z, Visitor&& visit, int part, int parts,
                      const std::vector<EdgeFrameDerivatives>* frames) const;
  bool edgesValid(const Eigen::VectorXd& z) const;

  ModelOptions options_;
  std::vector<RodData> rods_;
  std::vector<Bolt> bolts_;
  std::vector<AnchorData> anchors_;
  std::vector<PointLoad> pointLoads_;
  std::vector<EndMoment> endMoments_;
  std::vector<EdgeReference> references_;  // per edge, indexed like theta dofs minus thetaBase_
  std::vector<int> edgeReferenceBase_;     // per rod
  Eigen::VectorXd state_;
  Eigen::VectorXd
      baseConstantGradient_;  // gravity and point loads (linear potentials) at load factor 1
  Eigen::VectorXd constantGradient_;  // the same times loadFactor_
  double loadFactor_ = 1.0;
  double stiffFactor_ = 1.0;
  bool fastened_ = false;
  std::vector<bool> fixed_;
  int dofCount_ = 0;
  double forceScale_ = 0.0;
  double energyUnit_ = 0.0;
};

}  // namespace egg::rods
