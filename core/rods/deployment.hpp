#pragma once
// Deployment (issue 42): the path from the bolted flat grid to the deployed shell as a sequence of
// quasi-static equilibria. The thesis treats only the two ends ("our treatment of the deployment
// process is limited to the start and end configurations", 2.7.4) and reports a first attempt
// that broke and notches that jammed (3.5-3.6); here the supports are moved from where they hold
// the flat grid to where they hold the shell in synchronised steps, each step a DER solve
// (Section 2.5, with the sliding bolts and notch limits) warm-started from the last, and every
// step is measured as a crew would meet it: stresses, support forces, notch forces, crossing
// angles, and whether the grid snapped.
//
// Self-weight is left out: the path is the elastic one the supports impose (the flat grid is
// carried by the crew or the ground until it is fixed, which this model does not know). A
// weightless equilibrium does not depend on where the flat grid lies, so its rigid placement
// (flat_grid.hpp) only sets how far each support travels.
#include "core/rods/rod_model.hpp"
#include "core/rods/rod_network.hpp"
#include "core/rods/rod_solver.hpp"
#include "core/rods/simulation.hpp"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace egg::rods {

// Where every anchor of a network is at one point of the path: its position on the contact
// surface and the lamella normal there (what Anchor holds), in network order.
struct SupportState {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector3d> normals;
};

// The supports at path parameter t (0: the flat grid's anchors, 1: the deployed ones).
using SupportPath = std::function<SupportState(double t)>;

// Every support moved together along the straight line from `from` to `to`, its normal turned
// about the axis normal to both at a uniform rate (synchronised support moves). A straight line
// never asks a lamella to stretch: the distance between two supports along it is at most the
// larger of its two end distances, each of which the grid spans. Throws InvalidInput when the
// states differ in size or a normal turns by half a turn (no unique way).
SupportPath straightSupportPath(const SupportState& from, const SupportState& to);

struct DeploymentOptions {
  ModelOptions model;    // discretisation, notches, friction (gravity is switched off)
  SolverOptions solver;  // per step; the time limit is for the whole path
  int steps = 10;        // equal steps of t from 0 to 1
  // A step that does not converge, or whose energy drops, is split in halves up to this depth (a
  // step of 1 / (steps 2^depth)); a drop that persists at the finest step is a snap-through.
  int maxRefinements = 4;
  // An energy drop over one step, below both the energy before it and the last step's trend
  // carried on, by more than this fraction of the energy before it (at the finest step): under
  // imposed support motion the elastic energy of a stable path changes smoothly with the step, a
  // snap releases a finite part of it at once.
  double snapEnergyDrop = 0.05;
  // A step whose peak stress ratio changes by more than this (times the ratio, above 1) is split
  // too: the peak is resolved where it nears the limit.
  double stressRatioStep = 0.2;
  // A sliding bolt within one edge of a notch end pressing on it with more than this (N), harder
  // than at the step before (the path pushes it on), is jammed: the notch is too short for the
  // path, and a crew would have to force it. The flat grid's bolts rest at their notch ends by
  // design (s_bar, Section 2.4.5), where the barrier E_n holds them: not a jam.
  double jamForceN = 10.0;
  // Stress ratios max(sigma / f_m, tau / f_v); 0: not computed.
  double bendingStrengthPa = 0.0;
  double shearStrengthPa = 0.0;
  // Which supports the path moves (per anchor; empty: all). The others hold nothing on the way;
  // when the path ends they are switched on where the grid then is and moved to their places
  // (path(1)) in engageSteps steps, recorded as t in (1, 2]: a crew fixes the rest of the boundary
  // once the grid stands.
  std::vector<bool> movedSupports;
  int engageSteps = 4;
  bool keepFrames = true;  // every step's contact points (the animation)
  void validate() const;   // throws InvalidInput naming the field
};

