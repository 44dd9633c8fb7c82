// The scene's JSON Schema and `egg init`'s starting scene (issue 39): the schema is generated from
// the parser's field lists, so a scene the parser takes the schema takes, and a typo both refuse.
#include "core/errors.hpp"
#include "core/io/mesh_io.hpp"
#include "pipeline/scene.hpp"
#include "pipeline/scene_fields.hpp"
#include "pipeline/scene_template.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string schemaTestText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using Validation = egg::test::ToolRun;

// Validates each file against the schema with python3-jsonschema (Draft 2020-12), an
// implementation independent of ours; prints "FILE: ok" or "FILE: error: ...".
Validation validateWithPython(const fs::path& schema, const std::vector<fs::path>& files) {
  const fs::path script =
      fs::temp_directory_path() / ("egg_schema_check_" + std::to_string(::getpid()) + ".py");
  std::ofstream(script) << R"(import json, sys
import jsonschema
schema = json.load(open(sys.argv[1]))
jsonschema.Draft202012Validator.check_schema(schema)
v = jsonschema.Draft202012Validator(schema)
for f in sys.argv[2:]:
    errors = sorted(v.iter_errors(json.load(open(f))), key=lambda e: list(e.path))
    print(f + ": " + ("ok" if not errors else "error: " + errors[0].message))
)";
  std::string command = "/usr/bin/python3 " + script.string() + " " + schema.string();
  for (const auto& f : files) command += " " + f.string();
  const Validation out = egg::test::runTool(command);
  fs::remove(script);
  return out;
}

bool havePythonJsonschema() {
  return std::system("/usr/bin/python3 -c 'import jsonschema' >/dev/null 2>&1") == 0;
}

class SceneSchema : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("egg_scene_schema_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "schema.json") << sceneJsonSchema().dump(2);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  fs::path dir;
};

TEST_F(SceneSchema, TheCommittedSchemaIsTheGeneratedOne) {
  const std::string committed =
      schemaTestText(fs::path(EGG_SOURCE_DIR) / "docs" / "scene.schema.json");
  EXPECT_EQ(committed, sceneJsonSchema().dump(2) + "\n")
      << "regenerate it: egg scene-schema --out docs/scene.schema.json";
}

TEST_F(SceneSchema, EveryKeyOfEverySectionIsInTheSchemaWithItsDefault) {
  const json schema = sceneJsonSchema();
  EXPECT_FALSE(schema["additionalProperties"].get<bool>());
  for (const SceneSection& section : sceneSections()) {
    const json& object = section.key.empty() ? schema : schema["properties"][section.key];
    EXPECT_FALSE(object["additionalProperties"].get<bool>()) << section.key;
    for (const SceneField& f : section.fields)
      EXPECT_TRUE(object["properties"].contains(f.key)) << section.key << "." << f.key;
  }
  EXPECT_EQ(schema["properties"]["lamella"]["properties"]["width_m"]["default"], 0.25);
  EXPECT_EQ(schema["properties"]["simulation"]["properties"]["friction_mu"]["maximum"], 2.0);
}

