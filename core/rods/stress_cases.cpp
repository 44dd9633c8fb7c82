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
  vary("E 0.5 GPa", [](StressCase& c) { c.youngsModulusPa = 0.5e9; });
  vary("E 210 GPa (steel)", [](StressCase& c) {
    c.youngsModulusPa = 210.0e9;
    c.densityKgM3 = 7850.0;
  });
  vary("scale 0.1 m", [](StressCase& c) { c.scale = 0.1 / 3.0; });
  vary("scale 22 m", [](StressCase& c) { c.scale = 22.0 / 3.0; });
  vary("scale 220 m", [](StressCase& c) { c.scale = 220.0 / 3.0; });
  vary("density 400", [](StressCase& c) { c.densityKgM3 = 400.0; });
  vary("density 7850", [](StressCase& c) { c.densityKgM3 = 7850.0; });
  vary("soft heavy 220 m, w:t 100", [](StressCase& c) {
    c.scale = 220.0 / 3.0;
    c.widthToThickness = 100.0;
    c.youngsModulusPa = 0.5e9;
    c.densityKgM3 = 7850.0;
  });
  vary("stiff light 0.1 m, w:t 5", [](StressCase& c) {
    c.scale = 0.1 / 3.0;
    c.widthToThickness = 5.0;
    c.youngsModulusPa = 210.0e9;
    c.densityKgM3 = 400.0;
  });
  return cases;
}

StressOutcome runStressCase(const StressCase& stressCase, double timeLimitS, int maxIterations) {
  CylinderGridParameters parameters;
  const double f = stressCase.scale;
  parameters.radiusM = 3.0 * f;
  parameters.halfAngleRad = 0.6;
  parameters.lengthM = 3.0 * f;
  parameters.spacingM = 0.75 * f;
  parameters.meshEdgeM = 0.1 * f;
  parameters.section.widthM = 0.05 * f;
  parameters.section.thicknessM = parameters.section.widthM / stressCase.widthToThickness;
  parameters.material.youngsModulusPa = stressCase.youngsModulusPa;
  parameters.material.shearModulusPa = stressCase.youngsModulusPa / 2.6;
  parameters.material.densityKgM3 = stressCase.densityKgM3;
  const SampleGrid grid = cylinderGrid(parameters);

  SimulationOptions options;
  options.model.gravity = true;
  options.solver.timeLimitS = timeLimitS;
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
  outcome.sagM = run.maxSagM;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto& v : grid.surface.vertices()) {
    const auto& p = grid.surface.point(v);
    low = low.cwiseMin(Eigen::Vector3d(p[0], p[1], p[2]));
    high = high.cwiseMax(Eigen::Vector3d(p[0], p[1], p[2]));
  }
  outcome.extentM = (high - low).norm();
  for (const auto& line : run.centrelines) {
    for (const auto& p : line) outcome.finite = outcome.finite && p.allFinite();
  }
  if (run.deviation) {
    outcome.rmseM = run.deviation->rmseM;
    outcome.nrmse = run.deviation->nrmse;
    outcome.maxErrorM = run.deviation->maxM;
  }
  return outcome;
}

}  // namespace egg::rods
