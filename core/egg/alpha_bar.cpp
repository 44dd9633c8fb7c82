#include "core/egg/alpha_bar.hpp"
#include "core/egg/illinois_bracket.hpp"

#include "core/errors.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace egg {

void AlphaBarOptions::validate() const {
  if (!(slopeMin > 0.0)) throw InvalidInput("patching.slope_bounds[0] (k_min) must be > 0");
  if (!(slopeMax > slopeMin))
    throw InvalidInput("patching.slope_bounds[1] (k_max) must exceed k_min");
  if (choice == AlphaBarChoice::Given && !(givenAlphaBar > 0.0 && givenAlphaBar < M_PI))
    throw InvalidInput("grid.alpha_bar must lie in (0, pi) radians");
  if (!(unrolledTolerance >= 0.0)) throw InvalidInput("alpha_bar unrolled_tolerance must be >= 0");
  if (!(minPlanarAngle >= 0.0 && minPlanarAngle < M_PI / 4))
    throw InvalidInput("grid.min_planar_angle_rad must lie in [0, pi/4)");
  if (scanSamples < 3) throw InvalidInput("alpha_bar scan_samples must be >= 3");
  if (maxEvaluations < 1) throw InvalidInput("alpha_bar max_evaluations must be >= 1");
  if (!(tolerance > 0.0)) throw InvalidInput("alpha_bar tolerance must be > 0");
  cladding.validate();
}

void parseAlphaBarChoice(const std::string& text, AlphaBarOptions& options) {
  if (text == "min") {
    options.choice = AlphaBarChoice::Min;
    return;
  }
  if (text == "max") {
    options.choice = AlphaBarChoice::Max;
    return;
  }
  if (text == "unrolled") {
    options.choice = AlphaBarChoice::Unrolled;
    return;
  }
  size_t used = 0;
  double value = std::numeric_limits<double>::quiet_NaN();
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(value > 0.0 && value < M_PI))
    throw InvalidInput(
        "grid.alpha_bar must be \"min\", \"max\", \"unrolled\" or radians in (0, pi), got \"" +
        text + "\"");
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

  AlphaBarEvaluation operator()(double alphaBar, CladdingFunction* u = nullptr,
                                CladdingFunction* v = nullptr) {
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
    const auto fu = claddingFunction(maps.u, *quad, Family::U, scale, options.cladding);
    const auto fv = claddingFunction(maps.v, *quad, Family::V, scale, options.cladding);
    e.violationU = slopeViolation(fu, options.slopeMin, options.slopeMax);
    e.violationV = slopeViolation(fv, options.slopeMin, options.slopeMax);
    e.bijective = fu.bijective() && fv.bijective();
    e.feasible = e.bijective && e.diagonalProduct < 0.0 && e.violationU < 0.0 && e.violationV < 0.0;
    if (u) *u = fu;
    if (v) *v = fv;
    return e;
  }

  // One constraint alone (0: diagonal product, 1: slopes of F_u, 2: slopes of F_v), with only the
  // work it needs: the diagonal product costs no cladding function at all.
  double constraint(double alphaBar, int which) {
    ++count;
    const auto quad = planarQuad(maps.sides, alphaBar, options.minPlanarAngle);
    if (!quad) return 1.0;
    if (which == 0) return diagonalProduct(maps, *quad) / (scale * scale);
    const Family family = which == 1 ? Family::U : Family::V;
    return slopeViolation(
        claddingFunction(maps.map(family), *quad, family, scale, options.cladding),
        options.slopeMin, options.slopeMax);
  }
};

// The three constraint functions of Problem 2.3 at one angle, each feasible where negative.
constexpr int kConstraints = 3;
using Constraints = std::array<double, kConstraints>;
const char* const kConstraintNames[kConstraints] = {"(e - e_bar)(f - f_bar)", "slopes of F_u",
                                                    "slopes of F_v"};

struct Sample {
  double alpha = 0.0;
  Constraints g{};
  bool feasible = false;
};

Sample sampleAt(Evaluator& evaluate, double alpha) {
  const auto e = evaluate(alpha);
  return {alpha, {e.diagonalProduct, e.violationU, e.violationV}, e.feasible};
}

