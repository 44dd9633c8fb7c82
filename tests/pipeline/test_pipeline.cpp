// `egg run` end to end on a small bump patch: surface -> EGG solve -> grid -> simulation, with the
// report's invariants checked against each other and against the thesis' criteria.
#include "pipeline/pipeline.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>

#include <tbb/global_control.h>

#include <filesystem>

#include <unistd.h>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

Scene bumpPatchScene() {
  return parseScene(nlohmann::json::parse(R"({
    "name": "bump_patch",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5}, "edge_length_m": 0.5},
    "patching": {"patches": [[[-3,-3,0],[3,-3,0],[3,3,0],[-3,3,0]]]},
    "grid": {"map_resolution": 30, "members_per_family": 5},
    "lamella": {"width_m": 0.1, "thickness_m": 0.01},
    "simulation": {"gravity": false},
    "outputs": ["report", "previews"]})"),
                    "/virtual/bump_patch.json");
}

TEST(Pipeline, SlowBumpPatchRunsEndToEnd) {
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(bumpPatchScene(), options);
  const auto& report = result.report;
  EXPECT_TRUE(result.failures.empty());

  ASSERT_EQ(report["patches"].size(), 1u);
  const auto& patch = report["patches"][0];
  EXPECT_TRUE(patch["feasible"].get<bool>());
  EXPECT_EQ(patch["members_u"], 5);
  EXPECT_EQ(patch["members_v"], 5);
  // Criterion (i): planar and spatial member lengths agree.
  EXPECT_LT(patch["max_length_mismatch_relative"].get<double>(), 1e-9);
  // A bump is not developable: notches appear (Section 2.4.5) but stay a fraction of the patch.
  EXPECT_GT(patch["max_notch_m"].get<double>(), 1e-4);
  EXPECT_LT(patch["max_notch_m"].get<double>(), 1.0);
  const auto range = patch["alpha_bar_range_rad"];
  EXPECT_LE(range[0].get<double>(), patch["alpha_bar_rad"].get<double>());
  EXPECT_GE(range[1].get<double>(), patch["alpha_bar_rad"].get<double>());
  EXPECT_GT(patch["slope_min"].get<double>(), 0.1);
  EXPECT_LT(patch["slope_max"].get<double>(), 10.0);

  // Coverage is the patch area over the surface area.
  EXPECT_NEAR(report["coverage"]["covered_area_m2"].get<double>(), patch["area_m2"].get<double>(),
              1e-12);
  EXPECT_NEAR(report["coverage"]["fraction"].get<double>(),
              patch["area_m2"].get<double>() / report["surface"]["area_m2"].get<double>(), 1e-12);
  EXPECT_GT(patch["area_m2"].get<double>(), 36.0);  // the 6 x 6 m footprint, lifted by the bump

  const auto& sim = report["simulation"];
  ASSERT_TRUE(sim["ran"].get<bool>());
  EXPECT_TRUE(sim["converged"].get<bool>()) << sim.dump(1);
  // The deployed grid lies near the design surface: RMSE a small fraction of the 6 m span.
  EXPECT_GT(sim["rmse_m"].get<double>(), 0.0);
  EXPECT_LT(sim["rmse_m"].get<double>(), 0.1);
  EXPECT_GE(sim["max_error_m"].get<double>(), sim["rmse_m"].get<double>());
  EXPECT_FALSE(report["stages"]["propagation"]["ran"].get<bool>());
  EXPECT_TRUE(report["stages"]["grid"]["ran"].get<bool>());
  // The cladding functions with their members (report.html's cladding section): F from (0,0) to
  // (1,1), the 5 members on it, the scene's slope bounds, the patch's side lengths.
  const auto& cladding = patch["cladding"];
  EXPECT_EQ(cladding["slope_bounds"], nlohmann::json({0.1, 10.0}));
  for (const char* family : {"u", "v"}) {
    const auto& f = cladding[family];
    EXPECT_EQ(f["members_x1"].size(), 5u) << family;
    EXPECT_EQ(f["points_x1"].front(), 0.0) << family;
    EXPECT_EQ(f["points_x2"].back(), 1.0) << family;
    EXPECT_TRUE(f["bijective"].get<bool>()) << family;
    EXPECT_GT(f["start_side_m"].get<double>(), 6.0)
        << family;  // a side of the 6 x 6 m footprint, lifted by the bump
  }
  // Error against run time: from the start (the guess on the surface) to the final state.
  const auto& history = sim["patches"][0]["history"];
  ASSERT_GE(history.size(), 2u);
  EXPECT_EQ(history.front()["iteration"], 0);
  EXPECT_EQ(history.back()["iteration"], sim["patches"][0]["iterations"]);
  EXPECT_EQ(history.back()["rmse_m"], sim["rmse_m"]);
  EXPECT_EQ(history.back()["max_error_m"], sim["max_error_m"]);

  for (const char* file : {"report.json", "report.html", "patch_000/grid.json",
                           "patch_000/grid.obj", "patch_000/planar.svg", "patch_000/deployed.obj",
                           "preview/cladding_patch_0.png", "preview/error_time_patches.png"}) {
    EXPECT_TRUE(fs::exists(out / file)) << file;
  }
  fs::remove_all(out);
}

