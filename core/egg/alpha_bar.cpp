#include "core/egg/alpha_bar.hpp"

#include "core/errors.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace egg {

void AlphaBarOptions::validate() const {
  if (!(slopeMin > 0.0)) throw InvalidInput("patching.slope_bounds[0] (k_min) must be > 0");
  if (!(slopeMax > slopeMin)) throw InvalidInput("patching.slope_bounds[1] (k_max) must exceed k_min");
  if (choice == AlphaBarChoice::Given && !(givenAlphaBar > 0.0 && givenAlphaBar < M_PI))
    throw InvalidInput("grid.alpha_bar must lie in (0, pi) radians");
  if (!(unrolledTolerance >= 0.0)) throw InvalidInput("alpha_bar unrolled_tolerance must be >= 0");
  if (!(minPlanarAngle >= 0.0 && minPlanarAngle < M_PI / 4)) throw InvalidInput("grid.min_planar_angle_rad must lie in [0, pi/4)");
  if (scanSamples < 3) throw InvalidInput("alpha_bar scan_samples must be >= 3");
  if (maxEvaluations < 1) throw InvalidInput("alpha_bar max_evaluations must be >= 1");
  if (!(tolerance > 0.0)) throw InvalidInput("alpha_bar tolerance must be > 0");
  cladding.validate();
}

void parseAlphaBarChoice(const std::string& text, AlphaBarOptions& options) {
  if (text == "min") { options.choice = AlphaBarChoice::Min; return; }
  if (text == "max") { options.choice = AlphaBarChoice::Max; return; }
  if (text == "unrolled") { options.choice = AlphaBarChoice::Unrolled; return; }
  size_t used = 0;
  double value = std::numeric_limits<double>::quiet_NaN();
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(value > 0.0 && value < M_PI))
    throw InvalidInput("grid.alpha_bar must be \"min\", \"max\", \"unrolled\" or radians in (0, pi), got \"" + text + "\"");
  options.choice = AlphaBarChoice::Given;
  options.givenAlphaBar = value;
}

namespace {

double meanSide(const PatchDistanceMaps& maps) {
  return 0.25 * (maps.sides[0] + maps.sides[1] + maps.sides[2] + maps.sides[3]);
}

struct Evaluator {
  const PatchDistanceMaps& maps;
  const AlphaBarOptions& options;
  double scale;
  int count = 0;

