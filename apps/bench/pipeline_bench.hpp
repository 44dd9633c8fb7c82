#pragma once
// `egg bench pipeline`: error against run time over the whole job (issue 18, "report error against
// run time"). Each scene runs once per variant of the knobs that trade accuracy for time: the
// surface mesh's edge length, the distance maps' proxy size and row tolerance, the Newton
// tolerance of the simulation and the members' target spacing (members per family), and, for the
// samples, the paper's lamella section. Every run's wall time, RMSE and max error of the deployed
// grid against the design surface go to a CSV and an SVG plot (RMSE and max error against time)
// with each scene's Pareto front marked, beside the paper's Table 3.3.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace egg::app {

struct PipelineBenchOptions {
  std::vector<std::string> scenes{"great_court", "lilium",
                                  "yas"};  // samples/<name>.json or scene files
  // Knob values; the scene's own value is used where a list is empty. By default each knob is
  // varied alone from the first value of every list (one run per value, the others at their first);
  // `product` runs every combination instead.
  std::vector<double> edgeFactors{1.0, 1.5, 2.0};  // times the scene's surface.edge_length_m
  std::vector<int> mapProxyVertices{600, 0};  // grid.map_proxy_vertices (0 = maps on the patch)
  std::vector<double> mapTolerances{};        // grid.map_tolerance_relative (only with proxy 0)
  std::vector<double> newtonTolerances{1e-10, 1e-6};  // simulation.newton_tolerance
  std::vector<double> spacingFactors{
      8.0, 12.0};  // grid.member_spacing_factor (fewer members per family when larger)
  bool paperSection =
      true;  // also run each sample at Table 3.3's lamella section (25x4, 50x5, 40x5 cm)
  bool product = false;
  std::filesystem::path out = "out/bench_pipeline";  // pipeline.csv, pipeline.svg, runs/
  bool json = false;
  bool progress =
      false;  // a progress line on stderr (the command sets it when stderr is a terminal)
};

// Indices of the points (time, error) that no other point beats (no slower and as close, or
// closer), by time; a point without a finite error is never on it.
std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& timeAndError);

// One run of the bench: a value per knob (NaN / -1 = the scene's own) and what it varies.
struct PipelineVariant {
  double edgeFactor = 1.0;
  int mapProxyVertices = -1;
  double mapTolerance = -1.0, newtonTolerance = -1.0, spacingFactor = -1.0;
  double widthM = -1.0, thicknessM = -1.0;  // the lamella section (paper section variant)
  std::string varied = "base";              // the knob this run changes from the base, or "product"
};

// The runs of one scene (`sample` = its name, to find its paper section): the base first.
std::vector<PipelineVariant> pipelineVariants(const PipelineBenchOptions& options,
                                              const std::string& sample);

// Runs the sweep; returns the exit code (0, or 2 for bad input).
int runPipelineBench(const PipelineBenchOptions& options);

}  // namespace egg::app
