// `egg bench sim` (time against error of the rod simulation at several tolerances) and
// `egg stress` (stiff and extreme cases: converge or say why, never NaN, never hang).
#include "apps/bench/bench_stats.hpp"
#include "apps/bench/joined_bench.hpp"
#include "apps/egg/commands.hpp"

#include "apps/bench/stress_suite.hpp"
#include "apps/egg/progress.hpp"
#include "core/rods/sample_grids.hpp"
#include "core/rods/simulation.hpp"
#include "core/rods/stress_cases.hpp"

#include <unistd.h>
#include <filesystem>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace egg::app {
namespace {

// With --json, stdout carries only the JSON document; the human table goes to stderr.
std::FILE* simTableStream(bool json) { return json ? stderr : stdout; }

struct SimBenchArgs {
  std::vector<double> spacings{1.0, 0.8, 0.72};
  std::vector<double> tolerances{1e-4, 1e-6, 1e-8, 1e-10};
  double notchFraction = 0.2;
  bool gravity = false;
  int threads = 2;
  int repeats = 3;
  bool reference = true;
  std::string csv;
  bool json = false;
  JoinedSimBenchArgs joined;  // --joined: the samples' joined structures instead of the vault
};

// Runs one simulation `repeats` times (deterministic: the same iterations and result every
// time) and keeps the last run with the median wall time.
struct TimedRun {
  rods::SimulationRun run;
  double medianSeconds = 0.0, minSeconds = 0.0, maxSeconds = 0.0;
};

TimedRun timedRun(const rods::RodNetwork& network, const rods::SurfaceDistance& surface,
                  const rods::SimulationOptions& options, int repeats) {
  TimedRun timed;
  std::vector<double> seconds;
  for (int k = 0; k < repeats; ++k) {
    timed.run = rods::simulateRods(network, &surface, options);
    seconds.push_back(timed.run.solver.seconds);
  }
  timed.medianSeconds = median(seconds);
  timed.minSeconds = *std::min_element(seconds.begin(), seconds.end());
  timed.maxSeconds = *std::max_element(seconds.begin(), seconds.end());
  return timed;
}

int runSimBench(const SimBenchArgs& args) {
  if (args.repeats < 1) throw InvalidInput("--repeats must be >= 1");
  if (!args.joined.samples.empty()) {
    JoinedSimBenchArgs joined = args.joined;
    joined.repeats = args.repeats;
    joined.json = args.json;
    return runJoinedSimBench(joined);
  }
  nlohmann::json rows = nlohmann::json::array();
  fmt::print(simTableStream(args.json),
             "egg bench sim: cylinder vault R 5 m, 8 m long, exact geodesic grid at +-45 deg, "
             "lamellas 50 x 5 mm,\n"
             "supports at every member end, notches +-{:.0f} % of the spacing on inner bolts{}, {} "
             "thread(s);\n"
             "seconds = median of {} runs (solver + setup, one simulation){}\n",
             100.0 * args.notchFraction, args.gravity ? ", self-weight" : "", args.threads,
             args.repeats,
             args.reference ? ";\nplain_s = the same grid with plain holes (no sliding, RMS1 run), "
                              "ratio = seconds / plain_s"
                            : "");
  fmt::print(simTableStream(args.json),
             "{:>7} {:>8} {:>8} {:>5} {:>9} {:>5} {:>8} {:>15} {:>9} {:>4} {:>9} {:>9} {:>8} {:>5} "
             "{:>6}\n",
             "spacing", "vertices", "unknowns", "bolts", "tolerance", "iters", "seconds",
             "(min..max)", "grad_norm", "conv", "rmse_mm", "max_mm", "plain_s", "iters", "ratio");
  for (double spacing : args.spacings) {
    rods::CylinderGridParameters parameters;
    parameters.spacingM = spacing;
    parameters.notchFraction = args.notchFraction;
    parameters.meshEdgeM = 0.05;
    const rods::SampleGrid grid = rods::cylinderGrid(parameters);
    const rods::SurfaceDistance surface(grid.surface);
    for (double tolerance : args.tolerances) {
      rods::SimulationOptions options;
      options.model.gravity = args.gravity;
      options.solver.tolerance = tolerance;
      options.solver.threads = args.threads;
      const TimedRun notched = timedRun(grid.network, surface, options, args.repeats);
      std::optional<TimedRun> plain;
      if (args.reference) {
        rods::SimulationOptions plainOptions = options;
        plainOptions.model.notches = false;
        plain = timedRun(grid.network, surface, plainOptions, args.repeats);
      }
      const rods::SimulationRun& run = notched.run;
      const double rmse = run.deviation ? run.deviation->rmseM : 0.0;
      const double maxError = run.deviation ? run.deviation->maxM : 0.0;
      const double ratio = plain ? notched.medianSeconds / plain->medianSeconds : 0.0;
      fmt::print(simTableStream(args.json),
                 "{:>7.2f} {:>8} {:>8} {:>5} {:>9.0e} {:>5} {:>8.3f} {:>15} {:>9.2e} {:>4} "
                 "{:>9.4f} {:>9.4f} {:>8} {:>5} {:>6}\n",
                 spacing, run.vertices, run.unknowns, grid.network.connections.size(), tolerance,
                 run.solver.iterations, notched.medianSeconds,
                 fmt::format("({:.3f}..{:.3f})", notched.minSeconds, notched.maxSeconds),
                 run.solver.gradientNorm, run.solver.converged ? "yes" : "no", 1e3 * rmse,
                 1e3 * maxError, plain ? fmt::format("{:.3f}", plain->medianSeconds) : "-",
                 plain ? std::to_string(plain->run.solver.iterations) : "-",
                 plain ? fmt::format("{:.2f}", ratio) : "-");
      if (!run.solver.converged)
        fmt::print(simTableStream(args.json), "        not converged: {}\n", run.solver.reason);
      nlohmann::json row{{"spacing_m", spacing},
                         {"vertices", run.vertices},
                         {"unknowns", run.unknowns},
                         {"bolts", grid.network.connections.size()},
                         {"tolerance", tolerance},
                         {"iterations", run.solver.iterations},
                         {"seconds", notched.medianSeconds},
                         {"seconds_min", notched.minSeconds},
                         {"seconds_max", notched.maxSeconds},
                         {"repeats", args.repeats},
                         {"gradient_norm", run.solver.gradientNorm},
                         {"energy_J", run.solver.energy},
                         {"converged", run.solver.converged},
                         {"reason", run.solver.reason},
                         {"rmse_m", rmse},
                         {"max_error_m", maxError}};
      if (plain) {
        row["plain_seconds"] = plain->medianSeconds;
        row["plain_iterations"] = plain->run.solver.iterations;
        row["plain_converged"] = plain->run.solver.converged;
        row["plain_rmse_m"] = plain->run.deviation ? plain->run.deviation->rmseM : 0.0;
        row["ratio_to_plain"] = ratio;
      }
      rows.push_back(row);
    }
  }
  if (!args.csv.empty()) {
    std::ostringstream file;
    file << "spacing_m,vertices,unknowns,bolts,tolerance,iterations,seconds,seconds_min,seconds_"
            "max,gradient_norm,"
            "converged,rmse_m,max_error_m,plain_seconds,plain_iterations,plain_rmse_m,ratio_to_"
            "plain\n";
    for (const auto& r : rows) {
      auto number = [&](const char* key) {
        return r.contains(key) ? fmt::format("{}", r[key].get<double>()) : std::string();
      };
      file << fmt::format(
          "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r["spacing_m"].get<double>(),
          r["vertices"].get<int>(), r["unknowns"].get<int>(), r["bolts"].get<size_t>(),
          r["tolerance"].get<double>(), r["iterations"].get<int>(), r["seconds"].get<double>(),
          r["seconds_min"].get<double>(), r["seconds_max"].get<double>(),
          r["gradient_norm"].get<double>(), r["converged"].get<bool>() ? 1 : 0,
          r["rmse_m"].get<double>(), r["max_error_m"].get<double>(), number("plain_seconds"),
          r.contains("plain_iterations") ? std::to_string(r["plain_iterations"].get<int>()) : "",
          number("plain_rmse_m"), number("ratio_to_plain"));
    }
    writeFileAtomically(args.csv, file.str());
  }
  if (args.json) std::cout << rows.dump(2) << "\n";
  return kExitOk;
}

struct StressArgs {
  double timeLimit = 20.0;  // per rods case; per pipeline case too when given (timeLimitGiven)
  bool timeLimitGiven = false;
  int maxIterations = 1000;
  bool json = false;
  std::string suite = "all";
  bool keep = false;
  std::string largeMeshStages =
      "geodesic";  // the 1M-face case: "surface" (load + curvature) or also "geodesic"
};

// The pipeline suite (stress_suite.hpp): each case is `egg run` (or surface + geodesic) in a child.
bool runPipelineSuite(const StressArgs& args, nlohmann::json& rows) {
  namespace fs = std::filesystem;
  const fs::path work = makePrivateTempFolder("egg-stress");
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const EggCommand command = [exe](const std::vector<std::string>& a) {
    std::vector<std::string> all{exe.string()};
    all.insert(all.end(), a.begin(), a.end());
    std::vector<char*> argv;
    for (auto& s : all) argv.push_back(s.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    return 127;
  };
  std::FILE* out = simTableStream(args.json);
  fmt::print(out,
             "\negg stress --suite pipeline: fixed scenes and meshes through the real pipeline, "
             "one child process\n"
             "per case (time limit each; peak memory = the child's VmHWM); ok = converged or a "
             "stated reason\n");
  fmt::print(out, "{:<17} {:<21} {:>6} {:>9} {:>9} {:>8} {:>8}  {:<4} {} [{}]\n", "case", "class",
             "iters", "rmse_m", "max_err_m", "seconds", "peak_MB", "ok", "result", "stages");
  bool ok = true;
  // On a terminal, which case is running (the row appears when it ends; cases take up to minutes).
  ProgressLine bar(!args.json);
  const auto cases = pipelineStressCases();
  for (size_t k = 0; k < cases.size(); ++k) {
    PipelineStressCase c = cases[k];
    if (c.surfaceOnly && args.largeMeshStages == "surface") c.geodesic = false;
    // --time-limit bounds every case it is given for (issue 40: the pipeline cases ignored it and
    // kept their own 60 s and 300 s).
    if (args.timeLimitGiven) c.timeLimitS = args.timeLimit;
    bar.update(static_cast<double>(k) / cases.size(),
               fmt::format("case {} of {}: {}", k + 1, cases.size(), c.name));
    const PipelineStressRow r = runPipelineStressCase(c, command, work);
    bar.clear();
    ok = ok && r.ok;
    fmt::print(out, "{:<17} {:<21} {:>6} {:>9.3g} {:>9.3g} {:>8.2f} {:>8.0f}  {:<4} {} [{}]\n",
               r.name, r.kind, r.iterations, r.rmseM, r.maxErrorM, r.seconds, r.peakRssMb,
               r.ok ? "yes" : "NO", r.result, r.stages);
    std::fflush(out);
    rows.push_back(r.toJson());
  }
  if (!args.keep)
    fs::remove_all(work);
  else
    fmt::print(out, "case folders kept in {}\n", work.string());
  return ok;
}

int runStress(const StressArgs& args) {
  if (!(args.timeLimit > 0.0)) throw InvalidInput("--time-limit must be > 0");
  nlohmann::json rows = nlohmann::json::array();
  bool allFinite = true;
  if (args.suite == "pipeline") {
    nlohmann::json prow = nlohmann::json::array();
    const bool ok = runPipelineSuite(args, prow);
    if (args.json) std::cout << nlohmann::json{{"pipeline", prow}}.dump(2) << "\n";
    return ok ? kExitOk : kExitFailure;
  }
  fmt::print(simTableStream(args.json),
             "egg stress: cylinder vault (radius = length = 3 f, spacing 0.75 f, width 0.05 f) "
             "under self-weight;\n"
             "every case converges or says why, never NaN (limits: {} s, {} iterations)\n",
             args.timeLimit, args.maxIterations);
  fmt::print(
      simTableStream(args.json),
      "sag = largest displacement from the weightless equilibrium, in % of the vault's extent; a "
      "converged\n"
      "case that sags several % has found a collapsed equilibrium (the jump of Fig. 3.11)\n");
  fmt::print(simTableStream(args.json),
             "{:<28} {:>9} {:>6} {:>8} {:>6} {:>6} {:>8} {:>10} {:>9} {:>7}  {}\n", "case",
             "scale_m", "w:t", "E_GPa", "rho", "iters", "seconds", "rmse_m", "nrmse", "sag_%",
             "result");
  for (const rods::StressCase& c : rods::stressCases()) {
    const rods::StressOutcome o = rods::runStressCase(c, args.timeLimit, args.maxIterations);
    allFinite = allFinite && o.finite;
    const std::string result = !o.finite     ? "NON-FINITE"
                               : o.converged ? "converged"
                                             : "stopped: " + o.reason;
    const double sagPercent = o.extentM > 0.0 ? 100.0 * o.sagM / o.extentM : 0.0;
    fmt::print(simTableStream(args.json),
               "{:<28} {:>9.3g} {:>6.0f} {:>8.3g} {:>6.0f} {:>6} {:>8.2f} {:>10.3g} {:>9.3g} "
               "{:>7.2f}  {}\n",
               c.name, 3.0 * c.scale, c.widthToThickness, 1e-9 * c.youngsModulusPa, c.densityKgM3,
               o.iterations, o.seconds, o.rmseM, o.nrmse, sagPercent, result);
    rows.push_back({{"case", c.name},
                    {"span_m", 3.0 * c.scale},
                    {"width_to_thickness", c.widthToThickness},
                    {"youngs_modulus_pa", c.youngsModulusPa},
                    {"density_kg_m3", c.densityKgM3},
                    {"vertices", o.vertices},
                    {"iterations", o.iterations},
                    {"seconds", o.seconds},
                    {"converged", o.converged},
                    {"status", rods::toString(o.status)},
                    {"finite", o.finite},
                    {"reason", o.reason},
                    {"rmse_m", o.rmseM},
                    {"nrmse", o.nrmse},
                    {"sag_m", o.sagM},
                    {"extent_m", o.extentM},
                    {"max_error_m", o.maxErrorM}});
  }
  bool pipelineOk = true;
  nlohmann::json prow = nlohmann::json::array();
  if (args.suite == "all") pipelineOk = runPipelineSuite(args, prow);
  // --suite rods keeps the rod table's JSON array as before; all: both tables under their names.
  if (args.json && args.suite == "rods")
    std::cout << rows.dump(2) << "\n";
  else if (args.json)
    std::cout << nlohmann::json{{"rods", rows}, {"pipeline", prow}}.dump(2) << "\n";
  return allFinite && pipelineOk ? kExitOk : kExitFailure;
}

}  // namespace

void registerSimBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<SimBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "sim",
      "Rod simulation (DER, sliding bolts, notches) on a patch-like grid of ~400-800 vertices: "
      "Newton iterations, median wall time and RMSE to the design surface at several tolerances, "
      "against the same grid with plain holes");
  cmd->add_option("--spacings", args->spacings,
                  "member spacings in m (1.0 -> 416 vertices, 0.8 -> 640, 0.72 -> 784)")
      ->delimiter(',')
      ->check(finiteRange(0.25, 8.0));  // 0.25 m: ~8,000 vertices; 0.001 m grew past 12 GB
  cmd->add_option("--tolerances", args->tolerances, "relative Newton-decrement tolerances")
      ->delimiter(',')
      ->check(finiteRange(1e-15, 1.0));
  cmd->add_option("--notch-fraction", args->notchFraction,
                  "notch length on each side of inner bolts, in spacings")
      ->check(finiteRange(0.0, 0.45));
  cmd->add_flag("--gravity", args->gravity, "add self-weight");
  cmd->add_option("--threads", args->threads, "threads assembling the Hessian")
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_option("--repeats", args->repeats, "runs per row; the table shows the median time")
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("!--no-reference", args->reference,
                "skip the plain-hole reference run of each row");
  cmd->add_option("--csv", args->csv, "also write the table as CSV");
  cmd->add_flag("--json", args->json, "also print the table as JSON");
  cmd->add_option("--joined", args->joined.samples,
                  "instead: the joined structure of these samples (e.g. "
                  "great_court,lilium,yas), through the pipeline")
      ->delimiter(',');
  cmd->add_option("--thread-counts", args->joined.threadCounts,
                  "with --joined: thread counts (egg run --threads) to run each sample at")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxThreads));
  cmd->callback([args, &action] { action = [args] { return runSimBench(*args); }; });
}

