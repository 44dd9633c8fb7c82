#include "pipeline/scene.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/json_check.hpp"
#include "pipeline/scene_fields.hpp"
#include "pipeline/stages.hpp"

#include <algorithm>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// Deepest nesting of objects and arrays a scene file may have (the real ones nest 4 levels).
constexpr int kMaxSceneDepth = 64;
// Largest scene file read (a layout of 1000 patches is a few MB).
constexpr std::size_t kMaxSceneBytes = 64u << 20;

void readSection(const SceneSection& section, JsonSection& json, Scene& scene) {
  for (const SceneField& f : section.fields) f.read(json, scene);
  if (section.check) section.check(json, scene);
  json.rejectUnknownKeys();
}

}  // namespace

const char* toString(SupportChoice choice) {
  switch (choice) {
    case SupportChoice::Auto: return "auto";
    case SupportChoice::Anchors: return "anchors";
    case SupportChoice::DesignBoundary: return "design_boundary";
  }
  return "unknown";
}

bool Scene::wants(const std::string& output) const {
  return std::find(outputs.begin(), outputs.end(), output) != outputs.end();
}

bool layoutIsGiven(const Scene& scene) {
  return !scene.patching.quads.empty() && !scene.patching.workflowGiven;
}

EggOptions Scene::eggOptions() const {
  EggOptions options = design();
  options.members.lamellaWidthM = lamella.widthM;
  // Splitting replaces smoothing in the workflows (Section 3.1: smoothing alters the design).
  options.uniqueness.smooth = patching.smoothing.value_or(layoutIsGiven(*this));
  return options;
}

fabrication::FabricationOptions Scene::fabricationOptions() const {
  fabrication::FabricationOptions options = fabrication.options;
  options.lamellaWidthMm = lamella.widthM * 1000.0;
  options.lamellaThicknessMm = lamella.thicknessM * 1000.0;
  options.material = lamella.material;
  return options;
}

double defaultSampleEdgeLength(const std::string& sample) {
  // The architectural scenes are tens of metres across; the test surfaces a few metres. These
  // give meshes of a few thousand to ~15k vertices, enough for the 0.15 % eta test (Section 2.3.3).
  if (sample == "great_court" || sample == "lilium") return 1.0;
  if (sample == "yas") return 2.0;
  return 0.25;
}

Scene parseScene(const json& document, const std::filesystem::path& origin) {
  Scene scene;
  scene.path = origin;
  const auto& sections = sceneSections();
  JsonSection top(document, "", origin.string());
  for (const SceneField& f : sections.front().fields) f.read(top, scene);
  // "$schema" names the schema an editor checks the file with (`egg init` writes it); not read.
  if (top.has("$schema") && !top.raw("$schema").is_string())
    top.fail("$schema", "must be the path or URL of the scene's JSON Schema, a string");
  if (!top.has("surface"))
    top.fail("surface", "is required ({\"sample\": ...} or {\"file\": ...})");
  for (size_t i = 1; i < sections.size(); ++i) {
    JsonSection section = top.child(sections[i].key);
    readSection(sections[i], section, scene);
  }
  top.rejectUnknownKeys();
  return scene;
}

Scene parseSceneText(const std::string& text, const std::filesystem::path& origin) {
  const std::string where = abbreviate(origin.string());
  // One linear pass first: nesting, numbers that overflow a double, valid JSON, named by position.
  const JsonCheck check = checkJsonText(text, kMaxSceneDepth);
  if (!check.ok)
    throw InvalidInput(where + ": " + (check.path.empty() ? "" : check.path + ": ") + check.problem,
                       origin.string(), check.path);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {
    throw InvalidInput(where + ": not valid JSON: " + abbreviate(e.what(), 400), origin.string());
  }
  return parseScene(document, origin);
}

