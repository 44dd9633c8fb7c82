// `egg bench sim --joined`: the joined structure of each sample (every patch bolted to its
// neighbours, Section 3.5.3; issue 36), through the real pipeline up to the simulation, at each
// thread count: unknowns, Newton iterations, factorisations and where the wall time went.
#include "apps/bench/joined_bench.hpp"

#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/scene.hpp"

#include <tbb/global_control.h>
#include <unistd.h>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>

namespace egg::app {

int runJoinedSimBench(const JoinedSimBenchArgs& args) {
  if (args.repeats < 1) throw InvalidInput("--repeats must be >= 1");
  std::FILE* out = args.json ? stderr : stdout;
  fmt::print(out,
             "egg bench sim --joined: each sample's joined structure (samples/<name>.json, joined "
             "on,\nfabrication off), median of {} run(s) per thread count; phases in seconds of "
             "the joined solve\n",
             args.repeats);
  fmt::print(out,
             "{:<12} {:>7} {:>8} {:>5} {:>5} {:>5} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8}\n",
             "sample", "threads", "unknowns", "iters", "facts", "anal", "joined_s", "deriv_s",
             "factor_s", "search_s", "analys_s", "rmse_m", "max_m");
  nlohmann::json rows = nlohmann::json::array();
  bool ok = true;
  const std::filesystem::path work = makePrivateTempFolder("egg-bench-joined");
  for (const std::string& name : args.samples) {
    pipeline::Scene scene = pipeline::loadScene(pipeline::benchSceneFile(name));
    scene.simulation.joinPatches = true;
    scene.fabrication.enabled = false;
    scene.outputs = {"report"};
    for (int threads : args.threadCounts) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      static_cast<size_t>(threads));
      std::vector<double> seconds;
      nlohmann::json joined;
      for (int r = 0; r < args.repeats; ++r) {
        pipeline::PipelineOptions options;
        options.outDir = work / "run";  // a folder of this bench's own, never a path it was given
        const pipeline::PipelineResult result = pipeline::runPipeline(scene, options);
        std::filesystem::remove_all(work / "run");
        joined = result.report["simulation"].value("joined", nlohmann::json::object());
        seconds.push_back(joined.value("seconds", 0.0));
      }
      const bool converged = joined.value("converged", false);
      ok = ok && converged;
      const nlohmann::json phases = joined.value("phases_s", nlohmann::json::object());
      auto phase = [&](const char* key) { return phases.value(key, 0.0); };
      fmt::print(out,
                 "{:<12} {:>7} {:>8} {:>5} {:>5} {:>5} {:>8.2f} {:>8.2f} {:>8.2f} {:>8.2f} "
                 "{:>8.2f} {:>9.4f} {:>8.3f}{}\n",
                 name, threads, joined.value("unknowns", 0), joined.value("iterations", 0),
                 joined.value("factorisations", 0), joined.value("symbolic_analyses", 0),
                 median(seconds), phase("derivatives"), phase("factorisation"),
                 phase("line_search"), phase("symbolic_analysis"), joined.value("rmse_m", 0.0),
                 joined.value("max_error_m", 0.0),
                 converged ? "" : "  NOT CONVERGED: " + joined.value("reason", joined.dump()));
      std::fflush(out);
      rows.push_back({{"sample", name},
                      {"threads", threads},
                      {"repeats", args.repeats},
                      {"seconds", median(seconds)},
                      {"joined", joined}});
    }
  }
  std::error_code ignored;  // a folder of its own (makePrivateTempFolder): nothing else in it
  std::filesystem::remove_all(work, ignored);
  if (args.json) std::cout << rows.dump(2) << "\n";
  return ok ? kExitOk : kExitFailure;
}

}  // namespace egg::app
