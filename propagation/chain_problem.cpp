// Problem 3.3 on one chain (see chain_problem.hpp).
#include "propagation/chain_problem.hpp"

#include "core/errors.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace egg::propagation {

void ChainProblem::validate() const {
  if (maps.empty()) throw InvalidInput("ChainProblem.maps: a chain needs at least one patch");
  for (size_t i = 0; i < maps.size(); ++i)
    if (!maps[i]) throw InvalidInput("ChainProblem.maps[" + std::to_string(i) + "] is null");
  if (boundaries.size() != maps.size() + 1)
    throw InvalidInput("ChainProblem.boundaries: expected " + std::to_string(maps.size() + 1) +
                       " (one more than maps), got " + std::to_string(boundaries.size()));
  for (size_t i = 0; i < boundaries.size(); ++i) {
    const auto& b = boundaries[i];
    if (!(b.weight >= 0.0) || !(b.minGap >= 0.0) || !(b.minGap < 1.0) || !(b.lengthM > 0.0))
      throw InvalidInput("ChainProblem.boundaries[" + std::to_string(i) +
                         "]: weight >= 0, length > 0 and 0 <= minGap < 1 required");
  }
  if (members < 2)
    throw InvalidInput("ChainProblem.members must be at least 2 (the boundary members)");
  for (size_t k = 0; k < originals.size(); ++k) {
    const auto& o = originals[k];
    if (o.boundary < 0 || o.boundary >= static_cast<int>(boundaries.size()) || !(o.value > 0.0) ||
        !(o.value < 1.0))
      throw InvalidInput("ChainProblem.originals[" + std::to_string(k) +
                         "]: needs a boundary of the chain and a value in (0, 1)");
  }
  for (size_t k = 0; k < closed.size(); ++k) {
    const auto& c = closed[k];
    if (c.boundary < 0 || c.boundary >= static_cast<int>(boundaries.size()) || !(c.from >= 0.0) ||
        !(c.to <= 1.0) || !(c.from < c.to))
      throw InvalidInput("ChainProblem.closed[" + std::to_string(k) +
                         "]: needs a boundary of the chain and 0 <= from < to <= 1");
  }
}

void ChainOptions::validate() const {
  if (!(relativeTolerance > 0.0))
    throw InvalidInput("ChainOptions.relativeTolerance must be positive");
  if (maxIterations < 1) throw InvalidInput("ChainOptions.maxIterations must be at least 1");
  if (!(minOrderGap > 0.0) || !(minOrderGap < 0.1))
    throw InvalidInput("ChainOptions.minOrderGap must be in (0, 0.1)");
}

namespace {

// Positions and their derivatives dp_ij / dt_j (member j moves only with its own start t_j).
void propagateWithDerivatives(const ChainProblem& problem, const std::vector<double>& start,
                              std::vector<std::vector<double>>& p,
                              std::vector<std::vector<double>>* d) {
  const size_t n = problem.maps.size(), m = start.size();
  p.assign(n + 1, std::vector<double>(m));
  if (d) d->assign(n + 1, std::vector<double>(m, 1.0));
  p[0] = start;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < m; ++j) {
      // The boundary members are the patch sides: exactly 0 and 1 on every boundary.
      if (j == 0 || j + 1 == m) {
        p[i + 1][j] = j == 0 ? 0.0 : 1.0;
        continue;
      }
      p[i + 1][j] = problem.maps[i]->value(p[i][j]);
      if (d) (*d)[i + 1][j] = problem.maps[i]->slope(p[i][j]) * (*d)[i][j];
    }
}

}  // namespace

std::vector<std::vector<double>> propagateMembers(const ChainProblem& problem,
                                                  const std::vector<double>& start) {
  std::vector<std::vector<double>> p;
  propagateWithDerivatives(problem, start, p, nullptr);
  return p;
}

double chainObjective(const ChainProblem& problem, const std::vector<double>& start,
                      std::vector<double>* gradient) {
  std::vector<std::vector<double>> p, d;
  propagateWithDerivatives(problem, start, p, gradient ? &d : nullptr);
  const size_t m = start.size();
  double value = 0.0;
  if (gradient) gradient->assign(m, 0.0);
  for (size_t i = 0; i < p.size(); ++i) {
    const double w = problem.boundaries[i].weight;
    for (size_t j = 1; j < m; ++j) {
      const double gap = p[i][j] - p[i][j - 1];
      value += w * gap * gap;
      if (gradient) {
        (*gradient)[j] += 2.0 * w * gap * d[i][j];
        (*gradient)[j - 1] -= 2.0 * w * gap * d[i][j - 1];
      }
    }
  }
  return value;
}

