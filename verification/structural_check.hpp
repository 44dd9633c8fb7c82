#pragma once
// The FE check of a deployed grid (issue 37, docs/verification.md): the CalculiX model of the rod
// network in its deployed state, every load case solved by ccx, and per case the largest
// displacement, the equilibrium check (reactions against the applied load), each lamella's
// utilisation (deployment bending plus load stresses against f_m), and linear buckling factors of
// the governing case with a verdict. Plus the cross-check against the rod simulation's own sag.
#include "core/materials/materials.hpp"
#include "core/rods/rod_network.hpp"
#include "core/rods/simulation.hpp"
#include "verification/ccx_run.hpp"
#include "verification/fe_model.hpp"
#include "verification/load_cases.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace egg::verification {

struct RodNames {
  std::vector<std::string> rods;         // per rod: lamella name (default L<i>)
  std::vector<std::string> groups;       // per rod: its patch's set (default none)
  std::vector<std::string> connections;  // per connection: bolt name (default C<i>)
};

// The FE model of `network` deployed as `deployed` says: centrelines and lamella normals, bolts
// where the simulation left them (its bolt positions, fastened there), anchors as hinges about the
// surface normal. One material per distinct (E, rho) of the rods; f_m from `strength`.
FeModel feModelFromRods(const rods::RodNetwork& network, const rods::SimulationRun& deployed,
                        const MaterialProperties& strength, const RodNames& names = {});

struct LamellaUtilisation {
  std::string lamella;
  double utilisation = 0.0;         // (deployment + load stress) / f_m at the worst element
  double deploymentStressPa = 0.0;  // E kappa t / 2 there
  double loadStressPa = 0.0;        // largest axial fibre stress from the FE solution there
};

struct CaseResult {
  std::string name;
  double maxDisplacementM = 0.0;
  int maxDisplacementNode = 0;
  Eigen::Vector3d appliedN = Eigen::Vector3d::Zero();   // sum of the nodal loads
  Eigen::Vector3d reactionN = Eigen::Vector3d::Zero();  // sum of the support reactions
  double reactionRatio = 0.0;        // |reactions| / |applied| (1 in equilibrium)
  double equilibriumResidual = 0.0;  // |reactions + applied| / |applied|
  double maxUtilisation = 0.0;
  std::vector<LamellaUtilisation> top;         // the ten highest, worst first
  std::vector<double> lamellaUtilisation;      // per lamella of the model, in its order
  std::vector<Eigen::Vector3d> displacements;  // per mesh node (m)
  double seconds = 0.0;                        // ccx's run
  bool nonlinear = true;                       // NLGEOM; false: first order (linear static)
};

struct BucklingResult {
  std::string loadCase;  // the governing case (highest utilisation)
  std::vector<double> factors;
  std::string verdict;
  std::vector<std::vector<Eigen::Vector3d>> modes;  // per mode, per mesh node: shape (max 1)
  double seconds = 0.0;                             // ccx's run
};

struct CheckOptions {
  std::vector<LoadCase> cases;  // a self-weight case is added first when none is given
  double planAreaM2 = 0.0;      // for uniform plan loads
  int bucklingModes = 3;        // 0: no buckling step
  CcxOptions ccx;
  // Beam elements above which the model and its decks are written but not solved (0: no limit).
  int maxElements = 0;
  // Beam elements above which the load cases are solved first-order (linear static) instead of
  // with geometric nonlinearity (0: always nonlinear). ccx expands every B32R into a 20-node
  // brick and iterates each NLGEOM case to a tight residual: measured on 2 cores, the Great
  // Court's 7,657 elements ran past 10 minutes in their first case, where one linear solve takes
  // 9 s (docs/verification.md). First order is what EN 1993-1-1 5.2.1(3) accepts when the
  // buckling factor is at least 10; below, the verdict says the nonlinear decks (nl_<case>.inp,
  // written beside) must be run.
  int maxNonlinearElements = 0;
};

struct CheckResult {
  std::string ccxVersion;
  FeMesh mesh;
  bool solved = true;           // false: above maxElements, the decks are written, not run
  std::string notSolvedReason;  // why not, and how to run them
  std::vector<CaseResult> cases;
  BucklingResult buckling;
  double seconds = 0.0;
};

// Buckling verdict with its thresholds (EN 1993-1-1 5.2.1(3): alpha_cr >= 10, first-order
// analysis suffices; 5.2.2(5)B: down to 3 second-order effects may be allowed for by amplification;
// below 3 the design must change). `firstOrderCases`: the load cases were solved linearly, so a
// factor below 10 also says that their results do not suffice.
std::string bucklingVerdict(double firstFactor, bool firstOrderCases = false);

// Writes `folder`/model.inp and per case `folder`/<case>.inp, runs ccx on each (and on
// buckle.inp), reads the results back; above options.maxNonlinearElements the cases are linear
// and their NLGEOM decks nl_<case>.inp are written beside, not run. Above options.maxElements it
// writes them all (buckle.inp under the first case) and returns unsolved, with the reason. Throws
// SolverFailure with ccx's message when ccx fails, InvalidInput for a bad model or case.
CheckResult runCheck(const FeModel& model, const std::filesystem::path& folder,
                     const CheckOptions& options);

// The rod simulation's self-weight sag against the FE's (issue 37): the weightless equilibrium
// (start: `network`'s guesses), then self-weight with the bolts fastened there, as on site.
struct DerSelfWeight {
  rods::SimulationRun weightless, loaded;
};
DerSelfWeight derSelfWeight(const rods::RodNetwork& network, rods::SimulationOptions options);
// Its two halves: the weightless equilibrium (the FE model's geometry), and the self-weight solve
// from it (only needed to compare with a solved FE case).
rods::SimulationRun derWeightless(const rods::RodNetwork& network, rods::SimulationOptions options);
DerSelfWeight derSelfWeightFrom(const rods::RodNetwork& network, rods::SimulationRun weightless,
                                rods::SimulationOptions options);

struct SagComparison {
  double rmsM = 0.0;  // over the centreline vertices the FE mesh has nodes at
  double maxM = 0.0;
  double derMaxSagM = 0.0;
  double feMaxSagM = 0.0;
  int points = 0;
};
// FE displacements of `selfWeight` (a case of a model built from der.weightless) against
// der.loaded - der.weightless at every centreline vertex that is a mesh node.
SagComparison compareSag(const DerSelfWeight& der, const FeMesh& mesh,
                         const CaseResult& selfWeight);

}  // namespace egg::verification
