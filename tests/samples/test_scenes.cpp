// The scene files shipped in samples/: only docs/architecture.md "Scene file" keys (the parser
// rejects any other), a known sample with accepted parameters, the lamella sections of Table 3.3,
// and test scenes small enough for fast pipeline tests.
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace egg::samples {
namespace {

using nlohmann::json;
const std::filesystem::path kSamples = std::filesystem::path(EGG_SOURCE_DIR) / "samples";

json readScene(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  return json::parse(in);
}

void expectOnlyKeys(const json& object, const std::set<std::string>& allowed,
                    const std::string& where) {
  ASSERT_TRUE(object.is_object()) << where;
  for (auto it = object.begin(); it != object.end(); ++it) {
    EXPECT_TRUE(allowed.count(it.key())) << where << "." << it.key() << " is not a scene key";
  }
}

// docs/architecture.md "Scene file" (the full check, values included, is the scene parser's:
// tests/apps parses every shipped scene with it). Sections other than `surface` are optional.
void expectDesignKeys(const json& scene) {
  expectOnlyKeys(
      scene,
      {"name", "surface", "patching", "grid", "lamella", "simulation", "fabrication", "outputs"},
      "");
  const std::map<std::string, std::set<std::string>> sections{
      {"surface", {"sample", "params", "edge_length_m"}},
      {"patching",
       {"workflow", "eta_max", "slope_bounds", "max_patch_size_m", "block_grid", "patches"}},
      {"grid", {"members_per_family", "map_resolution", "alpha_bar", "min_planar_angle_rad"}},
      {"lamella", {"width_m", "thickness_m", "material"}},
      // block_grid, join_patches, stock_length_mm, splice_joint: beyond docs/architecture.md,
      // documented in docs/scene-reference.md (architectural lamellas are spliced from long stock,
      // Section 3.5; the Yas canopy's slots merge into slits that only a glued scarf can join, and
      // its joined run is too large).
      {"simulation", {"enabled", "gravity", "friction_mu", "notches", "join_patches"}},
      {"fabrication",
       {"enabled", "sheet_mm", "bolt_diameter_mm", "stock_length_mm", "splice_joint"}}};
  ASSERT_TRUE(scene.contains("surface"));
  for (const auto& [section, keys] : sections) {
    if (scene.contains(section)) expectOnlyKeys(scene[section], keys, section);
  }
  for (const auto& output : scene.value("outputs", json::array())) {
    EXPECT_TRUE(std::set<std::string>(
                    {"report", "plan", "cut_files", "stickers", "supports", "previews", "model"})
                    .count(output.get<std::string>()));
  }
  // Section 3.5.2: a lamella thinner than a fifth of its width behaves like a geodesic strip.
  EXPECT_LE(scene["lamella"]["thickness_m"].get<double>(),
            scene["lamella"]["width_m"].get<double>() / 5 + 1e-12);
}

TriMesh generateScene(const json& scene) {
  Params params;
  for (auto it = scene["surface"]["params"].begin(); it != scene["surface"]["params"].end(); ++it) {
    params[it.key()] = it.value().get<double>();
  }
  return generateSample(scene["surface"]["sample"].get<std::string>(), params,
                        scene["surface"]["edge_length_m"].get<double>());
}

TEST(SceneFiles, ArchitecturalScenesUseThePapersSections) {
  // Table 3.3: w x t = 50 x 5, 40 x 5 cm; Table 3.2: poplar plywood. The Great Court's 25 x 4 cm of
  // Table 3.3 collapses under its own weight in poplar (docs/samples.md, "The Great Court's
  // section"): the scene uses 40 x 8 cm, which stands.
  const std::map<std::string, std::pair<double, double>> sections{
      {"great_court", {0.40, 0.08}}, {"lilium", {0.50, 0.05}}, {"yas", {0.40, 0.05}}};
  for (const auto& [name, section] : sections) {
    SCOPED_TRACE(name);
    const json scene = readScene(kSamples / (name + ".json"));
    expectDesignKeys(scene);
    EXPECT_EQ(scene["name"], name);
    EXPECT_EQ(scene["surface"]["sample"], name);
    EXPECT_EQ(scene["lamella"]["width_m"].get<double>(), section.first);
    EXPECT_EQ(scene["lamella"]["thickness_m"].get<double>(), section.second);
    EXPECT_EQ(scene["lamella"]["material"], "poplar_plywood");
    EXPECT_EQ(scene["patching"]["eta_max"].get<double>(), 1.0015);  // Algorithm 1 / 2
    const TriMesh mesh = generateScene(scene);
    EXPECT_GT(mesh.n_vertices(), 4000u);
    EXPECT_LT(mesh.n_vertices(), 20000u);
  }
  // The default scene of `egg run`.
  EXPECT_EQ(readScene(kSamples / "great_court.json")["surface"]["edge_length_m"].get<double>(),
            1.0);
}

TEST(SceneFiles, TestScenesAreSmall) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSamples / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++scenes;
    const json scene = readScene(entry.path());
    expectDesignKeys(scene);
    const TriMesh mesh = generateScene(scene);
    EXPECT_GE(mesh.n_vertices(), 200u);
    EXPECT_LE(mesh.n_vertices(), 2500u);
  }
  EXPECT_GE(scenes, 3);
}

}  // namespace
}  // namespace egg::samples
