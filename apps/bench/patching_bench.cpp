// `egg bench patching`: the automatic decomposition (Workflow 2, then Workflow 1's splits) of the
// architectural samples at their scene settings: wall time, patches against the paper's hand
// layouts, patches evaluated, splits, coverage and how many patches are feasible (Section 3.4.3).
#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/timing.hpp"
#include "pipeline/patching_stage.hpp"
#include "pipeline/surface_stage.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

namespace egg::app {
using namespace egg::pipeline;
namespace {

struct PatchingBenchArgs {
  std::vector<std::string> samples{"great_court", "lilium", "yas"};
  int repeats = 1;
  bool json = false;
};

int runPatchingBench(const PatchingBenchArgs& args) {
  // The paper's hand layouts (Table 3.3) beside ours.
  const std::map<std::string, int> paper{{"great_court", 4}, {"lilium", 16}, {"yas", 16}};
  nlohmann::json rows = nlohmann::json::array();
  if (!args.json) {
    fmt::print(
        "egg bench patching: Workflow 2 + Workflow 1 on the sample scenes (samples/<name>.json), "
        "median of {} run(s)\n",
        args.repeats);
    fmt::print("{:<12} {:>8} {:>8} {:>7} {:>9} {:>7} {:>9} {:>9} {:>9}\n", "sample", "wall_s",
               "patches", "paper", "feasible", "splits", "screened", "evaluated", "coverage");
  }
  for (const auto& name : args.samples) {
    // A name is a sample scene of the repository (run from its root, as `egg run`'s default), or a
    // scene file.
    const std::filesystem::path file = benchSceneFile(name);
    const Scene scene = loadScene(file);
    const LoadedSurface surface = loadSurface(scene.surface);
    std::vector<double> times;
    PatchingRun run;
    for (int r = 0; r < args.repeats; ++r) {
      const Stopwatch watch;
      const geodesic::DistanceSolver solver(surface.mesh);
      run = runPatching(surface.mesh, solver, scene);
      times.push_back(watch.seconds());
    }
    const double wall = median(times);
    const int feasible =
        static_cast<int>(std::count_if(run.layout.patches.begin(), run.layout.patches.end(),
                                       [](const auto& p) { return p.feasible(); }));
    const int patches = static_cast<int>(run.layout.patches.size());
    const int paperCount = paper.count(name) ? paper.at(name) : 0;
    rows.push_back({{"sample", name},
                    {"wall_s", wall},
                    {"patches", patches},
                    {"paper_patches", paperCount},
                    {"feasible", feasible},
                    {"splits", run.layout.splits.size()},
                    {"screened", run.initial ? run.initial->candidatesScreened : 0},
                    {"evaluated", run.layout.evaluations},
                    {"coverage", run.coverage.fraction}});
    if (!args.json)
      fmt::print("{:<12} {:>8.2f} {:>8} {:>7} {:>9} {:>7} {:>9} {:>9} {:>9.3f}\n", name, wall,
                 patches, paperCount, feasible, run.layout.splits.size(),
                 run.initial ? run.initial->candidatesScreened : 0, run.layout.evaluations,
                 run.coverage.fraction);
  }
  if (args.json) std::cout << rows.dump(2) << "\n";
  return kExitOk;
}

}  // namespace

void registerPatchingBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<PatchingBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "patching",
      "Automatic decomposition of the architectural samples (Workflow 2 + 1): wall time, "
      "patches (beside the paper's hand layouts), feasible, splits, coverage");
  cmd->add_option("--samples", args->samples,
                  "sample scenes (samples/<name>.json, from the repository root) or scene files")
      ->delimiter(',');
  cmd->add_option("--repeats", args->repeats, "runs per sample; the median time is shown")
      ->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "print the rows as JSON only");
  cmd->callback([args, &action] { action = [args] { return runPatchingBench(*args); }; });
}

}  // namespace egg::app
