#pragma once
// `egg bench pipeline`: error against run time over the whole job (issue 18, "report error against
// run time"). Each scene runs once per variant of the knobs that trade accuracy for time (the
// surface mesh's edge length, the distance maps' proxy size); every run's wall time, RMSE and max
// error of the deployed grid against the design surface go to a CSV and an SVG plot with each
// scene's Pareto front marked, beside the paper's Table 3.3.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace egg::app {

struct PipelineBenchOptions {
  std::vector<std::string> scenes{"great_court", "lilium", "yas"};  // samples/<name>.json or scene files
  std::vector<double> edgeFactors{1.0, 1.5, 2.0};  // times the scene's surface.edge_length_m
  std::vector<int> mapProxyVertices{600};          // grid.map_proxy_vertices (0 = maps on the patch)
  std::filesystem::path out = "out/bench_pipeline";  // pipeline.csv, pipeline.svg, runs/
  bool json = false;
};

// Indices of the points (time, error) that no other point beats (no slower and as close, or closer),
// by time; a point without a finite error is never on it.
std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& timeAndError);

// Runs the sweep; returns the exit code (0, or 2 for bad input).
int runPipelineBench(const PipelineBenchOptions& options);

}  // namespace egg::app
