#include "apps/bench/pipeline_bench.hpp"

#include "core/errors.hpp"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

TEST(PipelineBench, ParetoFrontKeepsWhatNothingBeatsInBoth) {
  // (time, error): (3, 0.1) is beaten by (2, 0.05), (5, 0.01) by the faster (4, 0.01); (1, 0.2)
  // is the fastest; NaN never counts.
  const std::vector<std::pair<double, double>> points{{3, 0.1},  {1, 0.2},   {2, 0.05},
                                                      {4, 0.01}, {0.5, NAN}, {5, 0.01}};
  EXPECT_EQ(paretoFront(points), (std::vector<size_t>{1, 2, 3}));  // by time
  EXPECT_TRUE(paretoFront({}).empty());
}

TEST(PipelineBench, SweepsASmallSceneIntoACsvAndAPlot) {
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_bench_" + std::to_string(::getpid()));
  fs::remove_all(out);
  PipelineBenchOptions options;
  options.scenes = {(fs::path(EGG_SOURCE_DIR) / "samples" / "scenes" / "bump_small.json").string()};
  options.edgeFactors = {1.0, 2.0};
  options.mapProxyVertices = {600};
  options.newtonTolerances = {};
  options.spacingFactors = {};
  options.out = out;
  options.json = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(runPipelineBench(options), 0);
  testing::internal::GetCapturedStdout();
  std::ifstream csv(out / "pipeline.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("scene,edge_factor,edge_length_m,map_proxy_vertices,wall_s,", 0), 0u)
      << header;
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 2u);
  // The coarser mesh (edge x2: 0.8 m) has fewer vertices; both runs converge and give an RMSE.
  std::vector<std::vector<std::string>> cells;
  for (const auto& r : rows) {
    std::vector<std::string> c;
    std::stringstream ss(r);
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    cells.push_back(c);
  }
  EXPECT_EQ(cells[0][2], "0.4");
  EXPECT_EQ(cells[1][2], "0.8");
  EXPECT_GT(std::stoi(cells[0][5]), std::stoi(cells[1][5]));
  EXPECT_GT(std::stod(cells[0][7]), 0.0);
  EXPECT_EQ(cells[0][11], "1");
  EXPECT_EQ(cells[0][16], "base");
  EXPECT_EQ(cells[1][16], "edge_x2");
  EXPECT_TRUE(fs::exists(out / "runs" / "bump_small-00-base" / "report.json"));
  // The plot is an SVG a real renderer reads.
  ASSERT_TRUE(fs::exists(out / "pipeline.svg"));
  if (std::system("command -v rsvg-convert > /dev/null 2>&1") == 0) {
    const std::string png = (out / "pipeline.png").string();
    EXPECT_EQ(
        std::system(
            ("rsvg-convert '" + (out / "pipeline.svg").string() + "' -o '" + png + "'").c_str()),
        0);
    EXPECT_GT(fs::file_size(png), 1000u);
  }
  fs::remove_all(out);
}

TEST(PipelineBench, AVariantOutsideItsScenesBoundsIsAFailedRowAndTheOthersRun) {
  // bump_small with a 1 x 1 block grid under a 5 m patch limit: no variant can lay it out. Each is
  // a row with its failure, none stops the bench.
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_bench_bad_" + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  nlohmann::json scene;
  std::ifstream(fs::path(EGG_SOURCE_DIR) / "samples" / "scenes" / "bump_small.json") >> scene;
  scene["patching"]["block_grid"] = {1, 1};
  scene["patching"]["max_patch_size_m"] = 5;
  std::ofstream(out / "bump_small.json") << scene.dump();
  PipelineBenchOptions options;
  options.scenes = {(out / "bump_small.json").string()};
  options.edgeFactors = {1.0, 2.0};
  options.mapProxyVertices = {600};
  options.newtonTolerances = {};
  options.spacingFactors = {};
  options.out = out / "bench";
  testing::internal::CaptureStdout();
  EXPECT_EQ(runPipelineBench(options), 0);
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("not run: "), std::string::npos) << printed;
  EXPECT_NE(printed.find("patching.block_grid [1, 1]"), std::string::npos) << printed;
  std::ifstream csv(out / "bench" / "pipeline.csv");
  std::string line;
  std::getline(csv, line);
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    std::vector<std::string> c;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) c.push_back(cell);
    ASSERT_GT(c.size(), 13u) << line;
    EXPECT_EQ(c[12], "1") << line;  // failures
    EXPECT_EQ(c[13], "0") << line;  // not on the Pareto front
  }
  EXPECT_EQ(rows, 2);
  fs::remove_all(out);
}