  AlphaBarEvaluation operator()(double alphaBar, CladdingFunction* u = nullptr, CladdingFunction* v = nullptr) {
    ++count;
    AlphaBarEvaluation e;
    e.alphaBar = alphaBar;
    const auto quad = planarQuad(maps.sides, alphaBar, options.minPlanarAngle);
    if (!quad) {
      e.diagonalProduct = e.violationU = e.violationV = 1.0;
      return e;
    }
    e.closable = true;
    e.diagonalProduct = diagonalProduct(maps, *quad) / (scale * scale);
    const auto fu = claddingFunction(maps.u, planarDistanceMap(*quad, Family::U, maps.u.n1, maps.u.n2), Family::U,
                                     scale, options.cladding);
    const auto fv = claddingFunction(maps.v, planarDistanceMap(*quad, Family::V, maps.v.n1, maps.v.n2), Family::V,
                                     scale, options.cladding);
    e.violationU = slopeViolation(fu, options.slopeMin, options.slopeMax);
    e.violationV = slopeViolation(fv, options.slopeMin, options.slopeMax);
    e.bijective = fu.bijective() && fv.bijective();
    e.feasible = e.bijective && e.diagonalProduct < 0.0 && e.violationU < 0.0 && e.violationV < 0.0;
    if (u) *u = fu;
    if (v) *v = fv;
    return e;
  }
};

struct SqpContext {
  Evaluator* evaluate;
  double lo, hi, step;
  double sign;  // +1 minimises alpha_bar, -1 maximises it
  int objectiveCalls = 0;
};

double sqpObjective(unsigned, const double* x, double* grad, void* data) {
  auto* ctx = static_cast<SqpContext*>(data);
  ++ctx->objectiveCalls;
  if (grad) grad[0] = ctx->sign;
  return ctx->sign * x[0];
}

// The three constraints of Problem 2.3 as g <= 0, with central differences in alpha_bar
// (one-sided at the ends of the convex range).
void sqpConstraints(unsigned m, double* result, unsigned, const double* x, double* grad, void* data) {
  auto* ctx = static_cast<SqpContext*>(data);
  const auto values = [&](double a) {
    const auto e = (*ctx->evaluate)(a);
    return std::array<double, 3>{e.diagonalProduct, e.violationU, e.violationV};
  };
  const auto g = values(x[0]);
  for (unsigned k = 0; k < m; ++k) result[k] = g[k];
  if (!grad) return;
  const double a = std::max(ctx->lo, x[0] - ctx->step), b = std::min(ctx->hi, x[0] + ctx->step);
  const auto ga = values(a), gb = values(b);
  for (unsigned k = 0; k < m; ++k) grad[k] = b > a ? (gb[k] - ga[k]) / (b - a) : 0.0;
}

// Shrinks [feasible, infeasible] onto the feasibility boundary; returns the feasible end.
double bisectFeasibility(Evaluator& evaluate, double in, double out, double tolerance) {
  while (std::abs(in - out) > tolerance) {
    const double mid = 0.5 * (in + out);
    (evaluate(mid).feasible ? in : out) = mid;
  }
  return in;
}

// Finds the feasible angle furthest in direction -sign (sign = +1: smallest) starting from the
// feasible seed. `outside` is a known infeasible angle on that side (or nullopt if the seed is at
// the end of the convex range). SLSQP does the search; a bisection finishes it if SLSQP stops short
// of the feasibility boundary or ends slightly infeasible.
double feasibilityBound(Evaluator& evaluate, const AngleInterval& range, double seed, std::optional<double> outside,
                        double sign, const AlphaBarOptions& options, int& sqpCalls, std::string& how) {
  SqpContext ctx{&evaluate, range.lo, range.hi, 1e-6, sign};
  nlopt::opt opt(nlopt::LD_SLSQP, 1);
  opt.set_lower_bounds(std::vector<double>{sign > 0 ? range.lo : seed});
  opt.set_upper_bounds(std::vector<double>{sign > 0 ? seed : range.hi});
  opt.set_min_objective(sqpObjective, &ctx);
  opt.add_inequality_mconstraint(sqpConstraints, &ctx, std::vector<double>(3, 0.0));
  opt.set_xtol_abs(options.tolerance);
  opt.set_maxeval(options.maxEvaluations);
  std::vector<double> x{seed};
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {
    // NLopt reports roundoff/failed line searches by throwing; x still holds its last iterate.
  }
  sqpCalls += ctx.objectiveCalls;
  double best = seed;
  const double candidate = std::clamp(x[0], range.lo, range.hi);
  const bool candidateBeyondSeed = sign * (candidate - seed) <= 0.0;
  if (candidateBeyondSeed && evaluate(candidate).feasible) {
    best = candidate;
  } else if (candidateBeyondSeed && candidate != seed) {
    outside = outside ? (sign > 0 ? std::max(*outside, candidate) : std::min(*outside, candidate)) : candidate;
  }
  const double probe = best - sign * options.tolerance;
  const bool probeOutside = sign > 0 ? probe < range.lo : probe > range.hi;
  if (probeOutside || !evaluate(probe).feasible || !outside) {
    how = "slsqp";
    return best;
  }
  how = "slsqp+bisection";
  return bisectFeasibility(evaluate, best, *outside, options.tolerance);
}

}  // namespace

AlphaBarEvaluation evaluateAlphaBar(const PatchDistanceMaps& maps, double alphaBar, const AlphaBarOptions& options) {
  Evaluator evaluate{maps, options, meanSide(maps)};
  return evaluate(alphaBar);
}

