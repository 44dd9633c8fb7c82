// The "deployment" output on a 2 x 2 patch layout (issue 42): every patch driven from its flat
// grid to its supports, report.json deployment{}, deployment.csv, deployment.svg and a
// deployment.glb the Khronos validator accepts.
#include "pipeline/deployment_stage.hpp"

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

Scene deploymentTwoByTwoScene(bool joined = false) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "name": "bump_2x2_deployment",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1.0, "sigma": 1.5}, "edge_length_m": 0.4},
    "patching": {"patches": [[[-3,-3,0],[0,-3,0],[0,0,1],[-3,0,0]], [[0,-3,0],[3,-3,0],[3,0,0],[0,0,1]],
                             [[-3,0,0],[0,0,1],[0,3,0],[-3,3,0]], [[0,0,1],[3,0,0],[3,3,0],[0,3,0]]]},
    "grid": {"map_resolution": 30, "members_per_family": 4},
    "lamella": {"width_m": 0.05, "thickness_m": 0.005},
    "simulation": {"enabled": true, "gravity": false, "join_patches": false},
    "deployment": {"steps": 6},
    "outputs": ["report", "deployment"]})");
  if (joined) {
    scene["simulation"]["gravity"] = true;
    scene["simulation"]["join_patches"] = true;
  }
  return parseScene(scene, "/virtual/bump_2x2_deployment.json");
}

