#include "apps/egg/commands.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

namespace egg::app {

namespace {

constexpr const char* kAbout =
    "egg — elastic geodesic gridshells: from a design surface to a deployable grid of straight "
    "lamellas (patches, planar grids, simulation, cut files).";

// Every command and its options (runCli and checkCommandLine parse the same line).
void buildCli(CLI::App& app, Action& action) {
  app.require_subcommand(1);
  app.set_version_flag("--version", "eggshell 0.1.0");

  registerRunCommand(app, action);
  registerInitCommand(app, action);
  registerSceneReferenceCommand(app, action);
  registerSurfaceCommand(app, action);
  registerGeodesicCommand(app, action);
  registerStressCommand(app, action);
  registerSweepCommand(app, action);
  CLI::App* bench = app.add_subcommand("bench",
                                       "Benchmarks: error against run time, with a reference "
                                       "measured in the same run (CSV + table).");
  bench->require_subcommand(1);
  registerGeodesicBench(*bench, action);
  registerGridBench(*bench, action);
  registerLayoutBench(*bench, action);
  registerGeneralisedBench(*bench, action);
  registerPatchingBench(*bench, action);
  registerPipelineBench(*bench, action);
  registerSimBench(*bench, action);
  registerFemBench(*bench, action);
  registerDeploymentBench(*bench, action);
}

// Parses the line into `action`. The exit code when the line itself ends the run (--help and
// --version: 0; a parse error or no command: bad input), with CLI11's text printed when `print`;
// nothing when a command is to run.
std::optional<int> parseLine(CLI::App& app, const Action& action, int argc, char** argv,
                             bool print) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = print ? app.exit(e) : e.get_exit_code();
    return code == 0 ? kExitOk : kExitBadInput;
  }
  if (!action) return kExitBadInput;
  return std::nullopt;
}

}  // namespace

int checkCommandLine(int argc, char** argv) {
  CLI::App app{kAbout};
  Action action;
  buildCli(app, action);
  try {
    if (const auto code = parseLine(app, action, argc, argv, false)) return *code;
  } catch (const Error&) {
    return kExitBadInput;  // an option callback's own check
  }
  return kExitOk;
}

int runCli(int argc, char** argv) {
  // Past a file-size limit (ulimit -f, RLIMIT_FSIZE) the kernel kills the writer with SIGXFSZ, so
  // the run ended without a word and left its staging folder (issue 40). Ignored, the write fails
  // with EFBIG instead, and every checked write reports it naming the file: exit 1, the run
  // folder as it was.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{kAbout};
  Action action;
  buildCli(app, action);
  try {
    if (const auto code = parseLine(app, action, argc, argv, true)) return *code;
  } catch (const Error& e) {
    std::cerr << "egg: invalid input: " << e.what() << "\n";  // an option callback's own check
    return kExitBadInput;
  }
  // With --json a script reads stdout: a failure is a JSON object there too (issue 39), beside
  // the message on stderr.
  bool json = false;
  for (int i = 1; i < argc; ++i) json = json || std::string(argv[i]) == "--json";
  // file and field: where the library knew them (a scene key, a file that cannot be read), else
  // null.
  const auto fail = [json](const char* kind, const std::string& prefix, const std::exception& e,
                           int code) {
    const std::string what = e.what();
    std::cerr << "egg: " << prefix << what << "\n";
    if (json) {
      const auto* error = dynamic_cast<const Error*>(&e);
      const auto known = [](const std::string& s) {
        return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s);
      };
      std::cout << nlohmann::json{{"error",
                                   {{"kind", kind},
                                    {"message", what},
                                    {"file", known(error ? error->file() : "")},
                                    {"field", known(error ? error->field() : "")},
                                    {"exit_code", code}}}}
                       .dump(2)
                << "\n"
                << std::flush;
    }
    return code;
  };
  try {
    const int code = action();
    // A lost standard output (a full disk, /dev/full, a pipe closed early) is a failed run, never
    // success: the JSON or table a script reads from it is gone (issue 40).
    std::cout.flush();
    if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
      std::cerr << "egg: cannot write to standard output\n";
      return code == kExitOk ? kExitFailure : code;
    }
    return code;
  } catch (const InvalidInput& e) {
    return fail("invalid_input", "invalid input: ", e, kExitBadInput);
  } catch (const WriteError& e) {
    return fail("write_error", "cannot write output: ", e, kExitFailure);
  } catch (const IoError& e) {
    return fail("io_error", "", e, kExitBadInput);
  } catch (const InfeasiblePatch& e) {
    return fail("infeasible_patch", "infeasible patch: ", e, kExitFailure);
  } catch (const SolverFailure& e) {
    return fail("solver_failure", "solver failure: ", e, kExitFailure);
  } catch (const std::exception& e) {
    return fail("internal_error", "internal error: ", e, kExitFailure);
  }
}

}  // namespace egg::app
