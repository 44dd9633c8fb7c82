// egg bench sim --joined: the joined structure of a scene through the real pipeline, one row per
// thread count, each with its solve's phases; the same equilibrium at every thread count.
#include "apps/bench/joined_bench.hpp"

#include "apps/egg/commands.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

TEST(JoinedSimBench, TwoPatchesBoltedGiveOneRowPerThreadCountWithItsPhases) {
  // Two patches of the bump sharing a side (the scene of tests/pipeline/test_joined_simulation).
  const fs::path scene = fs::path(EGG_SOURCE_DIR) / "samples/scenes/bump_1x2.json";
  JoinedSimBenchArgs args;
  args.samples = {scene.string()};
  args.threadCounts = {1, 2};
  args.json = true;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = runJoinedSimBench(args);
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string table = testing::internal::GetCapturedStderr();
  ASSERT_EQ(code, kExitOk) << table;
  const auto rows = nlohmann::json::parse(out);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    const auto& joined = row["joined"];
    ASSERT_TRUE(joined["converged"].get<bool>()) << joined.dump(1);
    EXPECT_GT(joined["unknowns"].get<int>(), 0);
    EXPECT_GE(joined["factorisations"].get<int>(), joined["iterations"].get<int>());
    EXPECT_GE(joined["symbolic_analyses"].get<int>(), 1);
    double phases = 0.0;
    for (const auto& [name, seconds] : joined["phases_s"].items()) phases += seconds.get<double>();
    EXPECT_GT(phases, 0.0);
    EXPECT_LE(phases, joined["seconds"].get<double>() * 1.01 + 1e-3);
  }
  // The stencils are reduced in a fixed order: the thread count does not change the result.
  EXPECT_EQ(rows[0]["joined"]["iterations"], rows[1]["joined"]["iterations"]);
  EXPECT_DOUBLE_EQ(rows[0]["joined"]["rmse_m"].get<double>(),
                   rows[1]["joined"]["rmse_m"].get<double>());
}

}  // namespace
}  // namespace egg::app
