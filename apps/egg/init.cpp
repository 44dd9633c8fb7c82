// `egg init MESH|SAMPLE [--out SCENE]`: a starting scene for one's own surface (issue 39),
// pipeline/scene_template.hpp.
#include "apps/egg/commands.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/scene_template.hpp"

#include <fmt/core.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace egg::app {

void registerInitCommand(CLI::App& parent, Action& action) {
  struct Args {
    std::string surface;
    std::string out;
    double scaleToM = 0.0;  // 0: not given
    bool force = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = parent.add_subcommand(
      "init",
      "Write a starting scene for a mesh file or a sample: every key at its default with its unit "
      "and meaning, the lamella section and patch size suggested from the surface, and the "
      "\"$schema\" editors check it with.");
  cmd->add_option("surface", args->surface, "Mesh file (OBJ, STL, PLY, OFF, glTF) or sample name")
      ->required();
  cmd->add_option("--out,-o", args->out, "Scene file to write (default: print it)")
      ->check([](const std::string& v) {
        return v.empty() ? std::string("an empty path: leave --out out to print the scene")
                         : std::string();
      });
  cmd->add_option("--scale-to-m", args->scaleToM,
                  "A mesh file's coordinates times this are metres (0.001 for millimetres)")
      ->check(finiteRange(1e-9, 1e6));
  cmd->add_flag("--force", args->force, "Replace an existing --out file");
  cmd->callback([args, &action] {
    action = [args]() {
      const std::filesystem::path out(args->out);
      if (!out.empty() && !args->force &&
          std::filesystem::symlink_status(out).type() != std::filesystem::file_type::not_found)
        throw InvalidInput("--out " + out.string() +
                           ": exists; egg init does not replace a file (--force does)");
      pipeline::StartingSceneOptions options;
      options.surface = args->surface;
      if (args->scaleToM > 0.0) options.scaleToM = args->scaleToM;
      options.sceneFolder = out.empty() ? std::filesystem::current_path()
                                        : std::filesystem::absolute(out).parent_path();
      // The schema beside the program: relative to the scene where the two share a top folder
      // (a project tree that moves together), else by its absolute path.
      if (const std::string schema = besideProgram("docs/scene.schema.json"); !schema.empty()) {
        const std::filesystem::path absolute(schema);
        const auto top = [](const std::filesystem::path& p) {
          auto it = p.begin();
          return it == p.end() || ++it == p.end() ? std::filesystem::path() : *it;
        };
        const std::filesystem::path relative =
            std::filesystem::relative(absolute, options.sceneFolder);
        options.schema = relative.empty() || top(absolute) != top(options.sceneFolder)
                             ? schema
                             : relative.string();
      }
      const pipeline::StartingScene scene = pipeline::startingScene(options);
      for (const auto& warning : scene.warnings)
        std::cerr << "egg init: warning: " << warning << "\n";
      const std::string text = scene.scene.dump(2) + "\n";
      if (out.empty()) {
        std::cout << text;
      } else {
        writeFileAtomically(out, text);
        std::cerr << fmt::format(
            "egg init: wrote {} (span {:.1f} m, lamella {:.0f} x {:.0f} mm); run it with: egg run "
            "{}\n",
            out.string(), scene.measures.spanM, scene.widthM * 1000.0, scene.thicknessM * 1000.0,
            out.string());
      }
      return kExitOk;
    };
  });
}

}  // namespace egg::app
