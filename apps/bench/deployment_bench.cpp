// `egg bench deployment`: the deployment (output "deployment", issue 42) of scenes through the real
// pipeline, one row per patch: the path chosen, its steps, the peak stress ratio over the path
// beside the end state's, snaps, jammed steps, the largest support force, how far the end lies
// from the simulation's weightless equilibrium and the patch's run time; the stage's wall time.
#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/scene.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace egg::app {

namespace {

struct DeploymentBenchArgs {
  std::vector<std::string> scenes;
  int steps = 0;  // 0: the scene's deployment.steps
  bool json = false;
};

int runDeploymentBench(const DeploymentBenchArgs& args) {
  std::FILE* out = args.json ? stderr : stdout;
  fmt::print(
      out,
      "egg bench deployment: each patch from its flat grid to its supports (outputs report + "
      "deployment); peak = largest stress ratio on the path, end = at the end\n");
  fmt::print(out, "{:<12} {:>5} {:<22} {:>5} {:>5} {:>6} {:>6} {:>5} {:>6} {:>9} {:>8} {:>7}\n",
             "scene", "patch", "path", "steps", "peak", "peak_t", "end", "snaps", "jammed",
             "support_kN", "end_mm", "s");
  nlohmann::json rows = nlohmann::json::array();
  bool ok = true;
  const std::filesystem::path work = makePrivateTempFolder("egg-bench-deployment");
  for (const std::string& name : args.scenes) {
    pipeline::Scene scene = pipeline::loadScene(pipeline::benchSceneFile(name));
    scene.outputs = {"report", "deployment"};
    if (args.steps > 0) scene.deployment.steps = args.steps;
    pipeline::PipelineOptions options;
    options.outDir = work / "run";
    const pipeline::PipelineResult result = pipeline::runPipeline(scene, options);
    std::filesystem::remove_all(work / "run");
    const nlohmann::json d = result.report.value("deployment", nlohmann::json::object());
    const std::string stem = std::filesystem::path(name).stem().string();
    for (const auto& p : d.value("patches", nlohmann::json::array())) {
      if (p.contains("failure")) {
        ok = false;
        fmt::print(out, "{:<12} {:>5}  FAILED: {}\n", stem, p.value("patch", -1),
                   p["failure"].get<std::string>());
        continue;
      }
      ok = ok && p.value("completed", false);
      const auto& end = p["end_vs_simulation_rms_m"];
      fmt::print(out,
                 "{:<12} {:>5} {:<22} {:>5} {:>5.2f} {:>6.3f} {:>6.2f} {:>5} {:>6} {:>9.1f} "
                 "{:>8.2f} {:>7.1f}{}\n",
                 stem, p.value("patch", -1), p.value("path_kind", std::string()),
                 p.value("steps", 0), p.value("peak_stress_ratio", 0.0), p.value("peak_t", 0.0),
                 p.value("end_stress_ratio", 0.0), p.value("snaps", 0), p.value("jammed_steps", 0),
                 1e-3 * p.value("max_support_force_n", 0.0),
                 end.is_number() ? 1e3 * end.get<double>() : NAN, p.value("seconds", 0.0),
                 p.value("completed", false)
                     ? ""
                     : "  NOT COMPLETED: " + p.value("reason", std::string()));
    }
    // The joining of the standing patches (docs/deployment.md): its row, end against the joined
    // simulation, and the joints' gap at the end beside the joined simulation's.
    const nlohmann::json j = d.value("joined", nlohmann::json::object());
    if (j.value("ran", false) && j.contains("failure")) {
      ok = false;
      fmt::print(out, "{:<12} {:>5}  FAILED: {}\n", stem, "join", j["failure"].get<std::string>());
    } else if (j.value("ran", false)) {
      ok = ok && j.value("completed", false);
      const auto& end = j["end_vs_joined_simulation_rms_m"];
      fmt::print(out,
                 "{:<12} {:>5} {:<22} {:>5} {:>5.2f} {:>6.3f} {:>6.2f} {:>5} {:>6} {:>9.1f} "
                 "{:>8.2f} {:>7.1f}  joints {} gap {:.2f} mm (joined simulation {:.2f} mm){}\n",
                 stem, "join", "joining", j.value("steps", 0), j.value("peak_stress_ratio", 0.0),
                 j.value("peak_t", 0.0), j.value("end_stress_ratio", 0.0), j.value("snaps", 0),
                 j.value("jammed_steps", 0), 1e-3 * j.value("max_support_force_n", 0.0),
                 end.is_number() ? 1e3 * end.get<double>() : NAN, j.value("seconds", 0.0),
                 j.value("joints", 0), 1e3 * j.value("end_join_gap_m", 0.0),
                 1e3 * j.value("joined_simulation_join_gap_m", 0.0),
                 j.value("completed", false)
                     ? ""
                     : "  NOT COMPLETED: " + j.value("reason", std::string()));
    }
    fmt::print(out, "{:<12} stage {:.1f} s\n", stem, d.value("seconds", 0.0));
    std::fflush(out);
    rows.push_back({{"scene", name}, {"deployment", d}});
  }
  std::error_code ignored;  // a folder of its own (makePrivateTempFolder): nothing else in it
  std::filesystem::remove_all(work, ignored);
  if (args.json) std::cout << rows.dump(2) << "\n";
  return ok ? kExitOk : kExitFailure;
}

}  // namespace

void registerDeploymentBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<DeploymentBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "deployment",
      "The deployment of scenes through the pipeline, per patch: path chosen, steps, peak stress "
      "ratio on the path against the end state, snaps, jams, support force, end vs simulation, "
      "seconds");
  cmd->add_option("scenes", args->scenes, "sample names (great_court, ...) or scene files")
      ->required();
  cmd->add_option("--steps", args->steps, "override the scenes' deployment.steps (0: keep theirs)")
      ->check(CLI::Range(0, 1000));
  cmd->add_flag("--json", args->json, "also print the rows as JSON");
  cmd->callback([args, &action] { action = [args] { return runDeploymentBench(*args); }; });
}

}  // namespace egg::app
