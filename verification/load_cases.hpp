#pragma once
// Load cases of the FE check (issue 37) as ccx steps: self-weight always, a uniform load on the
// plan area (snow, live load) shared out by tributary plan length, point loads at named bolts.
// Every load is a nodal force (*CLOAD) computed here, so the applied total is known exactly and
// the reactions can be held against it (the equilibrium check, structural_check.hpp).
#include "verification/fe_model.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace egg::verification {

struct PointLoad {
  std::string bolt;  // FeBolt::name
  Eigen::Vector3d forceN = Eigen::Vector3d::Zero();
};

struct LoadCase {
  std::string name;            // letters, digits, underscores (the step's file name)
  bool selfWeight = true;      // lamellas' weight, along -z
  double uniformPlanPa = 0.0;  // on the plan area, along -z (1 kN/m^2 = 1000 Pa)
  std::vector<PointLoad> pointLoads;
};

// Nodal forces of a case: per node (1-based id - 1) the force in N.
// Self-weight: each lamella element's weight rho g A L, 1/6 to each end node and 2/3 to the middle
// one (the consistent load of a uniform line load on a straight 3-node element). Uniform plan
// load: the total p x planAreaM2 shared among the lamella elements in proportion to their length
// in plan (every member of a regular two-family grid carries a strip of half the spacing on each
// side, so its tributary plan area is its plan length x spacing / 2 x 2 families), split the same
// way. Throws InvalidInput naming an unknown bolt or a uniform load without a plan area.
std::vector<Eigen::Vector3d> nodalLoads(const FeModel& model, const FeMesh& mesh,
                                        const LoadCase& loadCase, double planAreaM2);

// A ccx input file for one case: *INCLUDE of the model file, one static step with geometric
// nonlinearity (*STEP, NLGEOM) and tight residual controls (so that the reactions close on the
// load to ~1e-9), displacements of every node and reactions of the supports into the .dat, and
// stresses and displacements into the .frd. `modelFile` is the model's file name next to it.
// `nonlinear` false: a first-order (linear static) step, one solve, no residual iterations.
std::string caseInp(const std::string& modelFile, const std::vector<Eigen::Vector3d>& loads,
                    bool nonlinear = true);

// A linear buckling step (*BUCKLE, `modes` factors) under the given loads from the unloaded
// model: the factors multiply the whole case. Mode shapes into the .frd.
std::string buckleInp(const std::string& modelFile, const std::vector<Eigen::Vector3d>& loads,
                      int modes);

}  // namespace egg::verification