TEST(Pipeline, InfeasiblePatchIsReportedNotFatal) {
  Scene scene = bumpPatchScene();
  // Slope bounds so tight that no alpha_bar satisfies Problem 2.3 on a bump.
  scene.design().alphaBar.slopeMin = 0.999;
  scene.design().alphaBar.slopeMax = 1.001;
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_infeasible_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(scene, options);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_FALSE(result.report["patches"][0]["feasible"].get<bool>());
  EXPECT_FALSE(result.report["simulation"]["ran"].get<bool>());
  EXPECT_TRUE(fs::exists(out / "report.json"));  // the report still explains what happened
  fs::remove_all(out);
}

// simulation.max_newton_iterations reaches the rod solver: a budget of 2 Newton iterations cannot
// deploy the bump's grid, and the run says so (exit 1) with every figure of the report.
TEST(Pipeline, TheNewtonBudgetOfTheSceneBoundsTheDeployment) {
  Scene scene = parseScene(
      [] {
        nlohmann::json j = sceneToJson(bumpPatchScene());
        j.erase("path");
        j["simulation"]["max_newton_iterations"] = 2;
        j["outputs"] = {"report"};
        return j;
      }(),
      "/virtual/bump_patch.json");
  EXPECT_EQ(scene.simulation.rods.solver.maxIterations, 2);
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_budget_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(scene, options);
  const auto& sim = result.report["simulation"];
  ASSERT_TRUE(sim["ran"].get<bool>());
  EXPECT_FALSE(sim["converged"].get<bool>());
  EXPECT_LE(sim["patches"][0]["iterations"].get<int>(), 2);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_EQ(result.failures[0].rfind("simulation: ", 0), 0u) << result.failures[0];
  fs::remove_all(out);
}

// Self-weight (Section 3.5.2): the report gives each patch's sag from its weightless equilibrium,
// and a sag means the same grid without gravity would sit higher.
TEST(Pipeline, SlowSelfWeightReportsTheSag) {
  Scene scene = bumpPatchScene();
  scene.simulation.rods.model.gravity = true;
  const fs::path out =
      fs::temp_directory_path() / ("egg_pipeline_gravity_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(scene, options);
  const auto& sim = result.report["simulation"];
  ASSERT_TRUE(sim["ran"].get<bool>());
  EXPECT_TRUE(sim["gravity"].get<bool>());
  ASSERT_EQ(sim["patches"].size(), 1u);
  const auto& patch = sim["patches"][0];
  ASSERT_TRUE(patch.contains("max_sag_m")) << patch.dump(1);
  EXPECT_GT(patch["max_sag_m"].get<double>(), 0.0);
  // A 6 m patch of 100 x 10 mm poplar lamellas, five per family, anchored at its corners: it sags,
  // but by far less than its span unless it collapsed (which the status would say).
  if (patch["status"] != "collapsed") {
    EXPECT_LT(patch["max_sag_m"].get<double>(), 0.6);
  }
  fs::remove_all(out);
}

}  // namespace
}  // namespace egg::pipeline

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

// The 2 x 2 layout on the bump: four patches meeting at the peak, given as four corners each
// (the corners they share are written twice and become one corner of the layout).
Scene twoByTwoScene(const std::string& outputs) {
  return parseScene(nlohmann::json::parse(R"({
    "name": "bump_2x2",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1.0, "sigma": 1.5}, "edge_length_m": 0.4},
    "patching": {"patches": [[[-3,-3,0],[0,-3,0],[0,0,1],[-3,0,0]], [[0,-3,0],[3,-3,0],[3,0,0],[0,0,1]],
                             [[-3,0,0],[0,0,1],[0,3,0],[-3,3,0]], [[0,0,1],[3,0,0],[3,3,0],[0,3,0]]]},
    "grid": {"map_resolution": 30, "members_per_family": 4},
    "lamella": {"width_m": 0.05, "thickness_m": 0.005},
    "simulation": {"gravity": false},
    "outputs": )" + outputs + "}"),
                    "/virtual/bump_2x2.json");
}

fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
}

TEST(PipelineMultiPatch, SlowTwoByTwoSharesItsSidesAndReportsTheGraph) {
  const fs::path out = scratch("egg_pipeline_2x2");
  PipelineOptions options;
  options.outDir = out;
  std::vector<std::pair<std::string, double>> progress;  // the progress bar's feed
  options.progress = [&](const std::string& stage, double fraction) {
    progress.emplace_back(stage, fraction);
  };
  const PipelineResult result =
      runPipeline(twoByTwoScene(R"(["report", "plan", "cut_files"])"), options);
  const auto& report = result.report;
  EXPECT_TRUE(result.failures.empty()) << nlohmann::json(result.failures).dump(1);
  // Stages in order, never going back, one step per simulated patch, ending at 1.
  ASSERT_FALSE(progress.empty());
  for (size_t i = 1; i < progress.size(); ++i)
    EXPECT_GE(progress[i].second, progress[i - 1].second) << progress[i].first;
  EXPECT_EQ(progress.back(), std::make_pair(std::string("done"), 1.0));
  EXPECT_EQ(
      std::count_if(progress.begin(), progress.end(),
                    [](const auto& p) { return p.first.rfind("simulation: patch ", 0) == 0; }),
      4);
  EXPECT_NE(std::find_if(progress.begin(), progress.end(),
                         [](const auto& p) { return p.first == "simulation: patch 4 of 4"; }),
            progress.end());
  EXPECT_EQ(report["patching"]["workflow"], "given");
  EXPECT_EQ(report["patching"]["corners"], 9);  // shared corners given twice are one
  EXPECT_EQ(report["patching"]["sides"], 12);
  int shared = 0;
  for (const auto& b : report["boundaries"]) shared += b["kind"] == "shared";
  EXPECT_EQ(shared, 4);
  EXPECT_EQ(report["chains"].size(), 4u);
  // Propagation (Problem 3.3, Section 3.4.4): the four chains (two per family) are optimised and
  // the traced member ends of neighbours coincide on all four shared sides.
  ASSERT_TRUE(report["stages"]["propagation"]["ran"].get<bool>());
  const auto& propagation = report["propagation"];
  EXPECT_EQ(propagation["chains"], 4);
  EXPECT_EQ(propagation["originals"], 0);
  EXPECT_LE(propagation["c0_max_gap_m"].get<double>(), 1e-6);
  EXPECT_LE(propagation["evenness_after"].get<double>(),
            propagation["evenness_before"].get<double>());
  ASSERT_EQ(propagation["sides"].size(), 4u);
  for (const auto& side : propagation["sides"]) EXPECT_EQ(side["kind"], "closed") << side.dump();
  ASSERT_EQ(report["patches"].size(), 4u);
  double area = 0.0;
  for (const auto& p : report["patches"]) {
    EXPECT_TRUE(p["feasible"].get<bool>()) << p.dump(1);
    area += p["area_m2"].get<double>();
  }
  // Coverage is the union of the patches: here their sum, the 6 x 6 m square lifted by the bump.
  EXPECT_NEAR(report["coverage"]["covered_area_m2"].get<double>(), area, 1e-9);
  EXPECT_TRUE(report["stages"]["design"]["ran"].get<bool>());
  EXPECT_TRUE(report["stages"]["simulation"]["ran"].get<bool>());
  EXPECT_EQ(report["simulation"]["patches"].size(), 4u);
  // The joined structure: 4 shared sides x 4 member ends bolted, a checkerboard of layer swaps.
  const auto& joined = report["simulation"]["joined"];
  EXPECT_TRUE(joined["converged"].get<bool>()) << joined.dump(1);
  EXPECT_EQ(joined["bolts"], 16);
  EXPECT_EQ(joined["patches_swapped"], 2);
  EXPECT_TRUE(report["simulation"]["patch_by_patch"].contains("rmse_m"));
  ASSERT_GE(joined["history"].size(), 2u);
  EXPECT_EQ(joined["history"].back()["rmse_m"], joined["rmse_m"]);
  EXPECT_EQ(joined["history"].back()["iteration"], joined["iterations"]);
  EXPECT_TRUE(fs::exists(out / "patches.json"));
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "cut" / "sheets.pdf"));
  // The architect's plan carries what the later stages made: every patch's members, every support
  // of the fabrication stage, each patch's surface area; the analytical sheet and the elevations
  // sit beside it, and report.html shows all three.
  const std::string plan = readRegularFile(out / "plan.svg", 1 << 26, "plan.svg");
  EXPECT_NE(plan.find("class=\"members-u"), std::string::npos);
  EXPECT_NE(plan.find("class=\"members-v"), std::string::npos);
  int supportMarks = 0;
  for (size_t at = plan.find(" id=\"support-S"); at != std::string::npos;
       at = plan.find(" id=\"support-S", at + 1))
    ++supportMarks;
  EXPECT_EQ(supportMarks, report["fabrication"]["supports"].get<int>());
  for (const auto& p : report["patches"])
    EXPECT_NE(plan.find(fmt::format(">{:.1f} m²<", p["area_m2"].get<double>())), std::string::npos)
        << "patch " << p["id"] << ": areas under 10 m² keep one decimal";
  EXPECT_EQ(report["plan"]["labels_left_out"], 0);
  EXPECT_TRUE(fs::exists(out / "curvature.svg"));
  const std::string elevations = readRegularFile(out / "elevations.svg", 1 << 26, "elevations");
  EXPECT_NE(elevations.find("<g id=\"section-a\""), std::string::npos);
  EXPECT_NE(elevations.find("<circle cx="), std::string::npos) << "no lamella cut by a section";
  const std::string html = readRegularFile(out / "report.html", 1 << 28, "report.html");
  EXPECT_NE(html.find("<svg id=\"elevations\""), std::string::npos);
  EXPECT_NE(html.find("<svg id=\"curvature\""), std::string::npos);
  for (const char* preview :
       {"preview/plan.png", "preview/curvature.png", "preview/elevations.png"})
    EXPECT_TRUE(fs::exists(out / preview)) << preview;
  EXPECT_FALSE(fs::exists(out / "patch_000" / "grid.obj"));  // previews were not asked for
  // Fabrication: 4 patches x 8 members, the 4 shared sides cut once each (one lamella carrying the
  // holes of both patches).
  EXPECT_EQ(report["fabrication"]["lamellae"], 4 * 8 - 4);
  fs::remove_all(out);
}

