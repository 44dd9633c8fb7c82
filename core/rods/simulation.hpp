#pragma once
// The simulation stage (Section 2.5, errors of 2.6.2 and 3.5.2): deploys a RodNetwork to its
// elastic equilibrium and measures how far it lies from the design surface, with notches (RMS2)
// and, for comparison, with plain holes (RMS1).
#include "core/rods/rod_model.hpp"
#include "core/rods/rod_network.hpp"
#include "core/rods/rod_solver.hpp"
#include "core/rods/surface_distance.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace egg::rods {

struct SimulationOptions {
  ModelOptions model;    // discretisation, notches, gravity, friction, penalty weights
  SolverOptions solver;  // Newton limits and tolerance
  // Load steps for self-weight after a first weightless solve; 0: the full weight at once, for a
  // start that is an equilibrium under self-weight already (the joined run started from the
  // patch-by-patch equilibria). Sag and collapse are then measured from the start state.
  int gravitySteps = 2;
  // A self-weight load step that runs out of iterations or time with some vertex farther than
  // collapseFraction x the grid's extent (bounding-box diagonal) from the weightless equilibrium
  // is reported as Collapsed rather than as slow: the grid is falling through (Section 3.5.2,
  // Fig. 3.11). Example: the 8 m vault of `egg bench sim --gravity` (50 x 5 mm strips) with
  // sliding bolts needs ~760 iterations to reach its collapsed equilibrium 1.7 m down. 0: off.
  double collapseFraction = 0.05;
  // Self-weight runs: the bolts are tightened at the weightless equilibrium (or at the start
  // state of a run from one), before the grid carries its weight, as on site (RodModel::
  // fastenBolts): no sliding, crossing angles held. false: the bolts stay loose under load.
  bool fastenBoltsUnderLoad = false;
  double scaleFactor = 1.0;            // f of the NRMSE (Section 3.5.2)
  bool compareWithoutNotches = false;  // also run with plain holes (RMS1 of Section 2.6.2)
  // Error against run time: with a surface, every historyEvery-th Newton iteration and
  // the end of every load step measure the contact points' deviation into SimulationRun::history,
  // through solver.observer (it is called on the same schedule; its progress then counts the run's
  // iterations and seconds). 0: no history, no measuring.
  int historyEvery = 0;
  void validate() const;  // throws InvalidInput naming the field
};

// One point of the error-against-time record of a run.
struct DeviationSample {
  int iteration = 0;  // Newton iterations of the run so far (all load steps)
  int loadStep =
      0;  // 0: the weightless solve (or the single full-weight one), then 1..gravitySteps
  double seconds =
      0.0;  // wall time since the run started (model set-up included), measuring excluded
  double rmseM = 0.0;  // contact points vs the design surface, as SimulationRun::deviation
  double maxM = 0.0;
};

// One deployed state and its error.
struct SimulationRun {
  SolverResult solver;
  bool notches = true;
  int vertices = 0;                                       // centreline vertices, all rods
  int unknowns = 0;                                       // Newton unknowns
  std::vector<std::vector<Eigen::Vector3d>> centrelines;  // per rod, vertices (m)
  std::vector<std::vector<Eigen::Vector3d>> normals;      // per rod vertex, lamella normal
  std::vector<std::vector<Eigen::Vector3d>>
      contactPoints;  // per rod vertex, on the contact surface between the layers
  std::vector<std::array<double, 2>> boltPositionsM;  // per connection: s along rod a, rod b
  // Per connection: how far the bolt leaves its two lamellas from where it holds them, and the
  // force it then applies (RodModel::boltGap, boltForce): the joints between patches of a joined
  // run stay open where the patches' boundary lamellas do not fit.
  std::vector<double> boltGapsM, boltForcesN;
  std::optional<DeviationStats> deviation;  // contact points vs surface (when given)
  // Self-weight runs with load steps: the contact points at the weightless equilibrium (step 0),
  // per rod vertex (the deployment stage's end state is compared with them).
  std::vector<std::vector<Eigen::Vector3d>> weightlessContactPoints;
  double maxSagM =
      0.0;  // self-weight runs: largest vertex displacement from the weightless equilibrium
  // options.historyEvery > 0 and a surface: the deviation from the start to the final state (the
  // last sample is `deviation`), and the wall time the measuring took (inside solver.seconds).
  std::vector<DeviationSample> history;
  double historySeconds = 0.0;
};

struct SimulationResult {
  SimulationRun deployed;  // with notches as options.model.notches says
  std::optional<SimulationRun>
      withoutNotches;      // plain holes (when compareWithoutNotches), without history
  bool converged = false;  // every run converged
  std::string reason;      // first non-convergence reason, if any
  double seconds = 0.0;
};

// Sets every rod's initial guess to the deployed state of `run` (its contact points and lamella
// normals: what a guess is, rod_network.hpp) and every sliding bolt's start to where the run left
// it (Connection::startAM/startBM), so that a further run starts from that equilibrium whichever
// layer each rod lies in now. Throws InvalidInput when the rods, their vertex counts or the
// connections do not match.
void startFrom(RodNetwork& network, const SimulationRun& run);

// The model's current state as a run's geometry: unknowns, vertices, centrelines, lamella normals,
// contact points and bolt positions (the solver fields and the deviation are left as they are).
void recordState(const RodModel& model, SimulationRun& run);

// One run; `surface` may be null (no error measure).
SimulationRun simulateRods(const RodNetwork& network, const SurfaceDistance* surface,
                           const SimulationOptions& options);

// The stage: the deployed grid with notches and, if asked, without; errors against `surface`.
SimulationResult simulateGrid(const RodNetwork& network, const TriMesh& surface,
                              const SimulationOptions& options);

}  // namespace egg::rods
