// `egg scene-reference [--out FILE]`: the scene file reference (docs/scene-reference.md), generated
// from the field lists the parser reads.
#include "apps/egg/commands.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/scene.hpp"

#include <iostream>
#include <memory>

namespace egg::app {

void registerSceneReferenceCommand(CLI::App& parent, Action& action) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = parent.add_subcommand("scene-reference",
                                        "Print the scene file reference (Markdown): every key with "
                                        "its type, range, default and meaning.");
  cmd->add_option("--out,-o", *out, "write it to this file instead of stdout");
  cmd->callback([out, &action] {
    action = [out] {
      const std::string text = pipeline::sceneReferenceMarkdown();
      if (out->empty())
        std::cout << text;
      else
        writeFileAtomically(*out, text);
      return kExitOk;
    };
  });
}

}  // namespace egg::app