// Issue 40: two given patches over the same surface were designed, cut and weighed twice. Sides
// that cross are found before the designs, a patch inside another after them; either way the run
// is bad input naming both patches, and no run folder appears.
TEST(PipelineMultiPatch, OverlappingGivenPatchesAreBadInputNamingBoth) {
  const auto scene = [](const std::string& second) {
    return parseScene(nlohmann::json::parse(R"({"name": "overlap",
      "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1.0,
                  "sigma": 1.5}, "edge_length_m": 0.4},
      "patching": {"patches": [[[-3,-3,0],[0,-3,0],[0,0,1],[-3,0,0]], )" +
                                            second + R"(]},
      "grid": {"map_resolution": 30, "members_per_family": 4},
      "lamella": {"width_m": 0.05, "thickness_m": 0.005},
      "simulation": {"enabled": false}, "outputs": ["report"]})"),
                      "/virtual/overlap.json");
  };
  const fs::path out = fs::temp_directory_path() / ("egg_overlap_" + std::to_string(::getpid()));
  PipelineOptions options;
  options.outDir = out;
  const auto messageOf = [&](const Scene& s) -> std::string {
    try {
      runPipeline(s, options);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string crossing = messageOf(scene("[[-2,-2,0],[1,-2,0],[1,1,0],[-2,1,0]]"));
  EXPECT_NE(crossing.find("patching.patches[0] and patches[1] overlap: their sides"),
            std::string::npos)
      << crossing;
  EXPECT_NE(crossing.find(" cross at ("), std::string::npos) << crossing;
  const std::string inside =
      messageOf(scene("[[-2.5,-2.5,0.1],[-0.5,-2.5,0.2],[-0.5,-0.5,0.9],[-2.5,-0.5,0.2]]"));
  EXPECT_NE(inside.find("patching.patches[0] and patches[1] overlap: they share"),
            std::string::npos)
      << inside;
  EXPECT_FALSE(fs::exists(out));
  // Neighbours that share a side are no overlap.
  EXPECT_EQ(messageOf(scene("[[0,-3,0],[3,-3,0],[3,0,0],[0,0,1]]")), "no error");
  fs::remove_all(out);
}

TEST(PipelineMultiPatch, SlowResultsDoNotDependOnTheThreadCount) {
  // With the simulation: patch by patch (patches in parallel) and joined (two assembly threads),
  // both limited by iterations, not by a clock, so the numbers are the same bit for bit.
  Scene scene = twoByTwoScene(R"(["report"])");
  const auto runWith = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    PipelineOptions options;
    options.outDir = scratch("egg_pipeline_threads_" + std::to_string(threads));
    auto report = runPipeline(scene, options).report;
    fs::remove_all(options.outDir);
    return report;
  };
  const auto one = runWith(1), two = runWith(2);
  ASSERT_EQ(one["patches"].size(), two["patches"].size());
  for (size_t i = 0; i < one["patches"].size(); ++i)
    for (const char* key :
         {"area_m2", "eta_u", "eta_v", "alpha_bar_rad", "max_notch_m", "members_u", "members_v"})
      EXPECT_EQ(one["patches"][i][key], two["patches"][i][key]) << i << " " << key;
  const auto &simOne = one["simulation"], &simTwo = two["simulation"];
  ASSERT_TRUE(simOne["ran"].get<bool>());
  for (const char* key : {"rmse_m", "max_error_m", "iterations", "converged"}) {
    EXPECT_EQ(simOne[key], simTwo[key]) << key;
    EXPECT_EQ(simOne["joined"][key], simTwo["joined"][key]) << "joined " << key;
  }
  for (size_t i = 0; i < simOne["patches"].size(); ++i)
    EXPECT_EQ(simOne["patches"][i]["energy_j"], simTwo["patches"][i]["energy_j"]) << i;
}