// Locates the sign change of constraint c between a and b (opposite signs there) to `tolerance`;
// returns the end of the final bracket on the feasible (negative) side. Regula falsi with the
// Illinois modification keeps the bracket, so a jump (a topology change of the cladding curve)
// is located as surely as a smooth root.
double constraintRoot(Evaluator& evaluate, int c, const Sample& first, const Sample& second,
                      double tolerance) {
  IllinoisBracket r{first.alpha, second.alpha, first.g[c], second.g[c]};
  const bool bNegative = r.gb < 0.0;
  while (std::abs(r.b - r.a) > tolerance) {
    double x = r.falsePosition();
    const double lo = std::min(r.a, r.b), hi = std::max(r.a, r.b), width = hi - lo;
    // Stay well inside the bracket so that it shrinks from both sides.
    if (!(x > lo + 0.01 * width && x < hi - 0.01 * width)) x = 0.5 * (r.a + r.b);
    const double g = evaluate.constraint(x, c);
    r.replace(x, g, (g < 0.0) == bNegative);
  }
  return bNegative ? r.b : r.a;
}

// Adaptive refinement of the scan (Lipschitz branch and bound). Between two samples where some
// constraint is positive at both ends, a feasible stretch can hide only if every constraint can
// reach zero inside: with L_c a bound on the rate of change of g_c there,
// g_c >= (g_c(a) + g_c(b)) / 2 - L_c (b - a) / 2 on [a, b]. L_c is estimated from the samples: the
// larger of 4x the largest rate over the interval and its two neighbours (local, so a smooth
// minimum just above zero is resolved without refining the whole range) and 1/4 of the largest
// rate seen anywhere (a floor against a dip in an otherwise flat stretch). Intervals whose bound
// stays positive for some constraint are certified free of feasible angles; the others are
// halved, most promising first, until certified, narrower than `minWidth`, or out of budget.
// Returns false when the budget ran out before every interval was certified or resolved.
bool refineScan(Evaluator& evaluate, std::vector<Sample>& samples, double minWidth, int budget) {
  constexpr double kLocalSafety = 4.0, kGlobalFloor = 0.25;
  const auto rate = [&](size_t k, int c) {  // |dg_c / d alpha| over interval k = (k-1, k)
    return std::abs(samples[k].g[c] - samples[k - 1].g[c]) /
           (samples[k].alpha - samples[k - 1].alpha);
  };
  Constraints global{};
  for (size_t k = 1; k < samples.size(); ++k)
    for (int c = 0; c < kConstraints; ++c) global[c] = std::max(global[c], rate(k, c));
  // Lower bound of max_c min_[a,b] g_c over interval k: negative means a feasible angle may hide.
  const auto bound = [&](size_t k) {
    double worst = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < kConstraints; ++c) {
      double local = rate(k, c);
      if (k > 1) local = std::max(local, rate(k - 1, c));
      if (k + 1 < samples.size()) local = std::max(local, rate(k + 1, c));
      const double lipschitz = std::max(kLocalSafety * local, kGlobalFloor * global[c]);
      worst = std::max(worst, 0.5 * (samples[k - 1].g[c] + samples[k].g[c]) -
                                  0.5 * lipschitz * (samples[k].alpha - samples[k - 1].alpha));
    }
    return worst;
  };
  // Only gaps with no feasible end and no sign change of a constraint that could open a
  // feasible stretch need refining: sign changes are located exactly afterwards.
  const auto hidden = [&](size_t k) {
    const Sample &a = samples[k - 1], &b = samples[k];
    if (a.feasible || b.feasible) return false;
    for (int c = 0; c < kConstraints; ++c)
      if (a.g[c] > 0.0 && b.g[c] > 0.0)
        return bound(k) < 0.0;  // some constraint positive at both ends
    return false;  // every constraint is negative at one end or changes sign: handled by root
                   // location
  };
  bool certified = true;
  for (int spent = 0;;) {
    size_t best = 0;
    double bestBound = 0.0;
    for (size_t k = 1; k < samples.size(); ++k) {
      if (samples[k].alpha - samples[k - 1].alpha <= minWidth || !hidden(k)) continue;
      const double b = bound(k);
      if (best == 0 || b < bestBound) best = k, bestBound = b;
    }
    if (best == 0) break;
    if (spent++ >= budget) {
      certified = false;
      break;
    }
    const double middle = 0.5 * (samples[best - 1].alpha + samples[best].alpha);
    samples.insert(samples.begin() + static_cast<long>(best), sampleAt(evaluate, middle));
  }
  return certified;
}