TEST(PipelineBench, VariesOneKnobAtATimeFromTheFirstValues) {
  PipelineBenchOptions
      options;  // defaults: edge {1, 1.5, 2}, proxy {600, 0}, Newton {1e-10, 1e-6}, spacing {8, 12}
  options.mapTolerances = {1e-4, 1e-2};
  const auto variants = pipelineVariants(options, "great_court");
  std::vector<std::string> varied;
  for (const auto& v : variants) varied.push_back(v.varied);
  EXPECT_EQ(varied,
            (std::vector<std::string>{"base", "edge_x1.5", "edge_x2", "proxy_0", "map_tol_0.01",
                                      "newton_tol_1e-06", "spacing_x12", "paper_section_25x4cm"}));
  // Each variant changes its own knob only; the row tolerance needs the maps on the patch.
  EXPECT_DOUBLE_EQ(variants[0].edgeFactor, 1.0);
  EXPECT_EQ(variants[0].mapProxyVertices, 600);
  EXPECT_DOUBLE_EQ(variants[0].newtonTolerance, 1e-10);
  EXPECT_DOUBLE_EQ(variants[2].edgeFactor, 2.0);
  EXPECT_EQ(variants[2].mapProxyVertices, 600);
  EXPECT_EQ(variants[4].mapProxyVertices, 0);
  EXPECT_DOUBLE_EQ(variants[4].mapTolerance, 1e-2);
  EXPECT_DOUBLE_EQ(variants[5].newtonTolerance, 1e-6);
  EXPECT_DOUBLE_EQ(variants[5].spacingFactor, 8.0);
  EXPECT_DOUBLE_EQ(variants[6].spacingFactor, 12.0);
  EXPECT_DOUBLE_EQ(variants[7].widthM, 0.25);
  EXPECT_DOUBLE_EQ(variants[7].thicknessM, 0.04);
  // A scene that is not one of the paper's gets no paper section; --product runs 3 x 2 x 2 x 2 x 2.
  EXPECT_EQ(pipelineVariants(options, "bump").size(), 7u);
  options.product = true;
  options.paperSection = false;
  EXPECT_EQ(pipelineVariants(options, "lilium").size(), 48u);
  // Issue 40: long lists made an unbounded product (here 20^5 = 3.2 million runs per sample).
  std::vector<double> many(20, 1.0);
  options.edgeFactors = options.mapTolerances = options.newtonTolerances = options.spacingFactors =
      many;
  options.mapProxyVertices = std::vector<int>(20, 0);
  try {
    pipelineVariants(options, "lilium");
    FAIL() << "3.2 million variants accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--product: 3200000 combinations"), std::string::npos)
        << e.what();
  }
}

TEST(PipelineBench, BadInputIsNamed) {
  PipelineBenchOptions options;
  options.scenes = {"/nonexistent/scene.json"};
  EXPECT_THROW(runPipelineBench(options), Error);
  options.scenes = {(fs::path(EGG_SOURCE_DIR) / "samples" / "scenes" / "bump_small.json").string()};
  options.edgeFactors = {0.0};
  try {
    runPipelineBench(options);
    FAIL() << "an edge factor of 0 ran";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--edge-factors"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace egg::app