void registerStressCommand(CLI::App& parent, Action& action) {
  auto args = std::make_shared<StressArgs>();
  auto* cmd = parent.add_subcommand("stress",
                                    "Stiff and extreme cases. Suite 'rods': the simulation on a "
                                    "cylinder vault (width:thickness 5-100, "
                                    "E 0.5-210 GPa, 0.1-220 m, 400-7850 kg/m3). Suite 'pipeline' "
                                    "(fixed, egg run per case in a child "
                                    "with a time limit): wt_5, wt_100, E_4GPa_birch, "
                                    "E_210GPa_steel, scale_0.1m, scale_220m, nearly_flat, "
                                    "sharp_k_peak, alpha_bar_max, alpha_bar_0.05 (near-collapsed "
                                    "quads), sliver_triangles, holes, "
                                    "disconnected, non_manifold (typed error expected), "
                                    "million_faces (surface + curvature + one geodesic "
                                    "field only). Each case converges or reports why; exit 1 on a "
                                    "non-finite result, a crash or a timeout");
  cmd->add_option("--suite", args->suite, "rods, pipeline or all")
      ->check(CLI::IsMember({"rods", "pipeline", "all"}));
  cmd->add_flag("--keep", args->keep,
                "keep the pipeline cases' folders (scenes, meshes, logs, reports)");
  cmd->add_option("--large-mesh-stages", args->largeMeshStages,
                  "the 1M-face case: surface (load + curvature) or geodesic (also one exact field "
                  "over 500k vertices, "
                  "~55 s on 2 cores with the wavefront engine)")
      ->check(CLI::IsMember({"surface", "geodesic"}));
  CLI::Option* timeLimit =
      cmd->add_option("--time-limit", args->timeLimit,
                      "seconds per case (default: 20 s a rods case; 60 s a pipeline case, 300 s "
                      "the 1M-face one)")
          ->check(finiteRange(1e-3, 86400.0));
  cmd->add_option("--max-iterations", args->maxIterations, "Newton iterations per case")
      ->check(CLI::Range(1, 1000000));
  cmd->add_flag("--json", args->json, "also print the table as JSON");
  cmd->callback([args, timeLimit, &action] {
    args->timeLimitGiven = timeLimit->count() > 0;
    action = [args] { return runStress(*args); };
  });
}

}  // namespace egg::app