TEST_F(SceneSchema, PythonJsonschemaTakesEverySampleSceneAndRefusesTyposAndRanges) {
  if (!havePythonJsonschema()) GTEST_SKIP() << "python3-jsonschema is not installed";
  std::vector<fs::path> scenes;
  for (const auto& folder :
       {fs::path(EGG_SOURCE_DIR) / "samples", fs::path(EGG_SOURCE_DIR) / "samples" / "scenes"})
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  ASSERT_GE(scenes.size(), 8u);
  const Validation samples = validateWithPython(dir / "schema.json", scenes);
  ASSERT_EQ(samples.status, 0) << samples.output;
  for (const auto& scene : scenes)
    EXPECT_NE(samples.output.find(scene.string() + ": ok"), std::string::npos) << samples.output;

  const auto typo =
      write("typo.json", R"({"surface": {"sample": "bump"}, "lamella": {"widht_m": 0.1}})");
  const auto range =
      write("range.json", R"({"surface": {"sample": "bump"}, "simulation": {"friction_mu": 3}})");
  const auto both = write("both.json", R"({"surface": {"sample": "bump", "file": "a.obj"}})");
  const auto comment =
      write("comment.json",
            R"({"$comment": ["a", "b"], "surface": {"$comment": "c", "sample": "bump"}})");
  const Validation bad = validateWithPython(dir / "schema.json", {typo, range, both, comment});
  ASSERT_EQ(bad.status, 0) << bad.output;
  EXPECT_NE(bad.output.find(typo.string() + ": error: Additional properties"), std::string::npos)
      << bad.output;
  EXPECT_NE(bad.output.find(range.string() + ": error: 3 is greater than the maximum of 2"),
            std::string::npos)
      << bad.output;
  EXPECT_NE(bad.output.find(both.string() + ": error"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find(comment.string() + ": ok"), std::string::npos) << bad.output;
  // The parser agrees on each.
  EXPECT_THROW(loadScene(typo), InvalidInput);
  EXPECT_THROW(loadScene(range), InvalidInput);
  EXPECT_THROW(loadScene(both), InvalidInput);
  EXPECT_NO_THROW(loadScene(comment));
}

TEST_F(SceneSchema, TheParserTakesCommentsAndASchemaNameButNothingElseOfThatSpelling) {
  EXPECT_NO_THROW(parseSceneText(
      R"({"$schema": "scene.schema.json", "$comment": "x", "surface": {"sample": "bump"}})", "a"));
  EXPECT_THROW(parseSceneText(R"({"$schema": 3, "surface": {"sample": "bump"}})", "a"),
               InvalidInput);
  EXPECT_THROW(parseSceneText(R"({"surface": {"sample": "bump", "$comment": 3}})", "a"),
               InvalidInput);
  EXPECT_THROW(parseSceneText(R"({"surface": {"sample": "bump", "$schema": "x"}})", "a"),
               InvalidInput);
}

// sigma = E kappa t / 2 at half the strength: t <= f_m / (E kappa), rounded down to stock.
TEST(StartingScene, TheSuggestedThicknessIsTheThickestStockAtHalfTheStrength) {
  // f_m / (E kappa) = 30e6 / (8e9 * 0.1) = 37.5 mm -> 35 mm.
  EXPECT_DOUBLE_EQ(suggestedThicknessM(0.1, 8e9, 30e6), 0.035);
  // Exactly on a stock thickness: 24e6 / (8e9 * 0.1) = 30 mm.
  EXPECT_DOUBLE_EQ(suggestedThicknessM(0.1, 8e9, 24e6), 0.030);
  EXPECT_DOUBLE_EQ(suggestedThicknessM(0.0, 8e9, 30e6), 0.100);    // flat: the thickest stocked
  EXPECT_DOUBLE_EQ(suggestedThicknessM(100.0, 8e9, 30e6), 0.004);  // the thinnest, never zero
  EXPECT_DOUBLE_EQ(suggestedMaxPatchSizeM(121.7), 85.0);
  EXPECT_DOUBLE_EQ(suggestedMaxPatchSizeM(10.0), 40.0);
  EXPECT_DOUBLE_EQ(suggestedMaxPatchSizeM(300.0), 100.0);
}

TEST_F(SceneSchema, TheStartingSceneOfASampleParsesWithEveryKeyAndTheSuggestions) {
  StartingSceneOptions options;
  options.surface = "bump";
  options.schema = "scene.schema.json";
  const StartingScene start = startingScene(options);
  const Scene scene = parseSceneText(start.scene.dump(), dir / "bump.json");
  EXPECT_EQ(scene.surface.sample, "bump");
  EXPECT_EQ(scene.name, "bump");
  EXPECT_DOUBLE_EQ(scene.lamella.thicknessM, start.thicknessM);
  EXPECT_DOUBLE_EQ(scene.lamella.widthM, start.widthM);
  EXPECT_GT(start.measures.bendingCurvaturePerM, 0.0);
  EXPECT_NEAR(start.measures.spanM, 10.0, 0.5);  // the bump sample is 10 m across
  EXPECT_EQ(start.scene["$schema"], "scene.schema.json");
  // Every key is commented in its section.
  for (const SceneSection& section : sceneSections()) {
    const auto& comments =
        section.key.empty() ? start.scene["$comment"] : start.scene[section.key]["$comment"];
    const std::string all = comments.dump();
    for (const SceneField& f : section.fields)
      EXPECT_NE(all.find(f.key + ": "), std::string::npos) << section.key << "." << f.key;
  }
  // The schema takes it too.
  if (havePythonJsonschema()) {
    const Validation v =
        validateWithPython(dir / "schema.json", {write("start.json", start.scene.dump(2))});
    EXPECT_NE(v.output.find("start.json: ok"), std::string::npos) << v.output;
  }
}

TEST_F(SceneSchema, AMillimetreMeshGetsTheScaleHintAndWithItARelativePath) {
  // A 10 m bump modelled in millimetres.
  TriMesh mesh = samples::generateSample("bump", {}, 0.5);
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * 1000.0);
  fs::create_directories(dir / "meshes");
  writeMeshFile(dir / "meshes" / "roof.obj", mesh);
  StartingSceneOptions options;
  options.surface = (dir / "meshes" / "roof.obj").string();
  options.sceneFolder = dir / "scenes";
  try {
    startingScene(options);
    FAIL() << "a 10 km surface passed";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("scale_to_m"), std::string::npos) << e.what();
  }
  options.scaleToM = 0.001;
  const StartingScene start = startingScene(options);
  EXPECT_EQ(start.scene["surface"]["file"], "../meshes/roof.obj");
  EXPECT_EQ(start.scene["surface"]["scale_to_m"], 0.001);
  EXPECT_EQ(start.scene["name"], "roof");
  EXPECT_NEAR(start.measures.spanM, 10.0, 0.5);
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "roof.json") << start.scene.dump(2);
  const Scene scene = loadScene(dir / "scenes" / "roof.json");
  EXPECT_EQ(fs::weakly_canonical(scene.surface.file),
            fs::weakly_canonical(dir / "meshes" / "roof.obj"));
}

TEST(StartingScene, ASceneFileOrNothingIsRefused) {
  StartingSceneOptions options;
  EXPECT_THROW(startingScene(options), InvalidInput);
  options.surface = "samples/great_court.json";
  EXPECT_THROW(startingScene(options), InvalidInput);
  options.surface = "no_such_mesh.obj";
  EXPECT_THROW(startingScene(options), Error);
  options.surface = "bump";
  options.scaleToM = 0.001;
  EXPECT_THROW(startingScene(options), InvalidInput);
}

}  // namespace
}  // namespace egg::pipeline
