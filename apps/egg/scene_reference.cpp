// `egg scene-reference [--out FILE]`: the scene file reference (docs/scene-reference.md), and
// `egg scene-schema [--out FILE]`: its JSON Schema (docs/scene.schema.json), both generated from
// the field lists the parser reads.
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

  auto schemaOut = std::make_shared<std::string>();
  CLI::App* schema = parent.add_subcommand(
      "scene-schema",
      "Print the scene file's JSON Schema (draft 2020-12): editors complete and check a scene "
      "whose \"$schema\" names it (docs/scene.schema.json).");
  schema->add_option("--out,-o", *schemaOut, "write it to this file instead of stdout");
  schema->callback([schemaOut, &action] {
    action = [schemaOut] {
      const std::string text = pipeline::sceneJsonSchema().dump(2) + "\n";
      if (schemaOut->empty())
        std::cout << text;
      else
        writeFileAtomically(*schemaOut, text);
      return kExitOk;
    };
  });
}

}  // namespace egg::app