namespace {
// A parameter on boundary `boundary` pulled back to boundary 0 through G^-1 (back-propagation,
// Fig. 3.8).
double pullBack(const ChainProblem& problem, int boundary, double t) {
  for (int i = boundary - 1; i >= 0; --i) t = problem.maps[i]->inverse(t);
  return t;
}
}  // namespace

std::vector<double> fixedStarts(const ChainProblem& problem, std::vector<bool>* closedGaps) {
  problem.validate();
  std::vector<double> fixed{0.0, 1.0};
  for (const auto& o : problem.originals) fixed.push_back(pullBack(problem, o.boundary, o.value));
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end(),
                          [](double a, double b) { return std::abs(a - b) < 1e-12; }),
              fixed.end());
  if (closedGaps) {
    closedGaps->assign(fixed.size() - 1, false);
    for (const auto& range : problem.closed) {
      const double from = pullBack(problem, range.boundary, range.from),
                   to = pullBack(problem, range.boundary, range.to);
      for (size_t g = 0; g + 1 < fixed.size(); ++g)
        if (fixed[g] >= from - 1e-12 && fixed[g + 1] <= to + 1e-12) (*closedGaps)[g] = true;
    }
  }
  return fixed;
}

std::vector<double> plainStart(const ChainProblem& problem, std::vector<bool>* fixedOut) {
  std::vector<bool> closed;
  const std::vector<double> fixed = fixedStarts(problem, &closed);
  const int free = problem.members - static_cast<int>(fixed.size());
  if (free < 0)
    throw InvalidInput("ChainProblem: " + std::to_string(fixed.size()) +
                       " fixed members (boundaries and originals) but only " +
                       std::to_string(problem.members) + " members in all");
  double open = 0.0;
  for (size_t g = 0; g + 1 < fixed.size(); ++g)
    if (!closed[g]) open += fixed[g + 1] - fixed[g];
  if (free > 0 && !(open > 0.0))
    throw InvalidInput("ChainProblem: " + std::to_string(free) +
                       " free members but every gap between fixed members is closed");
  // Largest remainder: each gap gets free members in proportion to its length.
  const size_t gaps = fixed.size() - 1;
  std::vector<int> count(gaps, 0);
  std::vector<std::pair<double, size_t>> remainder;
  int given = 0;
  for (size_t g = 0; g < gaps; ++g) {
    const double share = closed[g] ? 0.0 : free * (fixed[g + 1] - fixed[g]) / open;
    count[g] = static_cast<int>(std::floor(share));
    given += count[g];
    remainder.push_back({share - count[g], g});
  }
  std::stable_sort(remainder.begin(), remainder.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  // Only open gaps take the remainder (a closed one has share and remainder 0, sorted last).
  std::vector<size_t> openGaps;
  for (const auto& r : remainder)
    if (!closed[r.second]) openGaps.push_back(r.second);
  for (size_t k = 0; given < free; ++k, ++given) ++count[openGaps[k % openGaps.size()]];
  std::vector<double> start;
  std::vector<bool> isFixed;
  for (size_t g = 0; g < gaps; ++g) {
    start.push_back(fixed[g]);
    isFixed.push_back(true);
    for (int k = 1; k <= count[g]; ++k) {
      start.push_back(fixed[g] + (fixed[g + 1] - fixed[g]) * k / (count[g] + 1));
      isFixed.push_back(false);
    }
  }
  start.push_back(1.0);
  isFixed.push_back(true);
  if (fixedOut) *fixedOut = isFixed;
  return start;
}

namespace {

struct SolveData {
  const ChainProblem* problem;
  const ChainOptions* options;
  std::vector<double> start;   // all members; the free ones overwritten from x
  std::vector<int> freeIndex;  // variable k -> member
  int evaluations = 0;
  void load(const double* x) {
    for (size_t k = 0; k < freeIndex.size(); ++k) start[freeIndex[k]] = x[k];
  }
  std::vector<double> bounds;  // per boundary: the smallest spacing the constraints ask for
  double gapBound(size_t boundary) const { return bounds[boundary]; }
};

double objectiveCallback(unsigned n, const double* x, double* grad, void* raw) {
  auto& data = *static_cast<SolveData*>(raw);
  ++data.evaluations;
  data.load(x);
  std::vector<double> full;
  const double value = chainObjective(*data.problem, data.start, grad ? &full : nullptr);
  if (grad)
    for (unsigned k = 0; k < n; ++k) grad[k] = full[data.freeIndex[k]];
  return value;
}

// One constraint per boundary and neighbour pair: bound - (p_ij - p_i,j-1) <= 0. Pairs of two
// fixed members are constant and left out (constraintPairs lists the others).
struct PairRef {
  size_t boundary, member;  // member j and j-1
};
std::vector<PairRef> constraintPairs(const ChainProblem& problem, const std::vector<bool>& fixed) {
  std::vector<PairRef> pairs;
  for (size_t i = 0; i < problem.boundaries.size(); ++i)
    for (size_t j = 1; j < fixed.size(); ++j)
      if (!fixed[j] || !fixed[j - 1]) pairs.push_back({i, j});
  return pairs;
}

struct ConstraintData {
  SolveData* solve;
  std::vector<PairRef> pairs;
  std::vector<int> variableOf;  // member -> variable or -1
};

void constraintCallback(unsigned m, double* result, unsigned n, const double* x, double* grad,
                        void* raw) {
  auto& data = *static_cast<ConstraintData*>(raw);
  data.solve->load(x);
  std::vector<std::vector<double>> p, d;
  propagateWithDerivatives(*data.solve->problem, data.solve->start, p, grad ? &d : nullptr);
  if (grad) std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
  for (unsigned c = 0; c < m; ++c) {
    const auto [i, j] = data.pairs[c];
    result[c] = data.solve->gapBound(i) - (p[i][j] - p[i][j - 1]);
    if (!grad) continue;
    if (data.variableOf[j] >= 0) grad[c * n + data.variableOf[j]] -= d[i][j];
    if (data.variableOf[j - 1] >= 0) grad[c * n + data.variableOf[j - 1]] += d[i][j - 1];
  }
}

// Over the pairs with a free member: two fixed members' spacing is given, no optimum can change it.
double worstViolation(const ChainProblem& problem, const std::vector<double>& bounds,
                      const std::vector<double>& start, const std::vector<bool>& fixed) {
  const auto p = propagateMembers(problem, start);
  double worst = -1.0;
  for (const auto& [i, j] : constraintPairs(problem, fixed))
    worst = std::max(worst, bounds[i] - (p[i][j] - p[i][j - 1]));
  return worst;
}

struct SlsqpRun {
  nlopt_result result = NLOPT_FAILURE;
  std::vector<double> start;  // all members
  int evaluations = 0;
};

SlsqpRun runSlsqp(const ChainProblem& problem, const ChainOptions& options,
                  const std::vector<double>& initial, const std::vector<bool>& fixed,
                  const std::vector<double>& bounds) {
  SolveData data{&problem, &options, initial, {}, 0, bounds};
  std::vector<int> variableOf(initial.size(), -1);
  for (size_t j = 0; j < fixed.size(); ++j)
    if (!fixed[j])
      variableOf[j] = static_cast<int>(data.freeIndex.size()),
      data.freeIndex.push_back(static_cast<int>(j));
  const unsigned n = static_cast<unsigned>(data.freeIndex.size());
  ConstraintData constraints{&data, constraintPairs(problem, fixed), variableOf};
  nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, n);
  nlopt_set_lower_bounds1(opt, 0.0);
  nlopt_set_upper_bounds1(opt, 1.0);
  nlopt_set_min_objective(opt, objectiveCallback, &data);
  const std::vector<double> tolerances(constraints.pairs.size(), 1e-12);
  nlopt_add_inequality_mconstraint(opt, static_cast<unsigned>(constraints.pairs.size()),
                                   constraintCallback, &constraints, tolerances.data());
  nlopt_set_ftol_rel(opt, options.relativeTolerance);
  nlopt_set_xtol_abs1(opt, 1e-14);
  nlopt_set_maxeval(opt, options.maxIterations);
  std::vector<double> x(n);
  for (unsigned k = 0; k < n; ++k) x[k] = initial[data.freeIndex[k]];
  double value = 0.0;
  SlsqpRun run;
  run.result = nlopt_optimize(opt, x.data(), &value);
  nlopt_destroy(opt);
  run.evaluations = data.evaluations;
  run.start = initial;
  for (unsigned k = 0; k < n; ++k) run.start[data.freeIndex[k]] = x[k];
  return run;
}

}  // namespace

