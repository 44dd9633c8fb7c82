// The joined simulation of a multi-patch grid: two patches of the bump sharing a side, their
// boundary lamellas bolted face to face at the member ends propagation made coincide.
#include "pipeline/joined_simulation.hpp"

#include "pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

// samples/scenes/bump_1x2.json: two 3 x 6 m patches of the bump side by side, no self-weight.
Scene twoPatchScene(bool join) {
  Scene scene = loadScene(fs::path(EGG_SOURCE_DIR) / "samples/scenes/bump_1x2.json");
  scene.simulation.joinPatches = join;
  return scene;
}

nlohmann::json run(const Scene& scene, const std::string& name) {
  PipelineOptions options;
  options.outDir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  auto result = runPipeline(scene, options);
  fs::remove_all(options.outDir);
  EXPECT_TRUE(result.failures.empty()) << nlohmann::json(result.failures).dump(1);
  return result.report;
}

TEST(JoinedStage, SlowTwoPatchesSharingASideConvergeBoltedTogether) {
  const auto report = run(twoPatchScene(true), "egg_joined");
  const auto& sim = report["simulation"];
  ASSERT_TRUE(sim["converged"].get<bool>());
  const auto& joined = sim["joined"];
  ASSERT_TRUE(joined["ran"].get<bool>()) << joined.dump(1);
  EXPECT_TRUE(joined["converged"].get<bool>()) << joined.dump(1);
  // The shared side's two boundary lamellas are bolted at all five member ends (the corners and
  // the three propagated members); one patch swaps its layers so that they lie face to face.
  EXPECT_EQ(joined["sides_joined"], 1);
  EXPECT_EQ(joined["bolts"], 5);
  EXPECT_EQ(joined["patches_swapped"], 1);
  EXPECT_EQ(joined["sides_skipped_same_layer"], 0);
  EXPECT_LE(report["propagation"]["c0_max_gap_m"].get<double>(), 1e-6);
  // Both errors are reported: the joined structure's and the pooled patch-by-patch one.
  EXPECT_GT(joined["rmse_m"].get<double>(), 0.0);
  EXPECT_LT(joined["rmse_m"].get<double>(), 0.05);
  EXPECT_GE(joined["max_error_m"].get<double>(), joined["rmse_m"].get<double>());
  // Started from the converged patch-by-patch equilibria and stopped by its Newton decrement.
  EXPECT_EQ(joined["start"], "patch_by_patch_equilibria");
  EXPECT_EQ(joined["status"], "converged");
  EXPECT_LT(joined["decrement_j"].get<double>(), 1e-6 * joined["energy_j"].get<double>());
  EXPECT_EQ(sim["patch_by_patch"]["rmse_m"], sim["rmse_m"]);
  EXPECT_EQ(sim["patch_by_patch"]["max_error_m"], sim["max_error_m"]);
  EXPECT_EQ(sim["patch_by_patch"]["iterations"], sim["iterations"]);
  EXPECT_TRUE(sim["patch_by_patch"]["converged"].get<bool>());
  EXPECT_GT(sim["patch_by_patch"]["seconds"].get<double>(), 0.0);
  EXPECT_GT(joined["seconds"].get<double>(), 0.0);
}

// Self-weight on two patches: bolts tightened at the weightless equilibria (the scene's default)
// carry it with less sag than loose ones, patch by patch and joined.
TEST(JoinedStage, SlowFastenedBoltsSagLessThanLooseOnesOnTwoPatches) {
  double sag[2] = {0.0, 0.0};
  double joinedRmse[2] = {0.0, 0.0};
  for (const bool fastened : {false, true}) {
    Scene scene = twoPatchScene(true);
    scene.simulation.rods.model.gravity = true;
    scene.simulation.rods.fastenBoltsUnderLoad = fastened;
    // 20 x 5 mm strips on an 8 m grid sag by span / 125 loose: past the default acceptance limits
    // (docs/acceptance.md), which this test is not about.
    scene.acceptance.maxSagOverSpan = 0.05;
    scene.acceptance.rmseOverSpan = 0.05;
    const auto report = run(scene, fastened ? "egg_joined_fastened" : "egg_joined_loose");
    const auto& sim = report["simulation"];
    EXPECT_EQ(sim["bolts_fastened_under_load"].get<bool>(), fastened);
    ASSERT_EQ(sim["patches"].size(), 2u);
    for (const auto& patch : sim["patches"])
      sag[fastened] = std::max(sag[fastened], patch["max_sag_m"].get<double>());
    ASSERT_TRUE(sim["joined"]["ran"].get<bool>()) << sim["joined"].dump(1);
    joinedRmse[fastened] = sim["joined"]["rmse_m"].get<double>();
  }
  EXPECT_GT(sag[true], 0.0);
  // Measured 3.3 against 6.3 cm.
  EXPECT_LT(sag[true], 0.7 * sag[false]) << sag[true] << " fastened, " << sag[false] << " loose";
  EXPECT_LT(joinedRmse[true], joinedRmse[false]);
}

TEST(JoinedStage, APatchThatCollapsesHeldAllRoundSkipsTheJoinedRun) {
  std::vector<SolvedPatch> patches(3);
  for (int i = 0; i < 3; ++i) {
    patches[i].id = i;
    patches[i].simulation.emplace();
    patches[i].simulation->deployed.solver.status = rods::SolverStatus::Converged;
  }
  EXPECT_EQ(collapsedWhileHeld(patches), "");
  patches[2].simulation->deployed.solver.status =
      rods::SolverStatus::IterationLimit;  // slow is not collapsed
  EXPECT_EQ(collapsedWhileHeld(patches), "");
  patches[1].simulation->deployed.solver.status = rods::SolverStatus::Collapsed;
  const std::string reason = collapsedWhileHeld(patches);
  EXPECT_NE(reason.find("patch 1 collapses under its own weight"), std::string::npos) << reason;
  patches[1].simulation.reset();  // no simulation (a failure of its own): nothing to say
  EXPECT_EQ(collapsedWhileHeld(patches), "");
}

TEST(JoinedStage, SlowTheSceneCanKeepPatchesApart) {
  const auto report = run(twoPatchScene(false), "egg_unjoined");
  EXPECT_FALSE(report["simulation"]["joined"]["ran"].get<bool>());
  EXPECT_NE(
      report["simulation"]["joined"]["skipped_reason"].get<std::string>().find("join_patches"),
      std::string::npos);
}

}  // namespace
}  // namespace egg::pipeline
