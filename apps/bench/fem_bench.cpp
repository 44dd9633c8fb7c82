// `egg bench fem`: the FE check (output "fem", issue 37) of scenes through the real pipeline:
// the FE model's size, whether ccx was run on it (loads.max_fe_elements), the verification
// stage's wall time with ccx's share, the equilibrium residual, the first buckling factor and the
// DER-against-FE sag difference. Medians of --repeats runs.
#include "apps/bench/fem_bench.hpp"

#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/scene.hpp"

#include <unistd.h>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

namespace egg::app {

int runFemBench(const FemBenchArgs& args) {
  std::FILE* out = args.json ? stderr : stdout;
  fmt::print(out,
             "egg bench fem: the FE check of each scene (outputs report + fem), median of {} "
             "run(s); stage_s is the verification stage (the rods' weightless and self-weight "
             "solves, the model, ccx), ccx_s ccx's own runs (cases and buckling)\n",
             args.repeats);
  fmt::print(out, "{:<14} {:>8} {:>7} {:>6} {:>8} {:>8} {:>10} {:>8} {:>9}\n", "scene", "elements",
             "nodes", "solved", "stage_s", "ccx_s", "equil_res", "buckle1", "der_fe_mm");
  nlohmann::json rows = nlohmann::json::array();
  bool ok = true;
  // A folder of this bench's own, never a path it was given.
  const std::filesystem::path work = makePrivateTempFolder("egg-bench-fem");
  for (const std::string& name : args.scenes) {
    pipeline::Scene scene = pipeline::loadScene(pipeline::benchSceneFile(name));
    scene.outputs = {"report", "fem"};
    if (args.maxFeElements > 0) scene.loads.maxFeElements = args.maxFeElements;
    std::vector<double> stage, ccx;
    nlohmann::json v;
    for (int r = 0; r < args.repeats; ++r) {
      pipeline::PipelineOptions options;
      options.outDir = work / "run";
      const pipeline::PipelineResult result = pipeline::runPipeline(scene, options);
      std::filesystem::remove_all(work / "run");
      v = result.report.value("verification", nlohmann::json::object());
      stage.push_back(v.value("seconds", 0.0));
      double c = 0.0;
      for (const auto& k : v.value("cases", nlohmann::json::array()))
        c += k.value("ccx_seconds", 0.0);
      ccx.push_back(c + v.value("buckling_ccx_seconds", 0.0));
    }
    const bool failed = v.contains("failure") || !v.contains("model");
    ok = ok && !failed;
    const nlohmann::json model = v.value("model", nlohmann::json::object());
    const nlohmann::json factors = v.value("buckling_factors", nlohmann::json::array());
    const bool solved = v.value("solved", false);
    const double residual = v.value("max_equilibrium_residual", NAN);
    const double buckle = factors.empty() ? NAN : factors[0].get<double>();
    const double sagMm =
        1e3 * v.value("der_vs_fem", nlohmann::json::object()).value("rms_m", double(NAN));
    fmt::print(out, "{:<14} {:>8} {:>7} {:>6} {:>8.2f} {:>8.2f} {:>10.2e} {:>8.3f} {:>9.2f}{}\n",
               std::filesystem::path(name).stem().string(), model.value("elements", 0),
               model.value("nodes", 0), solved ? "yes" : "no", median(stage), median(ccx), residual,
               buckle, sagMm,
               failed ? "  FAILED: " + v.value("failure", v.dump())
                      : (solved ? "" : "  (decks written, not solved: loads.max_fe_elements)"));
    std::fflush(out);
    rows.push_back({{"scene", name},
                    {"repeats", args.repeats},
                    {"stage_seconds", median(stage)},
                    {"ccx_seconds", median(ccx)},
                    {"verification", v}});
  }
  std::error_code ignored;  // a folder of its own (makePrivateTempFolder): nothing else in it
  std::filesystem::remove_all(work, ignored);
  if (args.json) std::cout << rows.dump(2) << "\n";
  return ok ? kExitOk : kExitFailure;
}

void registerFemBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<FemBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "fem",
      "The FE check (CalculiX) of scenes through the pipeline: model size, solved or not, stage "
      "and ccx wall time, equilibrium residual, first buckling factor, DER vs FE sag");
  cmd->add_option("scenes", args->scenes, "sample names (great_court, ...) or scene files")
      ->required();
  cmd->add_option("--max-fe-elements", args->maxFeElements,
                  "override the scenes' loads.max_fe_elements (0: keep theirs)")
      ->check(CLI::Range(0, 10000000));
  cmd->add_option("--repeats", args->repeats, "runs per scene; the table shows medians")
      ->check(CLI::Range(1, 100));
  cmd->add_flag("--json", args->json, "also print the rows as JSON");
  cmd->callback([args, &action] { action = [args] { return runFemBench(*args); }; });
}

}  // namespace egg::app