AlphaBarResult solveAlphaBar(const PatchDistanceMaps& maps, const AlphaBarOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  maps.validate();
  AlphaBarResult result;
  Evaluator evaluate{maps, options, meanSide(maps)};

  const auto range = convexAlphaRange(maps.sides, 1e-9, options.minPlanarAngle);
  if (!range)
    throw InfeasiblePatch("no convex planar quad with inner angles above " + std::to_string(options.minPlanarAngle) +
                          " rad has the side lengths of this patch (criterion iv)");
  result.convexRange = *range;

  // Coarse scan of the convex range: seeds for SLSQP and bracketing infeasible neighbours.
  const int samples = options.scanSamples;
  std::vector<double> angles(samples);
  std::vector<char> feasible(samples);
  int first = -1, last = -1;
  double leastViolation = std::numeric_limits<double>::infinity();
  for (int k = 0; k < samples; ++k) {
    angles[k] = range->lo + (range->hi - range->lo) * k / (samples - 1);
    const auto e = evaluate(angles[k]);
    feasible[k] = e.feasible;
    leastViolation = std::min(leastViolation, std::max({e.diagonalProduct, e.violationU, e.violationV}));
    if (e.feasible) {
      if (first < 0) first = k;
      last = k;
    }
  }
  std::string howMin, howMax;
  if (first >= 0) {
    result.rangeFound = true;
    const auto below = first > 0 ? std::optional<double>(angles[first - 1]) : std::nullopt;
    const auto above = last < samples - 1 ? std::optional<double>(angles[last + 1]) : std::nullopt;
    result.alphaMin = feasibilityBound(evaluate, *range, angles[first], below, +1.0, options, result.sqpIterations, howMin);
    result.alphaMax = feasibilityBound(evaluate, *range, angles[last], above, -1.0, options, result.sqpIterations, howMax);
    // Runs of feasible scan samples; inner ends sharpened by bisection.
    for (int k = first; k <= last;) {
      int end = k;
      while (end + 1 <= last && feasible[end + 1]) ++end;
      AngleInterval interval;
      interval.lo = k == first ? result.alphaMin : bisectFeasibility(evaluate, angles[k], angles[k - 1], options.tolerance);
      interval.hi = end == last ? result.alphaMax : bisectFeasibility(evaluate, angles[end], angles[end + 1], options.tolerance);
      result.feasibleIntervals.push_back(interval);
      k = end + 1;
      while (k <= last && !feasible[k]) ++k;
    }
  }

  std::ostringstream status;
  switch (options.choice) {
    case AlphaBarChoice::Min:
    case AlphaBarChoice::Max:
      if (!result.rangeFound) {
        std::ostringstream message;
        message << "no feasible alpha_bar in the convex range [" << range->lo << ", " << range->hi
                << "] rad: (e - e_bar)(f - f_bar) < 0 and slopes in (" << options.slopeMin << ", " << options.slopeMax
                << ") cannot hold together (least violation " << leastViolation << ")";
        throw InfeasiblePatch(message.str());
      }
      result.alphaBar = options.choice == AlphaBarChoice::Min ? result.alphaMin : result.alphaMax;
      status << (options.choice == AlphaBarChoice::Min ? "min" : "max");
      break;
    case AlphaBarChoice::Unrolled:
      result.alphaBar = maps.alphaSpatial;
      status << "unrolled";
      break;
    case AlphaBarChoice::Given:
      result.alphaBar = options.givenAlphaBar;
      status << "given";
      break;
  }
  if (result.rangeFound) status << "; alpha_min by " << howMin << ", alpha_max by " << howMax;
  else status << "; no feasible range";

  auto chosen = evaluate(result.alphaBar, &result.claddingU, &result.claddingV);
  if (options.choice == AlphaBarChoice::Unrolled && chosen.closable && !chosen.bijective) {
    AlphaBarOptions loose = options;
    loose.cladding.degenerateTolerance = std::max(options.cladding.degenerateTolerance, options.unrolledTolerance);
    Evaluator nearDevelopable{maps, loose, meanSide(maps)};
    chosen = nearDevelopable(result.alphaBar, &result.claddingU, &result.claddingV);
    if (result.claddingU.degenerate && result.claddingV.degenerate) status << " (near-developable: maps agree within tolerance)";
  }
  if (!chosen.closable) {
    std::ostringstream message;
    message << "alpha_bar = " << result.alphaBar << " rad gives no convex planar quad (convex range [" << range->lo
            << ", " << range->hi << "])";
    throw InfeasiblePatch(message.str());
  }
  if (!chosen.bijective)
    throw InfeasiblePatch("alpha_bar = " + std::to_string(result.alphaBar) +
                          " rad gives a cladding function that is not bijective (criterion iii)");
  result.quad = *planarQuad(maps.sides, result.alphaBar, options.minPlanarAngle);
  result.degenerate = result.claddingU.degenerate && result.claddingV.degenerate;
  result.slopeMin = std::numeric_limits<double>::infinity();
  result.slopeMax = -std::numeric_limits<double>::infinity();
  for (const auto* f : {&result.claddingU, &result.claddingV})
    for (double s : segmentSlopes(*f, options.cladding.infiniteSlopeFactor)) {
      result.slopeMin = std::min(result.slopeMin, s);
      result.slopeMax = std::max(result.slopeMax, s);
    }
  result.evaluations = evaluate.count;
  result.status = status.str();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace egg
