#pragma once
// Minimises the grid energy of a RodModel (Section 2.5). The thesis used Gauss-Newton as in
// Vekhter et al. 2019; we use a full Newton method with the exact sparse Hessian, a
// Levenberg-style diagonal shift when the Hessian is indefinite, and a backtracking (Armijo) line
// search. Why not Ceres' Levenberg-Marquardt: the energy is not a sum of squares (gravity and
// loads are linear potentials, the barriers are logs), and with exact second derivatives Newton
// converges quadratically near the equilibrium with one sparse Cholesky per iteration.
#include "core/rods/rod_model.hpp"

#include <functional>
#include <memory>
#include <string>

namespace egg::rods {

// Where a Newton run is, for an observer (SolverOptions::observer).
struct SolverProgress {
  int iteration = 0;     // Newton iterations taken so far (all continuation stages of this call)
  double seconds = 0.0;  // wall time from minimiseEnergy's start to reaching this state, the
                         // observer's own calls left out
  double energy = 0.0;   // J, as Newton evaluated it at this state (stiff terms softened during the
                         // continuation)
  bool last = false;     // the state minimiseEnergy returns with
};
// Called with the model at the state `progress` describes (read only: the solver continues from
// it).
using SolverObserver = std::function<void(const SolverProgress& progress, const RodModel& model)>;

struct SolverOptions {
  int maxIterations = 500;  // Newton iterations before giving up: the limit that decides results
  // Wall-clock hang guard only: results must not depend on the machine, so the iteration limit
  // stops a slow solve; this stops a hung one and fails it (status TimeLimit) with a message.
  double timeLimitS = 900.0;
  double tolerance =
      1e-10;        // stop when the Newton decrement g^T H^-1 g is below tolerance x energy scale
  int threads = 2;  // assembling the Hessian: 1 on this thread, more: on TBB's threads
  // Newton in Cartesian coordinates crawls along the inextensibility valley of thin rods (each step
  // is cut short by stretching, ~100 iterations for a cantilever). Solving first with the stiff
  // terms (stretching, position penalties) softened by 1e-4, 1e-3, ... and then at full stiffness
  // reaches the same equilibrium in ~10-20 iterations.
  bool stiffnessContinuation = true;
  double continuationStart = 1e-4;  // first softening factor; factors grow tenfold up to 1
  // Where the exact Hessian is indefinite, project every stencil (the rods' stretching, bending
  // and twisting too), not only the penalty constraints'. For a start next to a stable
  // equilibrium whose indefiniteness is transient (the joined structure from its patches'
  // equilibria, pulled together at misfitting joints; a patch's grid after the stiffness
  // continuation, its bolts pulled into place): there the constraints' projection still
  // needs a diagonal shift that stalls Newton. Not for buckling or sliding paths, where the
  // rods' negative curvature is the physics (projected, Newton heads for the unstable state);
  // the solver drops back to the constraints' projection when a projected run ends on a state
  // whose exact Hessian is indefinite.
  bool projectAllWhenIndefinite = false;
  // Optional, e.g. the error against run time of the simulation stage (simulation.hpp history):
  // called on the state of every iteration whose number is a multiple of observeEvery when the
  // step leaving it is accepted (iteration 0 is the start), and on the state the call returns with
  // (last = true). Each state is reported once. Empty: no call, no cost. The solver knows nothing
  // of what is measured.
  SolverObserver observer;
  int observeEvery = 1;
  void validate() const;  // throws InvalidInput naming the field
};

// Collapsed: set by the simulation stage (simulation.hpp) when a self-weight load step carries the
// grid far from its weightless equilibrium without settling (Section 3.5.2, Fig. 3.11).
enum class SolverStatus { Converged, IterationLimit, TimeLimit, Stalled, NonFinite, Collapsed };

const char* toString(SolverStatus status);

// Where a solve's wall time went (egg bench sim, report.json's joined section), summed over the
// continuation stages and load steps of one simulation.
struct SolverPhases {
  double derivativesS = 0.0;  // energy, gradient and Hessian stencils, assembled into the matrix
  double analysisS = 0.0;     // symbolic analyses (ordering, elimination tree, supernodes)
  double factorS = 0.0;       // numeric factorisations and solves, shift trials included
  double lineSearchS = 0.0;   // energy evaluations of the line search
  int analyses = 0;           // symbolic analyses: a new pattern (a bolt moved to another edge)
  int derivativePasses = 0;  // passes over every stencil (two at a state whose exact Hessian fails)
  SolverPhases& operator+=(const SolverPhases& o);
};

struct SolverResult {
  SolverStatus status = SolverStatus::IterationLimit;
  bool converged = false;
  std::string reason;  // why it stopped, in words
  int iterations = 0;
  double energy = 0.0;        // J
  double gradientNorm = 0.0;  // Euclidean norm over free unknowns (mixed N, N m)
  double decrement = 0.0;     // last Newton decrement, J
  double seconds = 0.0;
  int boltEdgeSwitches = 0;   // reprojections of sliding bolts onto neighbouring edges
  int factorisations = 0;     // Cholesky factorisations (shift trials included)
  int energyEvaluations = 0;  // line-search trials
  // Converged with the exact Hessian positive definite at the last step: a stable equilibrium (a
  // minimum, not a saddle). false when a shift or the projected Hessian gave the last direction.
  bool stableEquilibrium = false;
  int observations = 0;          // calls of options.observer
  double observerSeconds = 0.0;  // wall time spent in them
  SolverPhases phases;
};

// What consecutive Newton runs on one model share (a continuation's stages, a simulation's load
// steps): the derivative pass's buffers, the Hessian's pattern and the factorisations' symbolic
// analysis, which is redone only when the pattern changes (a bolt moved to another edge) or other
// unknowns are fixed. Results do not depend on it: the analysis is a function of the pattern.
class SolverWorkspace {
 public:
  SolverWorkspace();
  ~SolverWorkspace();
  SolverWorkspace(SolverWorkspace&&) noexcept;
  SolverWorkspace& operator=(SolverWorkspace&&) noexcept;
  struct State;  // rod_solver.cpp
  State& state() { return *state_; }

 private:
  std::unique_ptr<State> state_;
};

// Runs Newton from the model's current state and leaves the model at the last accepted state
// (never at a non-finite one).
SolverResult minimiseEnergy(RodModel& model, const SolverOptions& options);
// The same with a workspace kept by the caller between runs on the same model.
SolverResult minimiseEnergy(RodModel& model, const SolverOptions& options,
                            SolverWorkspace& workspace);

}  // namespace egg::rods