ChainSolution solveChain(const ChainProblem& problem, const ChainOptions& options) {
  options.validate();
  ChainSolution out;
  out.startBefore = plainStart(problem, &out.fixed);
  out.start = out.startBefore;
  out.evennessBefore = out.evennessAfter = chainObjective(problem, out.start);
  if (std::all_of(out.fixed.begin(), out.fixed.end(), [](bool f) { return f; })) {
    out.status = "no free member";
    out.positions = propagateMembers(problem, out.start);
    return out;
  }
  // A footprint larger than the boundary can give (its members spaced equally between the fixed
  // ones, whose positions no solution moves) is capped there: the members are then as far apart
  // as that boundary allows.
  const auto plain = propagateMembers(problem, out.start);
  std::vector<double> required;
  int capped = 0;
  for (size_t i = 0; i < problem.boundaries.size(); ++i) {
    double cap = 1.0;
    for (size_t a = 0, b = 1; b < out.fixed.size(); ++b)
      if (out.fixed[b])
        cap = std::min(cap, (plain[i][b] - plain[i][a]) / static_cast<double>(b - a)), a = b;
    const double asked = problem.boundaries[i].minGap;
    if (asked > cap) ++capped;
    required.push_back(std::max(std::min(asked, cap), options.minOrderGap));
  }
  // Accepted if it is no less even (the optimisation must never make evenness worse) and no less
  // feasible than the plain propagation, or if it meets every footprint the plain propagation
  // did not (a hard constraint of 2.4.4, worth some evenness).
  const auto accept = [&](const SlsqpRun& run, const std::vector<double>& bounds) {
    if (!(run.result > 0 || run.result == NLOPT_ROUNDOFF_LIMITED)) return false;
    const double objective = chainObjective(problem, run.start);
    const double before = worstViolation(problem, bounds, out.start, out.fixed);
    const double after = worstViolation(problem, bounds, run.start, out.fixed);
    const bool feasible = after <= 1e-9;
    const bool noWorse = objective <= out.evennessBefore && (feasible || after <= before);
    if (!noWorse && !(feasible && before > 1e-9)) return false;
    out.start = run.start;
    out.evennessAfter = objective;
    out.optimised = true;
    return true;
  };
  SlsqpRun run = runSlsqp(problem, options, out.start, out.fixed, required);
  out.iterations = run.evaluations;
  out.status = nlopt_result_to_string(run.result);
  if (capped > 0)
    out.status +=
        " (footprint capped at equal spacing on " + std::to_string(capped) + " boundaries)";
  if (!accept(run, required)) {
    // The footprints cannot all be met (a side too short for its members at the smallest angle
    // they meet it at, 2.4.4): asked for no more than the plain propagation already has on each
    // boundary, the optimum improves evenness without crowding any side further.
    std::vector<double> relaxed = required;
    int loosened = 0;
    for (size_t i = 0; i < relaxed.size(); ++i) {
      double smallest = 1.0;
      for (const auto& [b, j] : constraintPairs(problem, out.fixed))
        if (b == i) smallest = std::min(smallest, plain[i][j] - plain[i][j - 1]);
      if (smallest < relaxed[i]) relaxed[i] = std::max(smallest, options.minOrderGap), ++loosened;
    }
    SlsqpRun second =
        loosened > 0 ? runSlsqp(problem, options, out.start, out.fixed, relaxed) : SlsqpRun{};
    out.iterations += second.evaluations;
    if (loosened > 0 && accept(second, relaxed) && out.evennessAfter < out.evennessBefore) {
      out.status += std::string(" (footprint not met; then ") +
                    nlopt_result_to_string(second.result) +
                    " with the spacing of the plain propagation on " + std::to_string(loosened) +
                    " boundaries)";
    } else {
      out.start = out.startBefore;
      out.evennessAfter = out.evennessBefore;
      out.optimised = false;
      out.status += " (no better than the plain propagation within the spacing: kept it)";
    }
  }
  out.positions = propagateMembers(problem, out.start);
  return out;
}

}  // namespace egg::propagation