std::filesystem::path benchSceneFile(const std::string& name) {
  const bool file = name.size() > 5 && name.substr(name.size() - 5) == ".json";
  return file ? std::filesystem::path(name) : std::filesystem::path("samples") / (name + ".json");
}

Scene loadScene(const std::filesystem::path& path) {
  // A folder, a FIFO or a device is refused before any read (a FIFO would block forever).
  return parseSceneText(readRegularFile(path, kMaxSceneBytes, "scene file"), path);
}

json sceneToJson(const Scene& scene) {
  json echo = json::object();
  for (const SceneSection& section : sceneSections()) {
    json& target = section.key.empty() ? echo : echo[section.key];
    if (!section.key.empty()) target = json::object();
    for (const SceneField& f : section.fields)
      if (std::optional<json> value = f.write(scene)) target[f.key] = std::move(*value);
  }
  echo["path"] = scene.path.string();
  return echo;
}

std::string sceneReferenceMarkdown() {
  const Scene defaults;
  std::string out =
      "# Scene file reference\n\n"
      "Generated from `pipeline/scene_fields.cpp` by `egg scene-reference`; a test keeps this file "
      "equal to it.\n"
      "A scene is a JSON object; every key but `surface` has a default, and an unknown key is an "
      "error.\n"
      "Lengths are metres unless the key ends in `_mm`; angles are radians.\n";
  for (const SceneSection& section : sceneSections()) {
    out += "\n## " + (section.key.empty() ? std::string("Top level") : "`" + section.key + "`") +
           "\n\n" + section.doc + "\n\n";
    out += "| key | value | default | what it does |\n|---|---|---|---|\n";
    for (const SceneField& f : section.fields) {
      // No default value: required, unset (its doc names what is derived instead) or empty.
      const std::optional<json> value = f.write(defaults);
      const bool none = !value ||
                        (value->is_string() && value->get_ref<const std::string&>().empty()) ||
                        ((value->is_array() || value->is_object()) && value->empty());
      out += "| `" + f.key + "` | " + f.type + " | " +
             (none ? std::string("none") : "`" + value->dump() + "`") + " | " + f.doc + " |\n";
    }
  }
  return out;
}

json sceneJsonSchema() {
  const Scene defaults;
  const json text = {{"type", "string"}};
  const json lines = {{"type", "array"}, {"items", text}};
  const json comment = {{"description", "a note to the reader, not read"},
                        {"anyOf", json::array({text, lines})}};
  // One object per section: its keys, their defaults and docs, and nothing else (the parser
  // refuses unknown keys too).
  const auto object = [&](const SceneSection& section) {
    json properties = {{"$comment", comment}};
    for (const SceneField& f : section.fields) {
      if (f.schema.is_null())
        throw std::logic_error("scene field " + section.key + "." + f.key + " has no schema");
      json property = f.schema;
      property["description"] = f.doc + " (" + f.type + ")";
      if (const std::optional<json> value = f.write(defaults); value && !value->is_null())
        property["default"] = *value;
      properties[f.key] = std::move(property);
    }
    return json{{"type", "object"},
                {"description", section.doc},
                {"properties", std::move(properties)},
                {"additionalProperties", false}};
  };
  const auto& sections = sceneSections();
  json schema = object(sections.front());
  schema["properties"]["$schema"] = {{"type", "string"},
                                     {"description", "the JSON Schema this file is checked with"}};
  for (size_t i = 1; i < sections.size(); ++i)
    schema["properties"][sections[i].key] = object(sections[i]);
  schema["required"] = json::array({"surface"});
  schema["properties"]["surface"]["oneOf"] = {{{"required", json::array({"sample"})}},
                                              {{"required", json::array({"file"})}}};
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  schema["title"] = "eggshell scene";
  schema["description"] =
      "A scene of `egg run` (docs/scene-reference.md): lengths in metres unless the key ends in "
      "_mm, angles in radians. Generated by `egg scene-schema`.";
  return schema;
}

}  // namespace egg::pipeline
