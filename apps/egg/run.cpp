#include "apps/egg/commands.hpp"
#include "apps/egg/progress.hpp"
#include "pipeline/pipeline.hpp"

#include <fmt/core.h>

#include <tbb/global_control.h>

#include <iostream>
#include <memory>
#include <optional>

namespace egg::app {
using namespace egg::pipeline;

namespace {
constexpr const char* kDefaultScene = "samples/great_court.json";
}  // namespace

std::string besideProgram(const std::string& relative) {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "";
  for (const auto& candidate : {exe.parent_path() / "../.." / relative,
                                exe.parent_path() / "../share/eggshell" / relative}) {
    if (std::filesystem::exists(candidate))
      return std::filesystem::weakly_canonical(candidate).string();
  }
  return "";
}

// `egg run` with no scene from any folder (issue 39): the default sample in the working folder,
// else beside the program. An explicit scene is always taken as given.
std::string defaultRunScene() {
  if (std::filesystem::exists(kDefaultScene)) return kDefaultScene;
  const std::string found = besideProgram(kDefaultScene);
  return found.empty() ? kDefaultScene : found;  // the error then names the path looked for
}

void registerRunCommand(CLI::App& parent, Action& action) {
  struct Args {
    std::string scene;  // empty: defaultScene()
    std::string out;
    bool json = false;
    bool quiet = false;
    int threads = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = parent.add_subcommand(
      "run",
      "Run the whole pipeline on a scene file and write report.json and the requested outputs.");
  cmd->add_option("scene", args->scene, "Scene file (default: samples/great_court.json)");
  cmd->add_option("--out,-o", args->out,
                  "Run folder (default: out/<scene name>); replaced whole when the run completes")
      ->check([](const std::string& v) {
        return v.empty() ? std::string("an empty path: leave --out out for out/<scene name>")
                         : std::string();
      });
  cmd->add_flag("--json", args->json, "Print the report as JSON on stdout");
  cmd->add_flag("--quiet,-q", args->quiet, "No progress on stderr");
  cmd->add_option("-j,--threads", args->threads,
                  "Worker threads (default: all cores); results do not depend on it")
      ->check(CLI::Range(1, kMaxThreads));
  cmd->callback([args, &action] {
    action = [args]() {
      const Scene scene = loadScene(args->scene.empty() ? defaultRunScene() : args->scene);
      std::optional<tbb::global_control> threadLimit;
      if (args->threads > 0)
        threadLimit.emplace(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(args->threads));
      PipelineOptions options;
      options.outDir = args->out.empty() ? std::filesystem::path("out") / scene.name
                                         : std::filesystem::path(args->out);
      ProgressLine bar(!args->quiet);  // drawn only on a terminal
      StageLog log(std::cerr);         // elsewhere: a line per stage (and every 15 s in one)
      if (bar.shown())
        options.progress = [&bar](const std::string& stage, double fraction) {
          bar.update(fraction, stage);
        };
      else if (!args->quiet)
        options.progress = [&log](const std::string& stage, double fraction) {
          log.update(fraction, stage);
        };
      const PipelineResult result = runPipeline(scene, options);
      bar.finish();
      if (result.nothingRequested) {
        std::cout << fmt::format(
            "egg run: {}: the scene asks for no outputs (\"outputs\": []): nothing to do\n",
            scene.name);
        return kExitOk;
      }
      // The summary (acceptance.hpp) ends with "passed" only when the run has no failure.
      if (args->json) {
        std::cout << result.report.dump(2) << "\n";
        std::cerr << runSummary(result.report, result.outDir, result.seconds);
      } else {
        std::cout << runSummary(result.report, result.outDir, result.seconds);
      }
      return result.failures.empty() ? kExitOk : kExitFailure;
    };
  });
}

}  // namespace egg::app