// Shrinks [feasible, infeasible] onto the feasibility boundary; returns the feasible end.
double bisectFeasibility(Evaluator& evaluate, double in, double out, double tolerance) {
  while (std::abs(in - out) > tolerance) {
    const double mid = 0.5 * (in + out);
    (evaluate(mid).feasible ? in : out) = mid;
  }
  return in;
}

// The feasible set from the refined samples: each constraint's negative set is bounded by its own
// sign changes (located separately), and the feasible set is their intersection. A stretch where
// two constraints' negative sets overlap only slightly is thereby found whatever its width.
std::vector<AngleInterval> feasibleSet(Evaluator& evaluate, const std::vector<Sample>& samples,
                                       double tolerance, std::string& active) {
  // Breakpoints: (angle, constraint, becomes negative there).
  struct Breakpoint {
    double alpha;
    int constraint;
    bool entering;
  };
  std::vector<Breakpoint> breaks;
  for (size_t k = 1; k < samples.size(); ++k) {
    const Sample &a = samples[k - 1], &b = samples[k];
    for (int c = 0; c < kConstraints; ++c) {
      if ((a.g[c] < 0.0) == (b.g[c] < 0.0)) continue;
      // The sign change matters only if every other constraint is negative at one end at least.
      bool relevant = true;
      for (int o = 0; o < kConstraints; ++o)
        if (o != c && a.g[o] >= 0.0 && b.g[o] >= 0.0) relevant = false;
      const bool entering = b.g[c] < 0.0;
      const double root =
          relevant ? constraintRoot(evaluate, c, a, b, tolerance) : (entering ? b.alpha : a.alpha);
      breaks.push_back({root, c, entering});
    }
  }
  std::sort(breaks.begin(), breaks.end(),
            [](const Breakpoint& x, const Breakpoint& y) { return x.alpha < y.alpha; });
  // Sweep: count constraints negative; the first sample gives the start state.
  std::array<bool, kConstraints> negative{};
  for (int c = 0; c < kConstraints; ++c) negative[c] = samples.front().g[c] < 0.0;
  const auto allNegative = [&] { return negative[0] && negative[1] && negative[2]; };
  std::vector<AngleInterval> intervals;
  std::vector<std::array<int, 2>>
      limits;  // constraint bounding each interval at lo and hi (-1: the convex range)
  bool open = allNegative();
  AngleInterval current{samples.front().alpha, samples.front().alpha};
  int openedBy = -1;
  for (const auto& b : breaks) {
    negative[b.constraint] = b.entering;
    const bool now = allNegative();
    if (now && !open) current.lo = b.alpha, openedBy = b.constraint;
    if (!now && open) {
      current.hi = b.alpha;
      if (current.hi > current.lo)
        intervals.push_back(current), limits.push_back({openedBy, b.constraint});
    }
    open = now;
  }
  if (open) {
    current.hi = samples.back().alpha;
    intervals.push_back(current), limits.push_back({openedBy, -1});
  }
  // Each end is on the feasible side of its own constraint and strictly inside the others; check
  // it, and where a constraint jumps (a topology change of a cladding curve) settle the end by
  // bisection on feasibility itself.
  std::vector<AngleInterval> checked;
  for (size_t i = 0; i < intervals.size(); ++i) {
    AngleInterval interval = intervals[i];
    const double middle = 0.5 * (interval.lo + interval.hi);
    if (!evaluate(middle).feasible) continue;
    if (!evaluate(interval.lo).feasible)
      interval.lo = bisectFeasibility(evaluate, middle, interval.lo, tolerance);
    if (!evaluate(interval.hi).feasible)
      interval.hi = bisectFeasibility(evaluate, middle, interval.hi, tolerance);
    checked.push_back(interval);
    if (i == 0) active = limits[i][0] < 0 ? "convex range" : kConstraintNames[limits[i][0]];
  }
  return checked;
}

}  // namespace