std::string deploymentFileText(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// deployment.svg rendered by librsvg's command line, as a person would open it.
bool chartRenders(const fs::path& out) {
  return std::system(("rsvg-convert -o " + (out / "deployment.png").string() + " " +
                      (out / "deployment.svg").string())
                         .c_str()) == 0;
}

// deployment.glb through the Khronos validator (when Node.js and its packages are there), then the
// run folder removed unless EGG_KEEP_TEST_FILES.
void expectValidGlbThenCleanUp(const fs::path& out) {
  if (const std::string why = exporter::testing::nodeChecksUnavailable(); !why.empty()) {
    fs::remove_all(out);
    GTEST_SKIP() << why;
  }
  const auto glb =
      exporter::testing::runNodeScript("check_glb.mjs", (out / "deployment.glb").string());
  EXPECT_EQ(glb.exitCode, 0) << glb.output;
  if (!std::getenv("EGG_KEEP_TEST_FILES")) fs::remove_all(out);
}

TEST(DeploymentStage, EveryPatchOfATwoByTwoLayoutDeploysFromItsFlatGridToTheSimulatedShape) {
  const fs::path out =
      fs::temp_directory_path() / ("egg_deployment_2x2_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(deploymentTwoByTwoScene(), options);
  const auto& section = result.report["deployment"];
  ASSERT_TRUE(section.value("ran", false)) << result.report.dump(1).substr(0, 4000);
  ASSERT_EQ(section["patches"].size(), 4u);
  size_t rows = 0;
  for (const auto& p : section["patches"]) {
    SCOPED_TRACE("patch " + std::to_string(p["patch"].get<int>()));
    ASSERT_TRUE(p["completed"].get<bool>()) << p.dump(1).substr(0, 2000);
    const auto& path = p["path"];
    ASSERT_GE(path.size(), 7u);  // the flat grid and at least the 6 steps asked for
    EXPECT_EQ(path.front()["t"], 0.0);
    // Corners first (t 0..1), then the shared sides' supports fixed (t 1..2).
    EXPECT_EQ(p["path_kind"], "corners first");
    EXPECT_EQ(p["engaged_from_t"], 1.0);
    EXPECT_EQ(path.back()["t"], 2.0);
    // Kept because it stays within the limits, or run beside the other path and lower.
    if (p.contains("alternative")) {
      EXPECT_LT(p["peak_stress_ratio"].get<double>(),
                p["alternative"]["peak_stress_ratio"].get<double>());
    } else {
      EXPECT_NE(p["path_choice"].get<std::string>().find("within the limits"), std::string::npos);
      EXPECT_LE(p["peak_stress_ratio"].get<double>(), 1.0);
      EXPECT_EQ(p["snaps"], 0);
      EXPECT_EQ(p["jammed_steps"], 0);
    }
    // The flat grid is the planar layout: all but stress free (the notch barriers hold the bolts
    // at their planar ends, Section 2.4.5).
    EXPECT_LT(path.front()["max_stress_ratio"].get<double>(), 0.05);
    // The weightless simulation's equilibrium is where the path ends, to the sliding bolts' path
    // dependence (pseudo-friction and notch barriers, Section 2.5): 0.2-2.3 mm here.
    EXPECT_LT(p["end_vs_simulation_rms_m"].get<double>(), 5e-3);
    EXPECT_GE(p["peak_stress_ratio"].get<double>(), p["end_stress_ratio"].get<double>());
    rows += path.size();
  }
  // One row per support and step.
  std::ifstream csv(out / "deployment.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("patch,step,t,support,x_m,y_m,z_m,force_x_n", 0), 0u);
  size_t lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_GE(lines, rows * 4);  // at least the 4 corners of every patch are supports
  EXPECT_GT(fs::file_size(out / "deployment.svg"), 1000u);
  EXPECT_TRUE(chartRenders(out));
  // report.html's section: the table and the chart inlined.
  const std::string html = deploymentFileText(out / "report.html");
  EXPECT_NE(html.find("<h2 id=\"deployment\">"), std::string::npos);
  EXPECT_NE(html.find("<td>P3</td><td>corners first</td>"), std::string::npos);
  EXPECT_NE(html.find("<svg id=\"deployment-chart\""), std::string::npos);
  ASSERT_TRUE(fs::exists(out / "deployment.glb"));
  expectValidGlbThenCleanUp(out);
}

TEST(DeploymentStage, TheStandingPatchesAreJoinedAndEndWhereTheJoinedSimulationStands) {
  const fs::path out =
      fs::temp_directory_path() / ("egg_deployment_joined_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(deploymentTwoByTwoScene(true), options);
  const auto& joined = result.report["deployment"]["joined"];
  ASSERT_TRUE(joined.value("ran", false)) << joined.dump(1).substr(0, 2000);
  ASSERT_TRUE(joined["completed"].get<bool>()) << joined.dump(1).substr(0, 2000);
  EXPECT_TRUE(joined["self_weight"].get<bool>());
  EXPECT_EQ(joined["joints"], result.report["simulation"]["joined"]["bolts"]);
  const auto& path = joined["path"];
  EXPECT_EQ(path.front()["t"], 0.0);
  // Self-weight (t 0..1), the joints (1..2), and the shoring (2..3) where there is any: here every
  // side connection is one of the grid's own anchors.
  EXPECT_EQ(path.back()["t"].get<double>(),
            joined["temporary_supports"].get<int>() > 0 ? 3.0 : 2.0);
  // The joints were open before the bolts pulled; what stays open is the misfit of the two
  // patches' boundary lamellas, the same in the joined simulation (0.2096 and 0.2104 mm here).
  EXPECT_GT(joined["join_gap_before_m"].get<double>(), joined["end_join_gap_m"].get<double>());
  const double simulated = joined["joined_simulation_join_gap_m"].get<double>();
  EXPECT_GT(simulated, 0.0);
  EXPECT_NEAR(joined["end_join_gap_m"].get<double>(), simulated, 0.1 * simulated);
  // The end is the joined simulation's equilibrium, to the sliding bolts' path dependence that
  // each patch's own path already carries (up to 2.3 mm here, the test above): 5.6 mm measured.
  EXPECT_LT(joined["end_vs_joined_simulation_rms_m"].get<double>(), 1e-2);
  // Its rows in the CSV, its panels in the chart, its animation in the GLB.
  std::ifstream csv(out / "deployment.csv");
  std::string line;
  size_t rows = 0;
  while (std::getline(csv, line)) rows += line.rfind("joined,", 0) == 0;
  EXPECT_GE(rows, path.size());
  EXPECT_NE(deploymentFileText(out / "deployment.svg").find("Joining the patches"),
            std::string::npos);
  EXPECT_TRUE(chartRenders(out));
  EXPECT_NE(deploymentFileText(out / "report.html").find("<td>joined</td>"), std::string::npos);
  expectValidGlbThenCleanUp(out);
}

}  // namespace
}  // namespace egg::pipeline
