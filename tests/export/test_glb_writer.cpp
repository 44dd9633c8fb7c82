#include "export/glb_writer.hpp"

#include "core/io/atomic_file.hpp"
#include "tests/export/node_check.hpp"
#include "tests/export/synthetic_model.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <cstring>

namespace egg::exporter {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("egg_test_export_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

nlohmann::json jsonChunk(const std::string& glb) {
  uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, length));
}

TEST(ExportGlb, HeaderChunksAndNamedNodes) {
  const StructureModel model = testing::syntheticModel();
  const std::string glb = glbBytes(model);
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  uint32_t version = 0, total = 0;
  std::memcpy(&version, glb.data() + 4, 4);
  std::memcpy(&total, glb.data() + 8, 4);
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(total, glb.size());
  const auto gltf = jsonChunk(glb);
  std::map<std::string, nlohmann::json> nodes;
  for (const auto& n : gltf["nodes"]) nodes[n.value("name", "")] = n;
  // One node per patch, per family and per lamella, with the ids in extras.
  for (const char* name : {"P0", "P1", "P0-U", "P0-V", "P1-U", "P1-V", "surface", "supports",
                           "P0-bolts", "P1-bolts", "S001", "S002"})
    EXPECT_TRUE(nodes.count(name)) << name;
  for (const auto& l : model.lamellas) {
    ASSERT_TRUE(nodes.count(l.id)) << l.id;
    const auto& extras = nodes[l.id]["extras"];
    EXPECT_EQ(extras["id"], l.id);
    EXPECT_EQ(extras["patch"], l.patch);
    EXPECT_DOUBLE_EQ(extras["length_m"].get<double>(), l.lengthM);
    EXPECT_NEAR(extras["max_deviation_m"].get<double>(), 1e-3 * (l.index + 1), 1e-12);
  }
  EXPECT_EQ(nodes["P1-bolts"]["extras"]["count"], 6);
  // The root turns site z up into glTF y up.
  const auto& root = gltf["nodes"][gltf["scenes"][0]["nodes"][0].get<int>()];
  EXPECT_NEAR(root["rotation"][0].get<double>(), -std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(root["extras"]["deviation_colour_scale_m"][1].get<double>(), 3e-3, 1e-12);
  // A lamella's POSITION bounds: the ribbon of P1-U2 (y = 1 +- w/2).
  const auto& mesh = gltf["meshes"][nodes["P1-U2"]["mesh"].get<int>()];
  const auto& position =
      gltf["accessors"][mesh["primitives"][0]["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(position["count"], 8 * 11 + 8);
  EXPECT_NEAR(position["max"][1].get<double>(), 1.05, 1e-3);
  EXPECT_NEAR(position["min"][0].get<double>(), 3.0, 2e-3);
}

TEST(ExportGlb, PassesTheKhronosValidatorAndAWrongFileFails) {
  if (const std::string why = testing::nodeChecksUnavailable(); !why.empty()) GTEST_SKIP() << why;
  const StructureModel model = testing::syntheticModel();
  const fs::path file = scratch("model.glb");
  writeFileAtomically(file, glbBytes(model));
  const auto ok = testing::runNodeScript("check_glb.mjs", file.string() + " 10");
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  EXPECT_NE(ok.output.find(" 0 errors"), std::string::npos) << ok.output;
  // The check counts lamella nodes: a wrong expectation fails.
  EXPECT_EQ(testing::runNodeScript("check_glb.mjs", file.string() + " 11").exitCode, 1);
  // A broken file fails the validator: the binary chunk cut short.
  std::string broken = glbBytes(model);
  broken.resize(broken.size() - 64);
  const fs::path bad = scratch("broken.glb");
  writeFileAtomically(bad, broken);
  const auto fails = testing::runNodeScript("check_glb.mjs", bad.string());
  EXPECT_EQ(fails.exitCode, 1) << fails.output;
  const auto supports = scratch("supports.glb");
  writeFileAtomically(supports, supportsGlbBytes(model));
  const auto s = testing::runNodeScript("check_glb.mjs", supports.string() + " 0");
  EXPECT_EQ(s.exitCode, 0) << s.output;
  fs::remove_all(file.parent_path());
}

}  // namespace
}  // namespace egg::exporter
