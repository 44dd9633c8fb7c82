#include "apps/bench/stress_suite.hpp"

#include "apps/egg/commands.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>
#include <csignal>

#include <cstdio>
#include <filesystem>
#include <set>
#include <thread>

namespace egg::app {
namespace {
namespace fs = std::filesystem;

fs::path scratchRoot() {
  return fs::temp_directory_path() / ("egg-test-stress-" + std::to_string(::getpid()));
}

fs::path scratch(const std::string& name) {
  const fs::path d = scratchRoot() / name;
  fs::create_directories(d);
  return d;
}

// The suites' folders of every test, removed when the tests end.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(scratchRoot(), ignored);
  }
};
[[maybe_unused]] ::testing::Environment* const kCleanup =
    ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

// The issue's list (issue 18): every named class of stiff and extreme case is in the suite.
TEST(StressSuite, SuiteHoldsEveryClassOfTheIssue) {
  std::set<std::string> kinds, names;
  for (const auto& c : pipelineStressCases()) {
    kinds.insert(c.kind);
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case " << c.name;
  }
  for (const char* k : {"width_thickness", "youngs_modulus", "scale", "nearly_flat", "sharp_k_peak",
                        "near_collapsed_quads", "sliver_triangles", "holes", "disconnected",
                        "non_manifold", "million_faces", "deployment"})
    EXPECT_TRUE(kinds.count(k)) << k;
  // Fixed: the same cases, in the same order, every call.
  const auto a = pipelineStressCases(), b = pipelineStressCases();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].scene, b[i].scene);
}

TEST(StressSuite, HangingChildIsKilledAndReportedAsTimeout) {
  const ChildOutcome o = runChild(
      [] {
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        return 0;
      },
      0.3, scratch("hang") / "log.txt");
  EXPECT_TRUE(o.timedOut);
  EXPECT_LT(o.seconds, 5.0);
  PipelineStressCase c;
  c.name = "hang";
  c.timeLimitS = 0.3;
  const PipelineStressRow row = classify(c, o, nlohmann::json());
  EXPECT_FALSE(row.ok);
  EXPECT_NE(row.result.find("TIMEOUT"), std::string::npos);
}

TEST(StressSuite, CrashingChildIsReportedAsCrash) {
  const ChildOutcome o = runChild(
      [] {
        // The default action, so that AddressSanitizer's handler (.ci/run's second build) does not
        // turn the signal into an exit code or an abort.
        std::signal(SIGSEGV, SIG_DFL);
        ::raise(SIGSEGV);
        return 0;
      },
      10.0, scratch("crash") / "log.txt");
  EXPECT_FALSE(o.timedOut);
  EXPECT_EQ(o.signal, SIGSEGV);
  PipelineStressCase c;
  c.name = "crash";
  const PipelineStressRow row = classify(c, o, nlohmann::json());
  EXPECT_FALSE(row.ok);
  EXPECT_NE(row.result.find("CRASH"), std::string::npos);
}

TEST(StressSuite, NonFiniteOutputOrReportIsAFailure) {
  const ChildOutcome o = runChild(
      [] {
        std::printf("rmse %f\n", std::nan(""));
        return 0;
      },
      10.0, scratch("nan") / "log.txt");
  EXPECT_EQ(o.exitCode, 0);
  PipelineStressCase c;
  c.name = "nan";
  EXPECT_FALSE(classify(c, o, nlohmann::json()).ok);
  // A clean exit whose report has a non-finite error (json writes NaN as null) fails too.
  ChildOutcome clean;
  clean.exitCode = 0;
  nlohmann::json report = {{"simulation", {{"rmse_m", nullptr}}}};
  EXPECT_FALSE(classify(c, clean, report).ok);
  report["simulation"]["rmse_m"] = 0.01;
  EXPECT_TRUE(classify(c, clean, report).ok);
  // Exit non-zero without any message is not a stated reason.
  ChildOutcome silent;
  silent.exitCode = 2;
  EXPECT_FALSE(classify(c, silent, nlohmann::json()).ok);
  // Memory is the child's own: a child that touches 200 MB reports at least that.
  const ChildOutcome big = runChild(
      [] {
        std::vector<char> v(200u << 20, 1);
        return v[12345] == 1 ? 0 : 1;
      },
      10.0, scratch("mem") / "log.txt");
  EXPECT_GT(big.peakRssMb, 190.0);
}

// The real pipeline on the suite's non-manifold mesh: a typed error naming the problem, not a
// crash.
TEST(StressSuite, NonManifoldMeshGivesAReasonNotACrash) {
  for (const auto& c : pipelineStressCases()) {
    if (c.kind != "non_manifold" && c.kind != "disconnected") continue;
    const EggCommand inProcess = [](const std::vector<std::string>& a) {
      std::vector<std::string> all{"egg"};
      all.insert(all.end(), a.begin(), a.end());
      std::vector<char*> argv;
      for (auto& s : all) argv.push_back(s.data());
      return runCli(static_cast<int>(argv.size()), argv.data());
    };
    const PipelineStressRow row = runPipelineStressCase(c, inProcess, scratch("bad"));
    EXPECT_TRUE(row.ok) << c.name << ": " << row.result;
    EXPECT_EQ(row.result.find("CRASH"), std::string::npos) << row.result;
    EXPECT_EQ(row.result.find("TIMEOUT"), std::string::npos) << row.result;
  }
}

}  // namespace
}  // namespace egg::app
