#include "pipeline/acceptance.hpp"

#include <gtest/gtest.h>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// A finished report of a 20 m dome whose grid has collapsed (the case of issue 36: RMSE 1.73 m,
// max 3.90 m, sag 3.97 m on a 4.4 m rise), one patch, no fabrication.
json collapsedDome() {
  return {{"surface", {{"bbox_m", {20.0, 19.0, 4.4}}}},
          {"simulation",
           {{"ran", true},
            {"gravity", true},
            {"rmse_m", 1.73},
            {"max_error_m", 3.90},
            {"patches", {{{"max_sag_m", 3.97}}}},
            {"joined", {{"ran", false}, {"skipped_reason", "one patch"}}}}},
          {"fabrication", {{"ran", false}, {"skipped_reason", "the scene disables it"}}}};
}

const Criterion& find(const Verdict& v, const std::string& name) {
  for (const Criterion& c : v.criteria)
    if (c.name == name) return c;
  throw std::runtime_error("no criterion " + name);
}

TEST(Acceptance, ACollapsedDomeFailsNamingEachCriterionWithValueAndLimit) {
  const Verdict v = judgeRun(collapsedDome(), AcceptanceLimits{});
  EXPECT_DOUBLE_EQ(v.spanM, 20.0);  // the longer plan side
  EXPECT_FALSE(v.passed());
  EXPECT_NEAR(find(v, "patch_by_patch_max_error").limit, 20.0 / 50.0, 1e-12);
  EXPECT_FALSE(find(v, "patch_by_patch_max_error").passed);
  EXPECT_DOUBLE_EQ(find(v, "patch_by_patch_rmse").value, 1.73);
  EXPECT_FALSE(find(v, "max_sag").passed);
  const auto failures = v.failures();
  ASSERT_EQ(failures.size(), 3u);
  EXPECT_NE(failures[1].find("patch_by_patch_max_error"), std::string::npos) << failures[1];
  EXPECT_NE(failures[1].find("3.9 m"), std::string::npos) << failures[1];
  EXPECT_NE(failures[1].find("0.4 m"), std::string::npos) << failures[1];
}

TEST(Acceptance, FiguresTheRunDidNotComputeAreNotEvaluatedWithTheReason) {
  const Verdict v = judgeRun(collapsedDome(), AcceptanceLimits{});
  const Criterion& joined = find(v, "joined_rmse");
  EXPECT_FALSE(joined.evaluated);
  EXPECT_TRUE(joined.passed);
  EXPECT_NE(joined.notEvaluatedReason.find("one patch"), std::string::npos);
  EXPECT_NE(find(v, "max_stress_ratio").notEvaluatedReason.find("disables"), std::string::npos);
}

// Where Newton stopped short there is no equilibrium to measure: the run fails on convergence
// (the simulation stage's own failure), not on a shape the grid would never stand in.
TEST(Acceptance, AnUnconvergedSimulationLeavesTheShapeUnjudged) {
  json report = collapsedDome();
  report["simulation"]["converged"] = false;
  const Verdict v = judgeRun(report, AcceptanceLimits{});
  const Criterion& max = find(v, "patch_by_patch_max_error");
  EXPECT_FALSE(max.evaluated);
  EXPECT_NE(max.notEvaluatedReason.find("did not converge"), std::string::npos);
  EXPECT_FALSE(find(v, "max_sag").evaluated);
  report["simulation"]["converged"] = true;
  report["simulation"]["joined"] = {
      {"ran", true}, {"converged", false}, {"rmse_m", 9.0}, {"max_error_m", 9.0}};
  const Verdict joinedVerdict = judgeRun(report, AcceptanceLimits{});
  const Criterion& joined = find(joinedVerdict, "joined_max_error");
  EXPECT_FALSE(joined.evaluated);
  EXPECT_NE(joined.notEvaluatedReason.find("joined simulation did not converge"),
            std::string::npos);
}

TEST(Acceptance, AStandingGridPassesAndLimitsComeFromTheScene) {
  json report = collapsedDome();
  report["simulation"]["rmse_m"] = 0.05;
  report["simulation"]["max_error_m"] = 0.3;
  report["simulation"]["patches"] = {{{"max_sag_m", 0.05}}};
  report["simulation"]["joined"] = {{"ran", true}, {"rmse_m", 0.06}, {"max_error_m", 0.39}};
  report["fabrication"] = {{"ran", true}, {"max_stress_ratio", 0.8}};
  EXPECT_TRUE(judgeRun(report, AcceptanceLimits{}).passed());
  AcceptanceLimits strict;
  strict.maxStressRatio = 0.5;  // a design check with k_mod / gamma_M
  const Verdict v = judgeRun(report, strict);
  EXPECT_FALSE(v.passed());
  ASSERT_EQ(v.failures().size(), 1u);
  EXPECT_NE(v.failures()[0].find("max_stress_ratio"), std::string::npos);
}

TEST(Acceptance, TheSummarySaysPassedOnlyWithoutFailures) {
  json report = collapsedDome();
  report["scene"] = {{"name", "dome"}};
  report["acceptance"] = verdictJson(judgeRun(report, AcceptanceLimits{}));
  report["failures"] = judgeRun(report, AcceptanceLimits{}).failures();
  const std::string failed = runSummary(report, "/tmp/x", 1.0);
  EXPECT_NE(failed.find("dome FAILED (3 failures)"), std::string::npos) << failed;
  EXPECT_EQ(failed.find("passed"), std::string::npos) << failed;
  report["failures"] = json::array();
  EXPECT_NE(runSummary(report, "/tmp/x", 1.0).find("dome passed"), std::string::npos);
}

}  // namespace
}  // namespace egg::pipeline
