#pragma once
// Stiff and extreme cases for the simulation (`egg stress`): the cylinder vault of
// sample_grids.hpp scaled from 0.1 m to 220 m, with width:thickness 5..100, E 0.5..210 GPa and
// densities 400..7850 kg/m^3, under self-weight. Each case must converge or say why, never give
// NaN, never hang (time and iteration limits).
#include "core/rods/simulation.hpp"

#include <string>
#include <vector>

namespace egg::rods {

struct StressCase {
  std::string name;
  double scale = 1.0;              // vault span factor: radius 3 f, length 3 f, spacing 0.75 f (m)
  double widthToThickness = 10.0;  // lamella width 0.05 f, thickness = width / this
  double youngsModulusPa = 10.0e9;
  double densityKgM3 = 500.0;
};

// One factor at a time around the base case, then the two extreme corners.
std::vector<StressCase> stressCases();

struct StressOutcome {
  StressCase stressCase;
  bool converged = false;
  bool finite = true;  // every centreline coordinate finite
  SolverStatus status =
      SolverStatus::IterationLimit;  // e.g. collapsed: no equilibrium near the design
  std::string reason;                // the solver's reason (why it stopped)
  int vertices = 0;
  int iterations = 0;
  double seconds = 0.0;
  double rmseM = 0.0;
  double nrmse = 0.0;  // rmse / scale
  double maxErrorM = 0.0;
  double sagM = 0.0;  // largest displacement from the weightless equilibrium
  double extentM =
      0.0;  // the design surface's bounding-box diagonal (a sag of several % of it: collapsed)
};

// 1000 iterations: thin or heavy vaults that fall through need several hundred Newton
// iterations to reach their collapsed equilibrium (w:t 100: 615-636, depending on round-off).
StressOutcome runStressCase(const StressCase& stressCase, double timeLimitS = 20.0,
                            int maxIterations = 1000);

}  // namespace egg::rods
