#include "core/rods/stress_cases.hpp"

#include "core/rods/sample_grids.hpp"

#include <cmath>

namespace egg::rods {

std::vector<StressCase> stressCases() {
  const StressCase base{"base", 1.0, 10.0, 10.0e9, 500.0};
  std::vector<StressCase> cases{base};
  auto vary = [&](const std::string& name, auto&& change) {
    StressCase c = base;
    c.name = name;
    change(c);
    cases.push_back(c);
  };
  vary("width:thickness 5", [](StressCase& c) { c.widthToThickness = 5.0; });
  vary("width:thickness 100", [](StressCase& c) { c.widthToThickness = 100.0; });
  vary("E 0.5 GPa", [](StressCase& c) { c.youngsModulus_pa = 0.5e9; });
  vary("E 210 GPa (steel)", [](StressCase& c) { c.youngsModulus_pa = 210.0e9; c.density_kg_m3 = 7850.0; });
  vary("scale 0.1 m", [](StressCase& c) { c.scale = 0.1 / 3.0; });
  vary("scale 22 m", [](StressCase& c) { c.scale = 22.0 / 3.0; });
  vary("scale 220 m", [](StressCase& c) { c.scale = 220.0 / 3.0; });
  vary("density 400", [](StressCase& c) { c.density_kg_m3 = 400.0; });
  vary("density 7850", [](StressCase& c) { c.density_kg_m3 = 7850.0; });
  vary("soft heavy 220 m, w:t 100", [](StressCase& c) {
    c.scale = 220.0 / 3.0;
    c.widthToThickness = 100.0;
    c.youngsModulus_pa = 0.5e9;
    c.density_kg_m3 = 7850.0;
  });
  vary("stiff light 0.1 m, w:t 5", [](StressCase& c) {
    c.scale = 0.1 / 3.0;
    c.widthToThickness = 5.0;
    c.youngsModulus_pa = 210.0e9;
    c.density_kg_m3 = 400.0;
  });
  return cases;
}

StressOutcome runStressCase(const StressCase& stressCase, double timeLimit_s, int maxIterations) {
  CylinderGridParameters parameters;
  const double f = stressCase.scale;
  parameters.radius_m = 3.0 * f;
  parameters.halfAngle_rad = 0.6;
  parameters.length_m = 3.0 * f;
  parameters.spacing_m = 0.75 * f;
  parameters.meshEdge_m = 0.1 * f;
  parameters.section.width_m = 0.05 * f;
  parameters.section.thickness_m = parameters.section.width_m / stressCase.widthToThickness;
  parameters.material.youngs_modulus_pa = stressCase.youngsModulus_pa;
  parameters.material.shear_modulus_pa = stressCase.youngsModulus_pa / 2.6;
  parameters.material.density_kg_m3 = stressCase.density_kg_m3;
  const SampleGrid grid = cylinderGrid(parameters);

  SimulationOptions options;
  options.model.gravity = true;
  options.solver.timeLimit_s = timeLimit_s;
  options.solver.maxIterations = maxIterations;
  options.scaleFactor = f;
  const SurfaceDistance surface(grid.surface);
  const SimulationRun run = simulateRods(grid.network, &surface, options);

  StressOutcome outcome;
  outcome.stressCase = stressCase;
  outcome.converged = run.solver.converged;
  outcome.status = run.solver.status;
  outcome.reason = run.solver.reason;
  outcome.vertices = run.vertices;
  outcome.iterations = run.solver.iterations;
  outcome.seconds = run.solver.seconds;
  outcome.sag_m = run.maxSag_m;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto& v : grid.surface.vertices()) {
    const auto& p = grid.surface.point(v);
    low = low.cwiseMin(Eigen::Vector3d(p[0], p[1], p[2]));
    high = high.cwiseMax(Eigen::Vector3d(p[0], p[1], p[2]));
  }
  outcome.extent_m = (high - low).norm();
  for (const auto& line : run.centrelines) {
    for (const auto& p : line) outcome.finite = outcome.finite && p.allFinite();
  }
  if (run.deviation) {
    outcome.rmse_m = run.deviation->rmse_m;
    outcome.nrmse = run.deviation->nrmse;
    outcome.maxError_m = run.deviation->max_m;
  }
  return outcome;
}

}  // namespace egg::rods
