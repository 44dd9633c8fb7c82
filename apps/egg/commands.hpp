#pragma once
// Subcommands of the `egg` program. Each subcommand lives in its own file and exposes one
// registration function; cli.cpp calls them all. A registration function adds a CLI11 subcommand
// to `parent` and, when that subcommand is chosen, stores in `action` what to run. The action
// returns an exit code; exceptions from the libraries are mapped to messages and codes in cli.cpp.
#include <CLI/CLI.hpp>

#include <cmath>
#include <functional>
#include <string>

namespace egg::app {

// Exit codes (docs/architecture.md "The `egg` command").
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

using Action = std::function<int()>;

void registerSurfaceCommand(CLI::App& parent, Action& action);  // surface.cpp
void registerRunCommand(CLI::App& parent, Action& action);      // run.cpp
// The scene `egg run` takes without one: samples/great_court.json in the working folder, else
// beside the program (build/bin/egg in a source tree, bin/ with share/eggshell installed).
std::string defaultRunScene();
// A file of the source tree (relative to its root) beside the program: build/bin/egg in a source
// tree, bin/egg with share/eggshell installed. Empty when neither has it.
std::string besideProgram(const std::string& relative);
void registerInitCommand(CLI::App& parent, Action& action);  // init.cpp (egg init)
// scene_reference.cpp: `egg scene-reference` and `egg scene-schema`.
void registerSceneReferenceCommand(CLI::App& parent, Action& action);
// `egg bench <kind>`: bench is a group; each benchmark registers under it.
// (Helpers add their register functions here, one line each, and one call in cli.cpp.)
void registerGeodesicCommand(CLI::App& parent,
                             Action& action);  // geodesic_commands.cpp (egg geodesic)
void registerGeodesicBench(CLI::App& bench, Action& action);  // apps/bench/geodesic_bench.cpp
void registerSimBench(CLI::App& bench, Action& action);       // sim_commands.cpp (egg bench sim)
void registerFemBench(CLI::App& bench, Action& action);       // apps/bench/fem_bench.cpp
void registerDeploymentBench(CLI::App& bench,
                             Action& action);               // apps/bench/deployment_bench.cpp
void registerGridBench(CLI::App& bench, Action& action);    // grid_commands.cpp (egg bench grid)
void registerLayoutBench(CLI::App& bench, Action& action);  // layout_bench.cpp (egg bench layout)
void registerGeneralisedBench(CLI::App& bench,
                              Action& action);  // generalised_bench.cpp (egg bench generalised)
void registerPatchingBench(CLI::App& bench,
                           Action& action);  // patching_bench.cpp (egg bench patching)
void registerPipelineBench(CLI::App& bench,
                           Action& action);  // pipeline_bench.cpp (egg bench pipeline)
void registerStressCommand(CLI::App& parent, Action& action);  // sim_commands.cpp (egg stress)
void registerSweepCommand(CLI::App& parent, Action& action);   // sweep.cpp (egg sweep)

// A CLI11 check for a floating-point option: a finite number in [lo, hi]. CLI11's own Range and
// PositiveNumber let NaN through (every comparison with NaN is false).
inline CLI::Validator finiteRange(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double x = 0.0;
        if (!CLI::detail::lexical_cast(text, x))
          return "'" + text.substr(0, 40) + "' is not a number";
        if (!std::isfinite(x) || x < lo || x > hi)
          return "'" + text.substr(0, 40) + "' is not a finite number in [" +
                 CLI::detail::to_string(lo) + ", " + CLI::detail::to_string(hi) + "]";
        return "";
      },
      "FINITE in [" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]");
}

// Worker threads any command accepts (thousands of threads made std::thread abort).
constexpr int kMaxThreads = 256;

// Runs the program; returns the process exit code.
int runCli(int argc, char** argv);
// Parses a command line as runCli does and runs nothing: kExitOk when it names a command with
// valid options (or asks for --help / --version), kExitBadInput otherwise. Prints nothing (the
// command-line fuzz target, tests/fuzz).
int checkCommandLine(int argc, char** argv);

}  // namespace egg::app
