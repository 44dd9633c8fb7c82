// egg bench fem: one row per scene with the FE model's size and whether ccx ran on it; the
// two-patch bump solved, and the same scene above its element limit written but not solved.
#include "apps/bench/fem_bench.hpp"

#include "apps/egg/commands.hpp"
#include "verification/ccx_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

nlohmann::json bench(int maxFeElements, int* code) {
  FemBenchArgs args;
  args.scenes = {(fs::path(EGG_SOURCE_DIR) / "samples/scenes/bump_1x2.json").string()};
  args.maxFeElements = maxFeElements;
  args.json = true;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  *code = runFemBench(args);
  const std::string out = testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  return nlohmann::json::parse(out);
}

TEST(FemBench, AboveTheElementLimitTheRowSaysNotSolved) {
  if (verification::findCcx().empty()) GTEST_SKIP() << "ccx is not installed";
  int code = -1;
  const auto rows = bench(50, &code);
  EXPECT_EQ(code, kExitOk);
  ASSERT_EQ(rows.size(), 1u);
  const auto& v = rows[0]["verification"];
  EXPECT_FALSE(v["solved"].get<bool>());
  EXPECT_GT(v["model"]["elements"].get<int>(), 50);
  EXPECT_EQ(rows[0]["ccx_seconds"].get<double>(), 0.0);
  EXPECT_GT(rows[0]["stage_seconds"].get<double>(), 0.0);
}

TEST(FemBench, SlowTheTwoPatchBumpIsSolvedWithItsCcxTime) {
  if (verification::findCcx().empty()) GTEST_SKIP() << "ccx is not installed";
  int code = -1;
  const auto rows = bench(0, &code);
  EXPECT_EQ(code, kExitOk);
  ASSERT_EQ(rows.size(), 1u);
  const auto& v = rows[0]["verification"];
  EXPECT_TRUE(v["solved"].get<bool>());
  EXPECT_GT(rows[0]["ccx_seconds"].get<double>(), 0.0);
  EXPECT_LE(rows[0]["ccx_seconds"].get<double>(), rows[0]["stage_seconds"].get<double>());
  EXPECT_LE(v["max_equilibrium_residual"].get<double>(), 1e-6);
}

}  // namespace
}  // namespace egg::app
