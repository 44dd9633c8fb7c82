// The "model" output on a 2 x 2 patch layout (issue 38): the files appear in the run folder and in
// report.json, the GLB passes the Khronos validator and the 3dm reads back through rhino3dm with a
// layer per patch and family and an object per lamella.
#include "pipeline/model_stage.hpp"

#include "pipeline/pipeline.hpp"
#include "tests/export/node_check.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

Scene twoByTwoGridScene() {
  // The simulation off: the lamellas follow the traced grid (a fast multi-patch run).
  return parseScene(nlohmann::json::parse(R"({
    "name": "bump_2x2_model",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1.0, "sigma": 1.5}, "edge_length_m": 0.4},
    "patching": {"patches": [[[-3,-3,0],[0,-3,0],[0,0,1],[-3,0,0]], [[0,-3,0],[3,-3,0],[3,0,0],[0,0,1]],
                             [[-3,0,0],[0,0,1],[0,3,0],[-3,3,0]], [[0,0,1],[3,0,0],[3,3,0],[0,3,0]]]},
    "grid": {"map_resolution": 30, "members_per_family": 4},
    "lamella": {"width_m": 0.05, "thickness_m": 0.005},
    "simulation": {"enabled": false},
    "outputs": ["report", "model"]})"),
                    "/virtual/bump_2x2_model.json");
}

TEST(ModelStage, TwoByTwoGridWritesAValidModelOfEveryLamella) {
  const fs::path out = fs::temp_directory_path() / ("egg_model_2x2_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(twoByTwoGridScene(), options);
  const auto& model = result.report["model"];
  ASSERT_TRUE(model.value("ran", false)) << model.dump(1);
  EXPECT_EQ(model["centreline_source"], "grid (simulation off)");
  EXPECT_EQ(model["lamellas"], 4 * 8);  // 4 patches, 4 members per family
  EXPECT_EQ(model["bolts"], 4 * 16);
  // On the grid every lamella lies on the design surface (its contact side is the traced
  // geodesic): the deviation is the mesh's own distance, nothing.
  EXPECT_LT(model["max_deviation_m"].get<double>(), 1e-9);
  std::set<std::string> files;
  for (const auto& f : model["files"]) {
    files.insert(f["path"].get<std::string>());
    EXPECT_EQ(fs::file_size(out / f["path"].get<std::string>()), f["bytes"].get<size_t>());
  }
  for (const char* f : {"model.glb", "model.obj"}) EXPECT_TRUE(files.count(f)) << f;
  EXPECT_EQ(files.count("supports.stl"), model["supports"].get<int>() > 0 ? 1u : 0u);
  // Lamella groups by id in the OBJ.
  std::ifstream obj(out / "model.obj");
  std::stringstream text;
  text << obj.rdbuf();
  for (const char* id : {"\ng P0-U0\n", "\ng P3-V3\n", "\ng P2-bolts\n"})
    EXPECT_NE(text.str().find(id), std::string::npos) << id;

  if (const std::string why = exporter::testing::nodeChecksUnavailable(); !why.empty()) {
    EXPECT_TRUE(model.contains("rhino_skipped"));
    fs::remove_all(out);
    GTEST_SKIP() << why;
  }
  const auto glb =
      exporter::testing::runNodeScript("check_glb.mjs", (out / "model.glb").string() + " 32");
  EXPECT_EQ(glb.exitCode, 0) << glb.output;
  ASSERT_TRUE(files.count("model.3dm"));
  const auto rhino = exporter::testing::runNodeScript(
      "check_3dm.mjs",
      (out / "model.3dm").string() + " P0-U,P0-V,P1-U,P1-V,P2-U,P2-V,P3-U,P3-V 32");
  EXPECT_EQ(rhino.exitCode, 0) << rhino.output;
  fs::remove_all(out);
}

// A 3dm writer that fails (here a stand-in script that exits 3; in the field a broken Node.js or
// rhino3dm) is a failure of the run, named in its report, not an internal error without one.
TEST(ModelStage, AFailingRhinoWriterIsARunFailureWithTheReportWritten) {
  const fs::path tmp =
      fs::temp_directory_path() / ("egg_model_badjs_" + std::to_string(::getpid()));
  const fs::path js = tmp / "js", out = tmp / "run";
  fs::create_directories(js / "node_modules" / "rhino3dm");
  std::ofstream(js / "write3dm.mjs") << "console.error('rhino3dm broke'); process.exit(3);\n";
  std::ofstream(js / "node_modules" / "rhino3dm" / "rhino3dm.js") << "\n";
  const char* before = std::getenv("EGG_EXPORT_JS");
  const std::string saved = before ? before : "";
  ::setenv("EGG_EXPORT_JS", js.c_str(), 1);
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(twoByTwoGridScene(), options);
  if (before)
    ::setenv("EGG_EXPORT_JS", saved.c_str(), 1);
  else
    ::unsetenv("EGG_EXPORT_JS");
  ASSERT_EQ(result.failures.size(), 1u) << nlohmann::json(result.failures).dump(1);
  EXPECT_EQ(result.failures[0].rfind("model.3dm not written: ", 0), 0u) << result.failures[0];
  EXPECT_NE(result.failures[0].find("exited with 3"), std::string::npos) << result.failures[0];
  EXPECT_NE(result.failures[0].find("rhino3dm broke"), std::string::npos) << result.failures[0];
  EXPECT_EQ(result.report["failures"], nlohmann::json(result.failures));
  EXPECT_TRUE(result.report["model"].contains("rhino_error"));
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "model.glb"));
  EXPECT_FALSE(fs::exists(out / "model.3dm"));
  // Nothing of the writer's is left behind (its temporary input, output and log).
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".log"), std::string::npos) << entry.path();
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace egg::pipeline
