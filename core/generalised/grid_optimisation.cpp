// E_grid and its minimisation (Sections 4.6.3-4.6.4): see grid_optimisation.hpp.
#include "core/generalised/grid_optimisation.hpp"

#include "core/errors.hpp"
#include "core/generalised/effort.hpp"
#include "core/timing.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <string>

namespace egg::generalised {
namespace {

// What an unbuildable layout scores: above any E_grid (the scaled E_effort is <= 0 and E_shape >=
// 0, so E_grid <= 0).
constexpr double kUnbuildableEnergy = 1e3;

struct OptimisationSearch {
  const GridDomain& domain;
  const GridOptimisationOptions& options;
  int evaluations = 0;
  int buildable = 0;
  double bestEnergy = std::numeric_limits<double>::infinity();
  LayoutParameters bestParameters;
  // An exception must not cross NLopt's C frames: the objective keeps it and stops the solver.
  std::exception_ptr failure;
  nlopt_opt solver = nullptr;

  LayoutParameters parametersOf(const double* x) const {
    LayoutParameters p;
    p.angleRad = x[0];
    p.skewRad = x[1];
    p.offsets = {std::clamp(x[2], 0.0, 1.0 - 1e-9), std::clamp(x[3], 0.0, 1.0 - 1e-9)};
    p.lines = options.lines;
    return p;
  }