TEST(PipelineMultiPatch, OutputsDecideWhatRuns) {
  // Nothing asked for: no stage runs, no folder appears.
  const fs::path out = scratch("egg_pipeline_outputs");
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult none = runPipeline(twoByTwoScene("[]"), options);
  EXPECT_TRUE(none.nothingRequested);
  for (const auto& [stage, entry] : none.report["stages"].items())
    EXPECT_FALSE(entry["ran"].get<bool>()) << stage;
  EXPECT_FALSE(fs::exists(out));
  // The plan alone: patching and design run, the grid and the simulation do not.
  const PipelineResult plan = runPipeline(twoByTwoScene(R"(["plan"])"), options);
  EXPECT_TRUE(plan.report["stages"]["design"]["ran"].get<bool>());
  EXPECT_FALSE(plan.report["stages"]["grid"]["ran"].get<bool>());
  EXPECT_FALSE(plan.report["stages"]["simulation"]["ran"].get<bool>());
  EXPECT_TRUE(fs::exists(out / "patches.json"));
  EXPECT_FALSE(fs::exists(out / "report.json"));
  fs::remove_all(out);
}

TEST(PipelineMultiPatch, AnInfeasiblePatchDoesNotStopTheOthers) {
  Scene scene = twoByTwoScene(R"(["report"])");
  scene.simulation.enabled = false;
  // Patch 3's corner 2 pulled inwards past its diagonal: the patch is not convex (criterion iv).
  scene.patching.corners.push_back({1.0, 1.0, 0.0});
  scene.patching.quads[3][2] = static_cast<int>(scene.patching.corners.size()) - 1;
  const fs::path out = scratch("egg_pipeline_one_bad");
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(scene, options);
  ASSERT_EQ(result.report["patches"].size(), 4u);
  int feasible = 0;
  for (const auto& p : result.report["patches"]) feasible += p["feasible"].get<bool>();
  EXPECT_EQ(feasible, 3);
  EXPECT_EQ(result.failures.size(), 1u);
  EXPECT_TRUE(fs::exists(out / "patch_000" / "grid.json"));
  fs::remove_all(out);
}

TEST(PipelineMultiPatch, PartsThatCannotBeCutAreAFailureWithItsReport) {
  // A sheet narrower than a lamella (50 mm): the grid is fine, its parts cannot be cut. The run
  // fails (exit 1) and says why; the report is written, the cut files are not.
  Scene scene = twoByTwoScene(R"(["report", "cut_files"])");
  scene.simulation.enabled = false;
  scene.fabrication.options.sheetMm = {2500.0, 40.0};
  const fs::path out = scratch("egg_pipeline_uncuttable");
  PipelineOptions options;
  options.outDir = out;
  const PipelineResult result = runPipeline(scene, options);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_EQ(result.failures[0].rfind("fabrication: ", 0), 0u) << result.failures[0];
  EXPECT_FALSE(result.report["stages"]["fabrication"]["ran"].get<bool>());
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_FALSE(fs::exists(out / "cut"));
  fs::remove_all(out);
}

}  // namespace
}  // namespace egg::pipeline