struct DeploymentStep {
  double t = 0.0;  // path parameter
  SolverStatus status = SolverStatus::Converged;
  int iterations = 0;
  double seconds = 0.0;
  double energyJ = 0.0;  // elastic energy of the grid (bending, twisting, stretching, joints)
  bool stable = false;   // the equilibrium's exact Hessian is positive definite
  bool snap = false;     // the energy dropped at the finest step: the grid jumped (snap-through)
  double maxBendingStressPa = 0.0;  // E (|kappa_weak| t / 2 + |kappa_strong| w / 2)
  double maxTorsionStressPa = 0.0;  // G t |theta'|
  double maxAxialStressPa = 0.0;    // E |stretching strain| (supports pulling the grid apart)
  double maxStressRatio = 0.0;      // max over rods of max((bending + axial) / f_m, tau / f_v)
  int maxStressRod = -1;
  double maxNotchForceN = 0.0;       // largest force of a bolt on a notch end
  int jammedBolts = 0;               // bolt sides jammed (DeploymentOptions::jamForceN)
  std::vector<double> notchForcesN;  // per connection, rod a then rod b
  double maxNotchTravelM = 0.0;      // largest |bolt position - its flat position| along a rod
  double minCrossingAngleRad = 0.0, maxCrossingAngleRad = 0.0;
  double maxVertexMoveM = 0.0;  // largest vertex displacement from the previous step
  double maxJoinGapM = 0.0;    // joining: the widest open joint between patches (RodModel::boltGap)
  double maxJoinForceN = 0.0;  // joining: the largest force pulling a joint closed
  std::vector<Eigen::Vector3d> supportPositionsM;  // per anchor, where the support holds the grid
  std::vector<Eigen::Vector3d> supportForcesN;     // per anchor, the force it applies to the grid
  double maxSupportForceN = 0.0;
  std::vector<std::vector<Eigen::Vector3d>> contactPoints;  // per rod (options.keepFrames)
};

struct DeploymentResult {
  std::vector<DeploymentStep> steps;  // steps[0]: the flat grid (t = 0)
  bool completed = false;             // every step converged up to t = 1
  std::string reason;                 // why not
  bool timedOut = false;              // stopped by options.solver.timeLimitS
  int snaps = 0;                      // steps flagged as snap-through
  int jammedSteps = 0;                // steps with a jammed bolt
  double engagedFromT = -1.0;         // t where the supports held only at the end were switched on
  int peakStep = 0;                   // the step with the largest stress ratio (bending stress
                                      // when no strengths are given)
  SimulationRun last;                 // the last state reached (geometry and solver totals)
  int iterations = 0;
  double seconds = 0.0;
};

// Solves the flat grid (`flat`: straight rods, bolts where the planar grid puts them, anchors at
// path(0)) at every step of `path`. Throws InvalidInput when the path's states do not match the
// network's anchors.
DeploymentResult deploy(const RodNetwork& flat, const SupportPath& path,
                        const DeploymentOptions& options);

// Joining deployed patches (beyond the thesis, which bolts adjacent grids "along their common
// lamellae", 3.5.3, and names the joined structure future work, 3.7.1). The patches stand where
// their own deployments left them, each on its supports, some of which are temporary (the shoring
// of the shared sides, which the finished structure does without). A crew then:
//   t 0..1  lets the patches take their self-weight (load factor t; skipped when selfWeight is
//   off), t 1..2  pulls the joints between the patches' boundary lamellas closed and bolts them:
//   the
//           join bolts' weights from minWeightFactor to full, geometrically (a clamp tightened),
//   t 2..3  lets go of the temporary supports: their weights from full to minWeightFactor,
//           geometrically (jacks lowered), and off at t = 3.
// Every step is solved and measured as in deploy(), the joints by their gap and force.
struct JoiningOptions {
  DeploymentOptions deployment;  // model, solver (its time limit for the whole joining), limits
  bool selfWeight = true;
  int weightSteps = 4, joinSteps = 8, releaseSteps = 8;
  double minWeightFactor = 1e-6;
  void validate() const;  // throws InvalidInput naming the field
};

// `network`: the joined structure (joinPatches) with its rods' guesses and bolt starts where the
// patches' deployments ended (startFrom), and every support the patches stood on; connections
// from firstJoin on are the joints; temporarySupports marks (per anchor) the supports let go at
// the end. Throws InvalidInput when they do not match the network.
DeploymentResult joinDeployedPatches(const RodNetwork& network, int firstJoin,
                                     const std::vector<bool>& temporarySupports,
                                     const JoiningOptions& options);

}  // namespace egg::rods
