// `egg bench layout`: the multi-patch stages (patching, design, grid) of a 2 x 2 layout on a bump,
// on 1 and on 2 threads in alternation (so both see the same machine load), medians and their
// ratio: patches are designed and traced in parallel, and the speed-up says how well.
#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/timing.hpp"
#include "pipeline/grid_stage.hpp"
#include "pipeline/patching_stage.hpp"
#include "pipeline/surface_stage.hpp"

#include <fmt/core.h>
#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <utility>

namespace egg::app {
using namespace egg::pipeline;
namespace {

struct LayoutBenchArgs {
  int repeats = 5;
  double edgeLength = 0.15;
  bool json = false;
};

int runLayoutBench(const LayoutBenchArgs& args) {
  // The 2 x 2 layout's corners on the bump itself (z = h(x, y)), so that every edge length in the
  // option's range meshes a surface they lie on.
  const auto corner = [](double x, double y) {
    return nlohmann::json::array({x, y, std::exp(-(x * x + y * y) / (2 * 1.5 * 1.5))});
  };
  nlohmann::json patches = nlohmann::json::array();
  for (const auto& [x0, y0] : {std::pair{-3.0, -3.0}, {0.0, -3.0}, {-3.0, 0.0}, {0.0, 0.0}})
    patches.push_back(
        {corner(x0, y0), corner(x0 + 3, y0), corner(x0 + 3, y0 + 3), corner(x0, y0 + 3)});
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "bench_layout",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1.0, "sigma": 1.5}},
    "grid": {"members_per_family": 8},
    "lamella": {"width_m": 0.05, "thickness_m": 0.005},
    "outputs": ["report"]})");
  doc["surface"]["edge_length_m"] = args.edgeLength;
  doc["patching"]["patches"] = patches;
  // The scene is the bench's own: its messages name the command and option the user gave.
  const Scene scene =
      parseScene(doc, fmt::format("egg bench layout --edge-length {}", args.edgeLength));
  const LoadedSurface surface = loadSurface(scene.surface);
  const geodesic::DistanceSolver solver(surface.mesh);
  std::map<int, std::vector<double>> wall, design;
  int vertices = 0;
  for (int r = 0; r < args.repeats; ++r)
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      const Stopwatch watch;
      PatchingRun run = runPatching(surface.mesh, solver, scene);
      std::vector<SolvedPatch> patches = layoutPatches(run);
      tracePatches(run, patches);
      wall[threads].push_back(watch.seconds());
      double perPatch = 0.0;
      for (const auto& p : run.layout.patches)
        if (p.design) perPatch += p.design->seconds.total / run.layout.patches.size();
      design[threads].push_back(perPatch);
      vertices = 0;
      for (const auto& p : patches)
        if (p.egg) vertices += static_cast<int>(p.egg->patch.mesh.n_vertices());
    }
  const double t1 = median(wall[1]), t2 = median(wall[2]);
  if (args.json) {
    std::cout << nlohmann::json{{"patches", 4},
                                {"patch_vertices_total", vertices},
                                {"repeats", args.repeats},
                                {"wall_1_thread_s", t1},
                                {"wall_2_threads_s", t2},
                                {"speedup", t1 / t2},
                                {"design_per_patch_1_thread_s", median(design[1])}}
                     .dump(2)
              << "\n";
    return kExitOk;
  }
  fmt::print(
      "egg bench layout: 4 patches of a 2 x 2 layout on a 1 m bump ({} patch vertices in all), "
      "patching + design + grid\n",
      vertices);
  fmt::print("medians of {} runs, 1 and 2 threads alternating\n", args.repeats);
  fmt::print("{:>8} {:>10} {:>18}\n", "threads", "wall_s", "design/patch_s");
  for (int threads : {1, 2})
    fmt::print("{:>8} {:>10.3f} {:>18.3f}\n", threads, median(wall[threads]),
               median(design[threads]));
  fmt::print("speed-up 2 threads / 1 thread: {:.2f}x\n", t1 / t2);
  return kExitOk;
}

}  // namespace

void registerLayoutBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<LayoutBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "layout",
      "Multi-patch stages (patching, design, grid) of a 2 x 2 layout on 1 and 2 threads: "
      "median wall times and the speed-up");
  cmd->add_option("--repeats", args->repeats, "runs per thread count")->check(CLI::Range(1, 1000));
  cmd->add_option("--edge-length", args->edgeLength, "mesh edge length of the bump (m)")
      ->check(CLI::Range(0.02, 2.0));
  cmd->add_flag("--json", args->json, "print the figures as JSON only");
  cmd->callback([args, &action] { action = [args] { return runLayoutBench(*args); }; });
}

}  // namespace egg::app
