#include "apps/egg/commands.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <iostream>

namespace egg::app {

int runCli(int argc, char** argv) {
  CLI::App app{
      "egg — elastic geodesic gridshells: from a design surface to a deployable grid of straight "
      "lamellas (patches, planar grids, simulation, cut files)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "eggshell 0.1.0");

  Action action;
  registerRunCommand(app, action);
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
  registerPatchingBench(*bench, action);
  registerPipelineBench(*bench, action);
  registerSimBench(*bench, action);
  registerFemBench(*bench, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  if (!action) return kExitBadInput;
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
    std::cerr << "egg: invalid input: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const WriteError& e) {
    std::cerr << "egg: cannot write output: " << e.what() << "\n";
    return kExitFailure;
  } catch (const IoError& e) {
    std::cerr << "egg: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InfeasiblePatch& e) {
    std::cerr << "egg: infeasible patch: " << e.what() << "\n";
    return kExitFailure;
  } catch (const SolverFailure& e) {
    std::cerr << "egg: solver failure: " << e.what() << "\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "egg: internal error: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace egg::app