  // E_grid of a layout, or kUnbuildableEnergy.
  double energyOf(const GeneralisedLayout& layout) {
    ++evaluations;
    if (!layoutProblem(domain, layout, options.layout).empty()) return kUnbuildableEnergy;
    std::vector<std::pair<int, int>> pairs;
    for (const auto& m : layout.members) pairs.emplace_back(m.start, m.end);
    domain.prepareMembers(pairs);  // traced in parallel, for the crossing angles and the energy
    const auto crossings = gridCrossings(domain, layout);
    for (const auto& c : crossings) {
      if (!c.found) return kUnbuildableEnergy;
      const auto& g = layout.members[c.g];
      const auto& h = layout.members[c.h];
      if (crossingAngle(domain.member(g.start, g.end), c.sGM, domain.member(h.start, h.end),
                        c.sHM) < options.minCrossingAngleRad)
        return kUnbuildableEnergy;
    }
    ++buildable;
    return gridEnergy(domain, layout, crossings, options.energy).eGrid;
  }
};

double optimisationObjective(unsigned, const double* x, double*, void* data) {
  auto& search = *static_cast<OptimisationSearch*>(data);
  const auto parameters = search.parametersOf(x);
  const double energy =
      search.energyOf(layoutFromLines(search.domain, parameters, search.options.layout));
  if (energy < search.bestEnergy) {
    search.bestEnergy = energy;
    search.bestParameters = parameters;
  }
  return energy;
}

}  // namespace

void GridEnergyOptions::validate() const {
  if (!(shapeWeight >= 0.0) || !std::isfinite(shapeWeight))
    throw InvalidInput("GridEnergyOptions.shape_weight must be finite and >= 0");
  shape.validate();
}

void GridOptimisationOptions::validate() const {
  for (int f = 0; f < 2; ++f) {
    if (lines[f] < 1 || lines[f] > 500)
      throw InvalidInput("GridOptimisationOptions.lines[" + std::to_string(f) +
                         "] must be in 1..500");
  }
  if (!(maxSkewRad >= 0.0 && maxSkewRad < std::numbers::pi / 3))
    throw InvalidInput("GridOptimisationOptions.max_skew_rad must be in [0, pi/3)");
  if (globalEvaluations < 1)
    throw InvalidInput("GridOptimisationOptions.global_evaluations must be >= 1");
  if (!(minCrossingAngleRad >= 0.0 && minCrossingAngleRad < std::numbers::pi / 2))
    throw InvalidInput("GridOptimisationOptions.min_crossing_angle_rad must be in [0, pi/2)");
  if (maxRefinementSweeps < 0)
    throw InvalidInput("GridOptimisationOptions.max_refinement_sweeps must be >= 0");
  layout.validate();
  energy.validate();
}

GridEnergy gridEnergy(const GridDomain& domain, const GeneralisedLayout& layout,
                      const std::vector<GridCrossing>& crossings,
                      const GridEnergyOptions& options) {
  options.validate();
  std::vector<std::pair<int, int>> pairs;
  for (const auto& m : layout.members) pairs.emplace_back(m.start, m.end);
  domain.prepareMembers(pairs);
  GridEnergy energy;
  std::vector<MemberCurvatureProfile> profiles;
  for (const auto& m : layout.members) {
    const auto& geometry = domain.member(m.start, m.end);
    energy.efforts.push_back(geometry.effort);
    profiles.push_back({geometry.arcLengthM, geometry.kappaN});
  }
  energy.eEffort = gridEffortEnergy(energy.efforts);
  const double scale2 = domain.kappaScale2();
  const int count = static_cast<int>(layout.members.size());
  energy.eEffortScaled = scale2 > 0.0 ? energy.eEffort / (count * scale2 * scale2) : 0.0;
  std::vector<StabilityCrossing> supports;
  for (const auto& c : crossings) {
    // The field's arc lengths, within the traced profile's (they agree to the tracing's rounding).
    supports.push_back({c.g, std::min(c.sGM, profiles[c.g].arcLengthM.back()), c.h,
                        std::min(c.sHM, profiles[c.h].arcLengthM.back())});
  }
  energy.shape = shapeStability(profiles, supports, options.shape);
  energy.eShape = energy.shape.eShape;
  energy.eGrid = energy.eEffortScaled - options.shapeWeight * energy.eShape;
  return energy;
}

GridOptimisationResult optimiseGrid(const GridDomain& domain,
                                    const GridOptimisationOptions& options) {
  options.validate();
  const Stopwatch clock;
  GridOptimisationResult result;
  OptimisationSearch search{domain, options, 0,      0, std::numeric_limits<double>::infinity(),
                            {},     nullptr, nullptr};
  {
    const double start[4] = {0.0, 0.0, 0.5, 0.5};
    result.initialEGrid = optimisationObjective(4, start, nullptr, &search);
    if (search.failure) std::rethrow_exception(search.failure);
  }
  // Stage 1: DIRECT-L over rotation (a half turn: the families are ordered), skew and offsets.
  nlopt_opt opt = nlopt_create(NLOPT_GN_DIRECT_L, 4);
  search.solver = opt;
  const double lower[4] = {0.0, -options.maxSkewRad, 0.0, 0.0};
  const double upper[4] = {std::numbers::pi, options.maxSkewRad, 1.0, 1.0};
  nlopt_set_lower_bounds(opt, lower);
  nlopt_set_upper_bounds(opt, upper);
  nlopt_set_min_objective(opt, optimisationObjective, &search);
  nlopt_set_maxeval(opt, options.globalEvaluations);
  double x[4] = {std::numbers::pi / 2, 0.0, 0.5, 0.5};
  double value = 0.0;
  nlopt_optimize(opt, x, &value);  // stops at maxeval; the best point is kept by the search
  nlopt_destroy(opt);
  search.solver = nullptr;
  if (search.failure) std::rethrow_exception(search.failure);
  if (!(search.bestEnergy < kUnbuildableEnergy)) {
    throw InvalidInput("generalised grid: no buildable layout with " +
                       std::to_string(options.lines[0]) + " x " + std::to_string(options.lines[1]) +
                       " lines on this boundary (" + std::to_string(domain.sampleCount()) +
                       " samples); use fewer lines or a finer boundary");
  }
  result.parameters = search.bestParameters;
  result.globalEGrid = search.bestEnergy;
  GeneralisedLayout layout = layoutFromLines(domain, result.parameters, options.layout);
  double energy = search.bestEnergy;
  // Stage 2: anchor moves in the discrete dual space.
  const int n = domain.sampleCount();
  for (int sweep = 0; sweep < options.maxRefinementSweeps; ++sweep) {
    int kept = 0;
    for (size_t i = 0; i < layout.members.size(); ++i) {
      for (int end = 0; end < 2; ++end) {
        for (int step : {-2, -1, 1, 2}) {
          GeneralisedLayout trial = layout;
          int& sample = end == 0 ? trial.members[i].start : trial.members[i].end;
          sample = ((sample + step) % n + n) % n;
          const double trialEnergy = search.energyOf(trial);
          if (trialEnergy < energy - 1e-12) {
            layout = std::move(trial);
            energy = trialEnergy;
            ++kept;
          }
        }
      }
    }
    result.anchorMoves += kept;
    if (kept == 0) break;
  }
  result.layout = std::move(layout);
  result.crossings = gridCrossings(domain, result.layout);
  result.energy = gridEnergy(domain, result.layout, result.crossings, options.energy);
  result.evaluations = search.evaluations;
  result.buildableEvaluations = search.buildable;
  result.tracedMembers = domain.tracedMemberCount();
  result.seconds = clock.seconds();
  return result;
}

}  // namespace egg::generalised