AlphaBarEvaluation evaluateAlphaBar(const PatchDistanceMaps& maps, double alphaBar,
                                    const AlphaBarOptions& options) {
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
    throw InfeasiblePatch("no convex planar quad with inner angles above " +
                          std::to_string(options.minPlanarAngle) +
                          " rad has the side lengths of this patch (criterion iv)");
  result.convexRange = *range;

  // Scan of the convex range, refined where a feasible stretch could hide between samples; then
  // every constraint's sign changes located on their own, and the feasible set is their
  // intersection (see feasibleSet). alpha_min / alpha_max are its outer ends.
  const int samplesCount = options.scanSamples;
  // The scan's samples are independent: evaluated in parallel, each with its own evaluator (the
  // same values in any order; a quarter of the SQP stage's serial time at 3.4k vertices).
  std::vector<Sample> samples(samplesCount);
  tbb::parallel_for(0, samplesCount, [&](int k) {
    Evaluator local{maps, options, evaluate.scale};
    samples[k] = sampleAt(local, range->lo + (range->hi - range->lo) * k / (samplesCount - 1));
  });
  evaluate.count += samplesCount;
  double leastViolation = std::numeric_limits<double>::infinity();
  for (const auto& sample : samples)
    leastViolation = std::min(leastViolation, *std::max_element(sample.g.begin(), sample.g.end()));
  // Stretches narrower than 1/256 of the scan spacing (about 2e-4 rad on a typical convex range)
  // are not searched for: far below any construction tolerance of alpha_bar.
  const double spacing = (range->hi - range->lo) / (samplesCount - 1);
  const bool certified = refineScan(evaluate, samples, std::max(options.tolerance, spacing / 256),
                                    options.maxEvaluations);
  for (const auto& sample : samples)
    leastViolation = std::min(leastViolation, *std::max_element(sample.g.begin(), sample.g.end()));
  std::string activeAtMin;
  result.feasibleIntervals = feasibleSet(evaluate, samples, options.tolerance, activeAtMin);
  result.scanSamples = static_cast<int>(samples.size());
  if (!result.feasibleIntervals.empty()) {
    result.rangeFound = true;
    result.alphaMin = result.feasibleIntervals.front().lo;
    result.alphaMax = result.feasibleIntervals.back().hi;
  }

  std::ostringstream status;
  switch (options.choice) {
    case AlphaBarChoice::Min:
    case AlphaBarChoice::Max:
      if (!result.rangeFound) {
        std::ostringstream message;
        message << "no feasible alpha_bar in the convex range [" << range->lo << ", " << range->hi
                << "] rad: (e - e_bar)(f - f_bar) < 0 and slopes in (" << options.slopeMin << ", "
                << options.slopeMax << ") cannot hold together (least violation " << leastViolation
                << ")";
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
  status << "; " << result.feasibleIntervals.size() << " feasible interval(s) from "
         << samples.size() << " samples (" << samples.size() - samplesCount
         << " added by refinement)";
  if (result.rangeFound) status << ", alpha_min limited by " << activeAtMin;
  if (!certified) status << "; refinement budget spent before every gap was cleared";

  auto chosen = evaluate(result.alphaBar, &result.claddingU, &result.claddingV);
  if (options.choice == AlphaBarChoice::Unrolled && chosen.closable && !chosen.bijective) {
    AlphaBarOptions loose = options;
    loose.cladding.degenerateTolerance =
        std::max(options.cladding.degenerateTolerance, options.unrolledTolerance);
    Evaluator nearDevelopable{maps, loose, meanSide(maps)};
    chosen = nearDevelopable(result.alphaBar, &result.claddingU, &result.claddingV);
    if (result.claddingU.degenerate && result.claddingV.degenerate)
      status << " (near-developable: maps agree within tolerance)";
  }
  if (!chosen.closable) {
    std::ostringstream message;
    message << "alpha_bar = " << result.alphaBar
            << " rad gives no convex planar quad (convex range [" << range->lo << ", " << range->hi
            << "])";
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
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace egg
