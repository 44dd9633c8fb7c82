#include "core/rods/rod_solver.hpp"

#include "core/errors.hpp"
#include "core/rods/supernodal_cholesky.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace egg::rods {

namespace {
template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), pattern, args...);
  return buffer;
}
}  // namespace

void SolverOptions::validate() const {
  if (maxIterations < 1) throw InvalidInput("SolverOptions.maxIterations must be >= 1");
  if (!(timeLimitS > 0.0)) throw InvalidInput("SolverOptions.timeLimit_s must be > 0");
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw InvalidInput("SolverOptions.tolerance must be in (0, 1)");
  if (threads < 1) throw InvalidInput("SolverOptions.threads must be >= 1");
  if (!(continuationStart > 0.0 && continuationStart <= 1.0)) {
    throw InvalidInput("SolverOptions.continuationStart must be in (0, 1]");
  }
  if (observeEvery < 1) throw InvalidInput("SolverOptions.observeEvery must be >= 1");
}

const char* toString(SolverStatus status) {
  switch (status) {
    case SolverStatus::Converged: return "converged";
    case SolverStatus::IterationLimit: return "iteration_limit";
    case SolverStatus::TimeLimit: return "time_limit";
    case SolverStatus::Stalled: return "stalled";
    case SolverStatus::NonFinite: return "non_finite";
    case SolverStatus::Collapsed: return "collapsed";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;

// Adds the wall time of its scope to one phase's seconds.
class PhaseTimer {
 public:
  explicit PhaseTimer(double& seconds) : seconds_(seconds), start_(Clock::now()) {}
  ~PhaseTimer() { seconds_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double& seconds_;
  Clock::time_point start_;
};

}  // namespace

// Named, not anonymous: SolverWorkspace::State (declared in the header) holds one.
namespace solver_detail {

// The Hessian of the free unknowns as a sparse lower triangle whose pattern changes only when a
// bolt moves to another edge: the triplets of the model come in the same order every iteration,
// so each is mapped once to its slot in the matrix and later iterations only add values (no
// sorting, no symbolic analysis).
class FreeHessian {
 public:
  explicit FreeHessian(std::vector<int> freeIndex, int freeCount)
      : freeIndex_(std::move(freeIndex)), matrix_(freeCount, freeCount) {}

  // The triplets are the parts' in order (DerivativeBuffers). Returns true when the matrix's
  // pattern changed (the factorisation needs a new symbolic analysis). New triplets may leave it
  // as it was: a fastened joint's stencil adds entries only where its bolt's already has some.
  bool assemble(const std::vector<std::vector<Eigen::Triplet<double>>>& parts) {
    size_t count = 0;
    for (const auto& part : parts) count += part.size();
    bool same = count == rows_.size(), patternChanged = false;
    for (size_t p = 0, k = 0; same && p < parts.size(); ++p) {
      for (size_t i = 0; same && i < parts[p].size(); ++i, ++k)
        same = parts[p][i].row() == rows_[k] && parts[p][i].col() == cols_[k];
    }
    if (!same) {
      std::vector<Eigen::Triplet<double>> triplets;
      triplets.reserve(count);
      for (const auto& part : parts) triplets.insert(triplets.end(), part.begin(), part.end());
      patternChanged = rebuild(triplets);
    }
    base_.assign(matrix_.nonZeros(), 0.0);
    for (size_t p = 0, k = 0; p < parts.size(); ++p) {
      for (size_t i = 0; i < parts[p].size(); ++i, ++k)
        if (slot_[k] >= 0) base_[slot_[k]] += parts[p][i].value();
    }
    return patternChanged;
  }
  // Diagonal of the assembled (unshifted) Hessian.
  Eigen::VectorXd diagonal() const {
    Eigen::VectorXd d(diagonalSlot_.size());
    for (size_t i = 0; i < diagonalSlot_.size(); ++i) d[i] = base_[diagonalSlot_[i]];
    return d;
  }
  // The assembled Hessian plus shift * scale on the diagonal, in copy `which` (0 or 1: two shifts
  // can be factorised at the same time).
  const Eigen::SparseMatrix<double>& shifted(double shift, const Eigen::VectorXd& scale,
                                             int which = 0) {
    // The two copies share one pattern, made in rebuild(): here each thread only writes the values
    // of its own copy.
    Eigen::SparseMatrix<double>& matrix = which == 0 ? matrix_ : second_;
    double* values = matrix.valuePtr();
    std::copy(base_.begin(), base_.end(), values);
    if (shift > 0.0) {
      for (size_t i = 0; i < diagonalSlot_.size(); ++i)
        values[diagonalSlot_[i]] += shift * scale[i];
    }
    return matrix;
  }

 private:
  // Maps the triplets to their slots; true when the matrix's pattern is not the one before.
  bool rebuild(const std::vector<Eigen::Triplet<double>>& triplets) {
    const int n = static_cast<int>(matrix_.rows());
    std::vector<Eigen::Triplet<double>> pattern;
    pattern.reserve(triplets.size() + n);
    for (const auto& t : triplets) {
      const int r = freeIndex_[t.row()], c = freeIndex_[t.col()];
      if (r >= 0 && c >= 0) pattern.emplace_back(std::max(r, c), std::min(r, c), 0.0);
    }
    for (int i = 0; i < n; ++i)
      pattern.emplace_back(i, i, 0.0);  // every diagonal entry exists (shifts)
    const std::vector<int> outerBefore(matrix_.outerIndexPtr(),
                                       matrix_.outerIndexPtr() + matrix_.outerSize() + 1);
    const std::vector<int> innerBefore(matrix_.innerIndexPtr(),
                                       matrix_.innerIndexPtr() + matrix_.nonZeros());
    matrix_.setFromTriplets(pattern.begin(), pattern.end());
    matrix_.makeCompressed();
    const bool changed =
        !std::equal(outerBefore.begin(), outerBefore.end(), matrix_.outerIndexPtr()) ||
        !std::equal(innerBefore.begin(), innerBefore.end(), matrix_.innerIndexPtr(),
                    matrix_.innerIndexPtr() + matrix_.nonZeros());
    second_ = matrix_;
    auto slotOf = [&](int r, int c) {
      const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[c];
      const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[c + 1];
      return static_cast<int>(std::lower_bound(begin, end, r) - matrix_.innerIndexPtr());
    };
    rows_.resize(triplets.size());
    cols_.resize(triplets.size());
    slot_.resize(triplets.size());
    for (size_t k = 0; k < triplets.size(); ++k) {
      rows_[k] = triplets[k].row();
      cols_[k] = triplets[k].col();
      const int r = freeIndex_[rows_[k]], c = freeIndex_[cols_[k]];
      slot_[k] = (r >= 0 && c >= 0) ? slotOf(std::max(r, c), std::min(r, c)) : -1;
    }
    diagonalSlot_.resize(n);
    for (int i = 0; i < n; ++i) diagonalSlot_[i] = slotOf(i, i);
    return changed;
  }

  std::vector<int> freeIndex_;
  Eigen::SparseMatrix<double> matrix_, second_;
  std::vector<int> rows_, cols_, slot_, diagonalSlot_;
  std::vector<double> base_;
};

}  // namespace solver_detail

namespace {

// The calls of SolverOptions::observer of one minimiseEnergy, with their count and cost (which the
// progress' seconds leave out, so that an error-against-time record does not count its own
// measuring).
class Observation {
 public:
  Observation(const SolverObserver& observer, Clock::time_point start)
      : observer_(observer), start_(start) {}
  // `reached`: when the model got to this state (seconds since start, observer calls included).
  void operator()(const RodModel& model, int iteration, double energy, bool last, double reached) {
    if (!observer_) return;
    const auto before = Clock::now();
    SolverProgress progress;
    progress.iteration = iteration;
    progress.seconds = reached - seconds_;
    progress.energy = energy;
    progress.last = last;
    observer_(progress, model);
    ++calls_;
    seconds_ += std::chrono::duration<double>(Clock::now() - before).count();
  }
  void last(const RodModel& model, const SolverResult& result) {
    (*this)(model, result.iterations, result.energy, true,
            std::chrono::duration<double>(Clock::now() - start_).count());
  }
  void record(SolverResult& result) const {
    result.observations = calls_;
    result.observerSeconds = seconds_;
  }

 private:
  const SolverObserver& observer_;
  Clock::time_point start_;
  int calls_ = 0;
  double seconds_ = 0.0;
};

// LLT rather than LDLT: cheaper, and it stops at the first non-positive pivot, which is all the
// shift search needs to know. Supernodal (supernodal_cholesky.hpp). Two factorisations: see the
// shift search in newtonDirection.
using Factorisation = SupernodalCholesky;

// The checks before a Newton step at energy `energy` and free gradient g: true (result's status
// and reason set) when the iteration stops here.
bool stopsBeforeStep(double energy, const Eigen::VectorXd& g, const SolverOptions& options,
                     SolverResult& result) {
  if (!std::isfinite(energy) || !g.allFinite()) {
    result.status = SolverStatus::NonFinite;
    result.reason = "energy or gradient not finite at the current state";
    return true;
  }
  if (g.squaredNorm() == 0.0) {
    // Already in equilibrium (an unloaded straight rod, say): no descent direction exists, and
    // the shift search below would report that as a stall.
    result.status = SolverStatus::Converged;
    result.converged = true;
    result.decrement = 0.0;
    result.reason = "gradient exactly zero: already in equilibrium";
    return true;
  }
  if (result.iterations >= options.maxIterations) {
    result.status = SolverStatus::IterationLimit;
    result.reason = format("no convergence in %d iterations (decrement %.3g J)", result.iterations,
                           result.decrement);
    return true;
  }
  if (result.seconds > options.timeLimitS) {
    result.status = SolverStatus::TimeLimit;
    result.reason = format(
        "wall-clock hang guard of %.3g s reached after %d iterations (the run is stopped, not "
        "converged: raise the guard or find the hang)",
        options.timeLimitS, result.iterations);
    return true;
  }
  return false;
}

// Newton direction; shift the diagonal (relative to itself) until the factor is positive
// definite. Starting from a tenth of the last shift keeps the number of refactorisations low
// (measured: ~2 per iteration when starting from zero every time, ~1.3 this way); the shift
// returns to zero near a stable equilibrium, where Newton converges quadratically.
// The trial shifts 0 or s/10, then x10 each, are tried in order; the first that gives a
// positive definite factor and a descent direction is taken. With two threads, two
// consecutive trials are factorised at once: the same choice as one after the other, in less
// wall time when the first fails (benchmark grid, 784 vertices: 1.76 factorisations per
// iteration one after the other, 1.2 pairs). An unshifted first trial is tried alone: it
// fails rarely (3 of 19 times there), and a second factorisation would be wasted work.
// `shift`: the last shift in, the one taken out; false when no trial gave a direction.
bool newtonDirection(solver_detail::FreeHessian& hessian, Factorisation (&solvers)[2],
                     const Eigen::VectorXd& g, const Eigen::VectorXd& scale, int threads,
                     double& shift, SolverResult& result, Eigen::VectorXd& direction) {
  bool factored = false;
  std::vector<double> trials;
  for (double trial = shift * 0.1 < 1e-10 ? 0.0 : shift * 0.1; trials.size() < 30;
       trial = trial == 0.0 ? 1e-8 : trial * 10.0) {
    trials.push_back(trial);
  }
  const PhaseTimer timer(result.phases.factorS);
  auto attempt = [&](int which, double trial, Eigen::VectorXd& out) {
    Factorisation& solver = solvers[which];
    if (!solver.factorize(hessian.shifted(trial, scale, which))) return false;
    out = -solver.solve(g);
    return out.allFinite() && out.dot(g) < 0.0;
  };
  for (size_t k = 0; k < trials.size() && !factored;) {
    const bool pair = threads >= 2 && trials[k] > 0.0 && k + 1 < trials.size();
    if (pair) {
      Eigen::VectorXd second;
      // std::async, not a bare thread: an exception on either side propagates (get() rethrows
      // the worker's; if the first attempt throws, the future's destructor waits for the worker).
      result.factorisations += 2;
      auto other =
          std::async(std::launch::async, [&]() { return attempt(1, trials[k + 1], second); });
      const bool firstOk = attempt(0, trials[k], direction);
      const bool secondOk = other.get();
      if (firstOk) {
        factored = true;
        shift = trials[k];
      } else if (secondOk) {
        factored = true;
        shift = trials[k + 1];
        direction = std::move(second);
      }
      k += 2;
    } else {
      ++result.factorisations;
      if (attempt(0, trials[k], direction)) {
        factored = true;
        shift = trials[k];
      }
      k += 1;
    }
  }
  return factored;
}

// Backtracking line search (Armijo), first limited so sliding bolts stay inside their
// barriers (fraction to the boundary). `direction` is over the free dofs (freeIndex); true with
// the accepted state in `candidate`, false when no step decreased the energy enough.
bool lineSearch(RodModel& model, const Eigen::VectorXd& z, const Eigen::VectorXd& direction,
                const std::vector<int>& freeIndex, double energy, SolverResult& result,
                Eigen::VectorXd& candidate) {
  const int n = static_cast<int>(freeIndex.size());
  Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (freeIndex[i] >= 0) step[i] = direction[freeIndex[i]];
  }
  const PhaseTimer timer(result.phases.lineSearchS);
  double alpha = model.maxStep(z, step);
  bool accepted = false;
  for (int tries = 0; tries < 60 && alpha > 1e-14; ++tries) {
    candidate = z + alpha * step;
    ++result.energyEvaluations;
    const double e = model.energy(candidate);
    if (std::isfinite(e) && e <= energy - 1e-4 * alpha * result.decrement) {
      accepted = true;
      break;
    }
    alpha *= 0.5;
  }
  return accepted;
}

}  // namespace

// The Hessian's pattern and slots, the factorisations with their symbolic analysis and the
// derivative buffers, for the free unknowns `freeIndex` (SolverWorkspace in rod_solver.hpp).
struct SolverWorkspace::State {
  std::vector<int> freeIndex;
  std::unique_ptr<solver_detail::FreeHessian> hessian;
  Factorisation solvers[2];   // two: see newtonDirection
  bool analysed = false;      // solvers[0] holds the analysis of the hessian's pattern
  bool pairAnalysed = false;  // solvers[1] too
  DerivativeBuffers buffers;
};

SolverWorkspace::SolverWorkspace() : state_(std::make_unique<State>()) {}
SolverWorkspace::~SolverWorkspace() = default;
SolverWorkspace::SolverWorkspace(SolverWorkspace&&) noexcept = default;
SolverWorkspace& SolverWorkspace::operator=(SolverWorkspace&&) noexcept = default;

namespace {

// Newton with line search on the model as it is (one stage of the continuation).
SolverResult newton(RodModel& model, const SolverOptions& options, Clock::time_point start,
                    int iterationsBefore, Observation& observe, SolverWorkspace::State& workspace) {
  auto elapsed = [&]() { return std::chrono::duration<double>(Clock::now() - start).count(); };

  const int n = model.dofCount();
  std::vector<int> freeIndex(n, -1);
  int freeCount = 0;
  for (int i = 0; i < n; ++i) {
    if (!model.fixed()[i]) freeIndex[i] = freeCount++;
  }

  SolverResult result;
  Eigen::VectorXd gradient(n);
  // Other unknowns fixed than in the workspace's last run: a new Hessian and a new analysis.
  if (!workspace.hessian || workspace.freeIndex != freeIndex) {
    workspace.freeIndex = freeIndex;
    workspace.hessian = std::make_unique<solver_detail::FreeHessian>(freeIndex, freeCount);
    workspace.analysed = workspace.pairAnalysed = false;
  }
  DerivativeBuffers& buffers = workspace.buffers;
  solver_detail::FreeHessian& hessian = *workspace.hessian;
  Factorisation(&solvers)[2] = workspace.solvers;
  double shift = 0.0;  // relative diagonal shift that last made the Hessian positive definite
  // Projected-Newton fallback: where the exact Hessian is indefinite (a bolt or a compressed edge
  // far from its rest state), the constraints' stencils (or every stencil, with
  // SolverOptions::projectAllWhenIndefinite) are projected onto positive semidefinite matrices
  // before any diagonal shift is tried. The shift is relative to a diagonal
  // that stretching dominates: any shift large enough for an indefinite bolt stencil also swamps
  // the soft bending and sagging modes, and Newton crawls (the Yas's joined structure: 479
  // iterations shift-bound). After a failed exact trial the exact Hessian is skipped for 1, 2, 4
  // and at most 8 iterations, so that a run that stays indefinite does not pay for a useless
  // factorisation every time, and one that reaches a stable equilibrium ends with exact Newton
  // steps (quadratic convergence).
  int skipExact = 0, exactBackoff = 1;
  // The projected Hessian of the fallback (SolverOptions::projectAllWhenIndefinite).
  HessianTerms projected = options.projectAllWhenIndefinite ? HessianTerms::ProjectedAll
                                                            : HessianTerms::ProjectedConstraints;

  for (int iteration = 0;; ++iteration) {
    const double reached = elapsed();
    const Eigen::VectorXd z = model.state();
    const bool tryExact = skipExact == 0;
    if (skipExact > 0) --skipExact;
    double energy = 0.0;
    {
      const PhaseTimer timer(result.phases.derivativesS);
      ++result.phases.derivativePasses;
      energy = model.derivatives(z, gradient, buffers, options.threads,
                                 tryExact ? HessianTerms::Exact : projected);
    }
    Eigen::VectorXd g(freeCount);
    for (int i = 0; i < n; ++i) {
      if (freeIndex[i] >= 0) g[freeIndex[i]] = gradient[i];
    }
    result.energy = energy;
    result.gradientNorm = g.norm();
    result.iterations = iterationsBefore + iteration;
    result.seconds = elapsed();
    if (stopsBeforeStep(energy, g, options, result)) return result;

    bool newPattern = false;
    {
      const PhaseTimer timer(result.phases.derivativesS);
      newPattern = hessian.assemble(buffers.triplets);
    }
    // A new pattern needs a new symbolic analysis; the second factorisation copies the first's.
    if (newPattern || !workspace.analysed) {
      const PhaseTimer timer(result.phases.analysisS);
      ++result.phases.analyses;
      solvers[0].analyzePattern(hessian.shifted(0.0, Eigen::VectorXd()));
      workspace.analysed = true;
      workspace.pairAnalysed = false;
    }
    if (options.threads >= 2 && !workspace.pairAnalysed) {
      solvers[1] = solvers[0];
      workspace.pairAnalysed = true;
    }

    Eigen::VectorXd direction;
    bool exactDirection = false;  // from the unshifted exact Hessian: positive definite
    auto assembleTerms = [&](HessianTerms terms) {  // at the same state: g and energy unchanged
      const PhaseTimer timer(result.phases.derivativesS);
      ++result.phases.derivativePasses;
      model.derivatives(z, gradient, buffers, options.threads, terms);
      hessian.assemble(buffers.triplets);
    };
    auto unshifted = [&]() {
      const PhaseTimer timer(result.phases.factorS);
      ++result.factorisations;
      if (!solvers[0].factorize(hessian.shifted(0.0, Eigen::VectorXd()))) return false;
      direction = -solvers[0].solve(g);
      return direction.allFinite() && direction.dot(g) < 0.0;
    };
    auto shifted = [&]() {
      const Eigen::VectorXd diagonal = hessian.diagonal();
      const double largestDiagonal = diagonal.cwiseAbs().maxCoeff();
      const Eigen::VectorXd scale = diagonal.cwiseAbs().cwiseMax(1e-12 * largestDiagonal + 1e-300);
      return newtonDirection(hessian, solvers, g, scale, options.threads, shift, result, direction);
    };
    bool factored = false;
    if (tryExact) {
      exactDirection = factored = unshifted();
      if (factored) {
        exactBackoff = 1;
        shift = 0.0;
      } else {
        skipExact = exactBackoff;
        exactBackoff = std::min(2 * exactBackoff, 8);
        assembleTerms(projected);
      }
    }
    if (!factored) factored = shifted();
    if (!factored) {
      result.status = SolverStatus::Stalled;
      result.reason = "Hessian could not be made positive definite";
      return result;
    }
    result.decrement = -direction.dot(g);
    // The energy scale from the energy just computed: no second pass over the stencils.
    const double external = model.externalPotential(z);
    const double internal = energy - external;
    const double energyScale = std::abs(internal) + std::abs(external) + model.energyUnit();
    if (result.decrement <= options.tolerance * energyScale && !exactDirection) {
      // A projected Hessian hides negative curvature, so a small decrement there may be a saddle:
      // the exact Hessian decides, as it always did before the fallback existed (with its shift
      // search where it is indefinite), and the next iterations try it first again.
      skipExact = 0;
      exactBackoff = 1;
      assembleTerms(HessianTerms::Exact);
      exactDirection = !tryExact && unshifted();  // tried: it failed at this state
      // Every stencil projected hides the rods' own negative curvature too: from here on only
      // the constraints' are, so that the shift search finds the way off a saddle.
      if (!exactDirection) projected = HessianTerms::ProjectedConstraints;
      factored = exactDirection || shifted();
      if (!factored) {
        result.status = SolverStatus::Stalled;
        result.reason = "Hessian could not be made positive definite";
        return result;
      }
      result.decrement = -direction.dot(g);
    }
    if (result.decrement <= options.tolerance * energyScale) {
      result.status = SolverStatus::Converged;
      result.converged = true;
      result.stableEquilibrium = exactDirection;
      result.reason = format("Newton decrement %.3g J below %.3g x energy scale %.3g J",
                             result.decrement, options.tolerance, energyScale);
      return result;
    }

    Eigen::VectorXd candidate;
    const bool accepted = lineSearch(model, z, direction, freeIndex, energy, result, candidate);
    if (!accepted) {
      // At round-off level the Armijo test cannot see a decrease any more: that is convergence.
      const bool roundOff = result.decrement <= 1e-6 * energyScale;
      result.status = roundOff ? SolverStatus::Converged : SolverStatus::Stalled;
      result.converged = roundOff;
      result.reason =
          format("line search found no decrease (decrement %.3g J, energy scale %.3g J)",
                 result.decrement, energyScale);
      return result;
    }
    // The state z is left by this step: the observer sees it now, before the model moves on (the
    // state a call returns with is seen by minimiseEnergy), so every state is reported once.
    if (result.iterations % options.observeEvery == 0)
      observe(model, result.iterations, energy, false, reached);
    result.boltEdgeSwitches += model.accept(candidate);
  }
}

}  // namespace

SolverPhases& SolverPhases::operator+=(const SolverPhases& o) {
  derivativesS += o.derivativesS;
  analysisS += o.analysisS;
  factorS += o.factorS;
  lineSearchS += o.lineSearchS;
  analyses += o.analyses;
  derivativePasses += o.derivativePasses;
  return *this;
}

SolverResult minimiseEnergy(RodModel& model, const SolverOptions& options) {
  SolverWorkspace workspace;
  return minimiseEnergy(model, options, workspace);
}

SolverResult minimiseEnergy(RodModel& model, const SolverOptions& options,
                            SolverWorkspace& workspace) {
  options.validate();
  const auto start = Clock::now();
  Observation observe(options.observer, start);
  const double finalFactor = model.stiffTermsFactor();
  int iterations = 0, switches = 0, factorisations = 0, evaluations = 0;
  SolverPhases phases;
  if (options.stiffnessContinuation) {
    SolverOptions stage = options;
    stage.tolerance = std::max(options.tolerance, 1e-6);  // warm starts only: no need to be exact
    for (double factor = options.continuationStart; factor < 0.99; factor *= 10.0) {
      model.setStiffTermsFactor(factor * finalFactor);
      const SolverResult r = newton(model, stage, start, iterations, observe, workspace.state());
      iterations = r.iterations;
      switches += r.boltEdgeSwitches;
      factorisations += r.factorisations;
      evaluations += r.energyEvaluations;
      phases += r.phases;
      if (r.status == SolverStatus::TimeLimit || r.status == SolverStatus::NonFinite ||
          iterations >= options.maxIterations) {
        model.setStiffTermsFactor(finalFactor);
        SolverResult out = r;
        out.converged = false;
        out.reason = "during stiffness continuation: " + r.reason;
        out.boltEdgeSwitches = switches;
        out.factorisations = factorisations;
        out.energyEvaluations = evaluations;
        out.phases = phases;
        observe.last(model, out);
        observe.record(out);
        return out;
      }
    }
    model.setStiffTermsFactor(finalFactor);
  }
  SolverResult result = newton(model, options, start, iterations, observe, workspace.state());
  result.boltEdgeSwitches += switches;
  result.factorisations += factorisations;
  result.energyEvaluations += evaluations;
  result.phases += phases;
  observe.last(model, result);
  observe.record(result);
  return result;
}

}  // namespace egg::rods
