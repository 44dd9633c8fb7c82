// Generalised patches in `egg run` (issue 41): the Great Court's ring between the Reading Room and
// its tangent box, which the four quad patches leave cut off, is split at its four necks into
// disks and each gets a generalised grid anchored on the Reading Room's rim and on the quad
// patches' sides.
#include "pipeline/pipeline.hpp"

#include "core/io/atomic_file.hpp"
#include "tests/export/node_check.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <unistd.h>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

fs::path infillScratch(const std::string& name) {
  return fs::temp_directory_path() / (name + "_" + std::to_string(getpid()));
}

Scene infillGreatCourt(bool infill, std::vector<std::string> outputs = {"report", "plan"}) {
  Scene scene = loadScene(fs::path(EGG_SOURCE_DIR) / "samples" / "great_court.json");
  scene.outputs = std::move(outputs);
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

// The generalised patches are part of the structure, not drawings beside it: the joined run bolts
// their member ends to the quads' boundary lamellas, the cut sheets carry their lamellas, their
// rim anchors stand on supports, the assembly order deploys them after the quads they bolt to, and
// the 3D model holds them.
TEST(InfillStage, SlowGreatCourtGeneralisedPatchesAreJoinedCutAndModelled) {
  PipelineOptions options;
  options.outDir = infillScratch("egg_infill_gc_joined");
  const auto result = runPipeline(
      infillGreatCourt(true, {"report", "cut_files", "stickers", "supports", "model"}), options);
  EXPECT_TRUE(result.failures.empty()) << nlohmann::json(result.failures).dump(1);
  const auto& report = result.report;
  const auto& generalised = report["generalised_patches"];
  ASSERT_EQ(generalised.size(), 4u);
  int members = 0, crossings = 0, rimAnchors = 0;
  for (size_t i = 0; i < generalised.size(); ++i) {
    // Numbered after the four quads.
    EXPECT_EQ(generalised[i]["patch_id"].get<int>(), 4 + static_cast<int>(i));
    members += generalised[i]["members"].get<int>();
    crossings += generalised[i]["crossings"].get<int>();
    rimAnchors += generalised[i]["anchors"]["design_boundary"].get<int>();
  }
  const auto& joined = report["simulation"]["joined"];
  ASSERT_TRUE(joined["ran"].get<bool>()) << joined.dump(1);
  EXPECT_TRUE(joined["converged"].get<bool>()) << joined.dump(1);
  const auto& ring = joined["generalised_patches"];
  EXPECT_EQ(ring["patches"].get<int>(), 4);
  // Every end on a quad side lies on that quad's boundary lamella (the layout mesh carries the
  // sides): about half the ends (the family in the other layer) are bolted to it.
  EXPECT_GT(ring["ring_beam_bolts"].get<int>(), 10);
  EXPECT_GE(ring["ring_beam_bolts"].get<int>(),
            ring["patch_side_ends_anchored_same_layer"].get<int>());
  EXPECT_EQ(ring["patch_side_ends_anchored_no_lamella"].get<int>(), 0);
  EXPECT_LT(ring["ring_beam_max_gap_m"].get<double>(), 0.01);
  // Within Table 3.3's tolerance like the quads alone (7.9 cm joined).
  EXPECT_LT(joined["rmse_m"].get<double>(), 0.1);
  // Fabrication: every generalised member a lamella ("P4-U0" ...) with a hole or slot at each of
  // its crossings and a bolt hole at each end (its anchor bolt, or its bolt through the quad's
  // boundary lamella), as bom.csv counts them.
  std::ifstream bom(result.outDir / "bom.csv");
  std::string row;
  int lamellas = 0, cutOuts = 0, brackets = 0;
  while (std::getline(bom, row)) {
    brackets += row.rfind("ring_beam_bracket,P", 0) == 0;
    const std::regex generalisedRow(R"(^lamella,P[4-7]-[UV]\d+,.*; (\d+) holes; (\d+) slots;)");
    std::smatch m;
    if (!std::regex_search(row, m, generalisedRow)) continue;
    ++lamellas;
    cutOuts += std::stoi(m[1]) + std::stoi(m[2]);
  }
  EXPECT_EQ(lamellas, members);
  EXPECT_EQ(cutOuts, 2 * crossings + 2 * members);
  const auto& fabrication = report["fabrication"];
  int quadConnections = 0;
  for (const auto& p : report["patches"])
    if (p["feasible"].get<bool>()) quadConnections += p["connections"].get<int>();
  // The ends in a quad lamella's own layer are fixed by brackets, one each.
  EXPECT_EQ(brackets, ring["patch_side_ends_anchored_same_layer"].get<int>());
  // Shared sides' holes merge; each generalised crossing and member end adds one bolt, and each
  // bracket a second through the quad's lamella.
  EXPECT_GE(fabrication["bolts"].get<int>(), crossings + 2 * members + brackets);
  EXPECT_LE(fabrication["bolts"].get<int>(), quadConnections + crossings + 2 * members + brackets);
  // Supports at the generalised members' ends on the Reading Room's rim (one per point).
  std::ifstream supports(result.outDir / "supports" / "supports.csv");
  std::string line;
  int endSupports = 0;
  while (std::getline(supports, line))
    endSupports += line.find("generalised member end") != std::string::npos;
  EXPECT_GT(endSupports, rimAnchors / 2);
  EXPECT_LE(endSupports, rimAnchors);
  // Assembly: the generalised patches after the quads they bolt to.
  const auto text =
      egg::test::runTool("pdftotext '" + (result.outDir / "cut" / "assembly.pdf").string() + "' -");
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("P4 after P"), std::string::npos) << text.output.substr(0, 2000);
  ASSERT_NE(text.output.find("Patch P4"), std::string::npos);
  EXPECT_LT(text.output.find("Patch P0"), text.output.find("Patch P4"));
  // The 3D model holds every lamella of the quads and the generalised patches.
  const auto& model = report["model"];
  int quadMembers = 0;
  for (const auto& p : report["patches"])
    if (p["feasible"].get<bool>())
      quadMembers += p["members_u"].get<int>() + p["members_v"].get<int>();
  EXPECT_EQ(model["lamellas"].get<int>(), quadMembers + members);
  EXPECT_EQ(model["centreline_source"], "joined simulation");
  // Checked by the programs people open them with: the glTF validator and rhino3dm, with a layer
  // per patch and family for the generalised patches P4-P7 too.
  if (exporter::testing::nodeChecksUnavailable().empty()) {
    const int all = quadMembers + members;
    const auto glb = exporter::testing::runNodeScript(
        "check_glb.mjs", (result.outDir / "model.glb").string() + " " + std::to_string(all));
    EXPECT_EQ(glb.exitCode, 0) << glb.output;
    std::string layers;
    for (int p = 0; p < 8; ++p)
      layers += (p ? ",P" : "P") + std::to_string(p) + "-U,P" + std::to_string(p) + "-V";
    const auto rhino = exporter::testing::runNodeScript(
        "check_3dm.mjs",
        (result.outDir / "model.3dm").string() + " " + layers + " " + std::to_string(all));
    EXPECT_EQ(rhino.exitCode, 0) << rhino.output;
  }
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

TEST(InfillStage, TwoGivenPatchesInAGeneralisedFrameAreJoinedDeployedAndJoinedAgain) {
  // Two 3 x 6 m patches side by side on an 8 x 8 m bump, their frame closed by generalised
  // patches: the joined simulation bolts the quads along their shared side and the generalised
  // members' ends to the quads' sides; the deployment stands the quads up along their paths and
  // joins everything, the generalised patches as their own simulations left them.
  const Scene scene = parseScene(nlohmann::json::parse(R"({
    "name": "bump_frame_two",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5},
                "edge_length_m": 0.25},
    "patching": {"patches": [[[-3,-3,0],[0,-3,0],[0,3,0],[-3,3,0]],
                             [[0,-3,0],[3,-3,0],[3,3,0],[0,3,0]]], "generalised_infill": true},
    "grid": {"map_resolution": 30, "members_per_family": 5},
    "lamella": {"width_m": 0.06, "thickness_m": 0.006},
    "simulation": {"gravity": false},
    "outputs": ["report", "deployment", "model"]})"),
                                 "/virtual/bump_frame_two.json");
  PipelineOptions options;
  options.outDir = infillScratch("egg_infill_frame_two");
  const auto result = runPipeline(scene, options);
  EXPECT_TRUE(result.failures.empty()) << nlohmann::json(result.failures).dump(1);
  const auto& report = result.report;
  EXPECT_GE(report["coverage"]["fraction"].get<double>(), 0.99);
  int members = 0;
  for (const auto& g : report["generalised_patches"]) {
    ASSERT_TRUE(g["feasible"].get<bool>()) << g.dump(1);
    members += g["members"].get<int>();
  }
  const auto& joined = report["simulation"]["joined"];
  ASSERT_TRUE(joined["ran"].get<bool>()) << joined.dump(1);
  EXPECT_TRUE(joined["converged"].get<bool>());
  const int ringBolts = joined["generalised_patches"]["ring_beam_bolts"].get<int>();
  EXPECT_GT(ringBolts, 0);
  // Each patch's layers bolt the more of its ends on the quads' sides (a swap trades the bolted
  // ends for the bracket ends), so brackets are the fewer.
  const int brackets =
      joined["generalised_patches"]["patch_side_ends_anchored_same_layer"].get<int>();
  EXPECT_GT(brackets, 0);
  EXPECT_GE(ringBolts, brackets);
  // The quads' own joints along their shared side, then the ring-beam bolts.
  EXPECT_GT(joined["bolts"].get<int>(), ringBolts);
  const auto& deployment = report["deployment"];
  ASSERT_EQ(deployment["patches"].size(), 2u);  // the quads along their support paths
  const auto& joining = deployment["joined"];
  EXPECT_TRUE(joining["completed"].get<bool>()) << joining.dump(1).substr(0, 2000);
  EXPECT_EQ(joining["joints"].get<int>(), joined["bolts"].get<int>());
  EXPECT_TRUE(deployment.contains("generalised_patches"));
  int quadMembers = 0;
  for (const auto& p : report["patches"])
    quadMembers += p["members_u"].get<int>() + p["members_v"].get<int>();
  EXPECT_EQ(report["model"]["lamellas"].get<int>(), quadMembers + members);
  fs::remove_all(result.outDir);
}

}  // namespace
}  // namespace egg::pipeline
