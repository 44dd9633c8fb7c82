// Generalised patches in `egg run` (issue 41): the Great Court's ring between the Reading Room and
// its tangent box, which the four quad patches leave cut off, is split at its four necks into
// disks and each gets a generalised grid anchored on the Reading Room's rim and on the quad
// patches' sides.
#include "pipeline/pipeline.hpp"

#include "core/io/atomic_file.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

fs::path infillScratch(const std::string& name) {
  return fs::temp_directory_path() / (name + "_" + std::to_string(getpid()));
}

Scene infillGreatCourt(bool infill) {
  Scene scene = loadScene(fs::path(EGG_SOURCE_DIR) / "samples" / "great_court.json");
  scene.outputs = {"report", "plan"};
  scene.patching.generalisedInfill = infill;
  return scene;
}

TEST(InfillStage, SlowGreatCourtRingIsClosedByFourGeneralisedPatches) {
  PipelineOptions options;
  options.outDir = infillScratch("egg_infill_gc");
  const auto result = runPipeline(infillGreatCourt(true), options);
  EXPECT_TRUE(result.failures.empty()) << nlohmann::json(result.failures).dump(1);
  const auto& report = result.report;
  const auto& coverage = report["coverage"];
  // The quads alone leave the 503 m^2 ring (0.919); with the generalised patches nothing is left.
  EXPECT_LT(coverage["fraction_quad_patches"].get<double>(), 0.93);
  EXPECT_GE(coverage["fraction"].get<double>(), 0.99);
  EXPECT_TRUE(coverage["cut_offs"].empty());
  const auto& generalised = report["generalised_patches"];
  ASSERT_EQ(generalised.size(),
            4u);  // one per corner of the box: the ring's necks are at its sides
  double area = 0.0;
  for (const auto& g : generalised) {
    ASSERT_TRUE(g["feasible"].get<bool>()) << g.dump(1);
    EXPECT_EQ(g["kind"], "generalised");
    area += g["area_m2"].get<double>();
    EXPECT_GE(g["members"].get<int>(), 6);
    EXPECT_GE(g["e_shape"].get<double>(), 0.0);
    EXPECT_LE(g["e_shape"].get<double>(), 1.0);
    EXPECT_LE(g["planarisation"]["length_residual_m"].get<double>(), 1e-9);
    EXPECT_EQ(g["planarisation"]["overlapping_lamellas"].get<int>(), 0);
    EXPECT_EQ(g["planarisation"]["overlapping_neighbours"].get<int>(), 0);
    // Members run from the quad patches' sides to the Reading Room's rim.
    EXPECT_GT(g["anchors"]["design_boundary"].get<int>(), 0);
    EXPECT_GT(g["anchors"]["patch_sides"].get<int>(), 0);
    ASSERT_TRUE(g.contains("simulation"));
    EXPECT_TRUE(g["simulation"]["converged"].get<bool>());
    // Within a few lamella depths of the surface (the quads: 8.7 cm RMSE patch by patch).
    EXPECT_LT(g["simulation"]["rmse_m"].get<double>(), 0.1);
  }
  EXPECT_NEAR(area, coverage["covered_area_generalised_patches_m2"].get<double>(), 1e-6);
  // Each patch's cut list: a row per lamella, its length the member's and every crossing a hole
  // in both of its lamellas; the planar layout renders.
  for (int i = 0; i < 4; ++i) {
    const fs::path dir = result.outDir / ("generalised_G" + std::to_string(i));
    std::ifstream csv(dir / "lamellas.csv");
    ASSERT_TRUE(csv.good()) << dir;
    std::string line;
    int rows = -1, holes = 0;
    while (std::getline(csv, line)) {
      ++rows;
      if (rows > 0) holes += static_cast<int>(std::count(line.begin(), line.end(), '@'));
    }
    EXPECT_EQ(rows, generalised[i]["members"].get<int>());
    EXPECT_EQ(holes, 2 * generalised[i]["crossings"].get<int>());
    const auto png =
        fs::temp_directory_path() / ("egg_infill_planar_" + std::to_string(i) + ".png");
    const auto run = egg::test::runTool("rsvg-convert -w 1200 -o '" + png.string() + "' '" +
                                        (dir / "planar.svg").string() + "'");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_GT(fs::file_size(png), 2000u);
    fs::remove(png);
  }
  std::ifstream plan(result.outDir / "plan.svg");
  std::stringstream text;
  text << plan.rdbuf();
  EXPECT_NE(text.str().find("id=\"generalised-G0\""), std::string::npos);
  EXPECT_NE(text.str().find("id=\"generalised-G3\""), std::string::npos);
  fs::remove_all(result.outDir);
}

TEST(InfillStage, SlowSwitchedOffTheRingStaysACutOff) {
  PipelineOptions options;
  options.outDir = infillScratch("egg_infill_gc_off");
  const auto result = runPipeline(infillGreatCourt(false), options);
  const auto& coverage = result.report["coverage"];
  EXPECT_LT(coverage["fraction"].get<double>(), 0.93);
  EXPECT_EQ(coverage["cut_offs"].size(), 1u);
  EXPECT_FALSE(result.report.contains("generalised_patches") &&
               !result.report["generalised_patches"].is_null());
  fs::remove_all(result.outDir);
}

TEST(InfillStage, AGivenPatchInsideItsSurfaceGetsItsFrameOnlyWhenAsked) {
  // One 6 x 6 m patch given on an 8 x 8 m bump: the frame round it is a ring whose necks are the
  // middles of its sides (1 m wide against 1.4 m at the corners), so it is split into four
  // corner pieces. A given layout is taken as it is unless the scene asks for the infill.
  const auto scene = [](const std::string& infill) {
    return parseScene(nlohmann::json::parse(R"({
      "name": "bump_frame",
      "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5}, "edge_length_m": 0.25},
      "patching": {"patches": [[[-3,-3,0],[3,-3,0],[3,3,0],[-3,3,0]]])" +
                                            infill + R"(},
      "grid": {"map_resolution": 30, "members_per_family": 7},
      "lamella": {"width_m": 0.1, "thickness_m": 0.01},
      "simulation": {"gravity": false},
      "outputs": ["report"]})"),
                      "/virtual/bump_frame.json");
  };
  PipelineOptions options;
  options.outDir = infillScratch("egg_infill_frame");
  const auto plain = runPipeline(scene(""), options);
  EXPECT_LT(plain.report["coverage"]["fraction"].get<double>(), 0.8);
  EXPECT_TRUE(!plain.report.contains("generalised_patches") ||
              plain.report["generalised_patches"].is_null());
  const auto framed = runPipeline(scene(R"(, "generalised_infill": true)"), options);
  EXPECT_TRUE(framed.failures.empty()) << nlohmann::json(framed.failures).dump(1);
  const auto& generalised = framed.report["generalised_patches"];
  ASSERT_EQ(generalised.size(), 4u);
  for (const auto& g : generalised) {
    ASSERT_TRUE(g["feasible"].get<bool>()) << g.dump(1);
    EXPECT_GT(g["anchors"]["design_boundary"].get<int>(), 0);
    EXPECT_GT(g["anchors"]["patch_sides"].get<int>(), 0);
    EXPECT_TRUE(g["simulation"]["converged"].get<bool>());
  }
  EXPECT_GE(framed.report["coverage"]["fraction"].get<double>(), 0.99);
  fs::remove_all(framed.outDir);
}

}  // namespace
}  // namespace egg::pipeline
