#include "pipeline/report.hpp"

#include <gtest/gtest.h>

namespace egg::pipeline {
namespace {

TEST(RunReport, HasEveryRequiredKeyAndExplainsStagesThatDidNotRun) {
  RunReport report(nlohmann::json{{"name", "t"}});
  report.stageRan("surface", 0.5);
  report.section("surface") = {{"vertices", 4}};
  report.stageSkipped("simulation", "the scene disables it");
  const auto doc = report.finish(1.25);
  for (const char* key : {"scene", "units", "surface", "stages", "patches", "coverage",
                          "propagation", "simulation", "fabrication", "timings"}) {
    EXPECT_TRUE(doc.contains(key)) << key;
  }
  EXPECT_TRUE(doc["stages"]["surface"]["ran"].get<bool>());
  EXPECT_DOUBLE_EQ(doc["stages"]["surface"]["seconds"].get<double>(), 0.5);
  EXPECT_FALSE(doc["simulation"]["ran"].get<bool>());
  EXPECT_EQ(doc["simulation"]["skipped_reason"], "the scene disables it");
  EXPECT_FALSE(doc["stages"]["fabrication"]["ran"].get<bool>());
  EXPECT_TRUE(doc["patches"].is_array());
  EXPECT_DOUBLE_EQ(doc["timings"]["total_s"].get<double>(), 1.25);
  EXPECT_EQ(doc["surface"]["vertices"], 4);
}

}  // namespace
}  // namespace egg::pipeline
