// egg bench layout: every edge length its option allows meshes a bump that the bench's 2 x 2
// layout lies on (at 0.03 m its corners were 0.13 m off the finer mesh, and the message named the
// bench's internal scene file).
#include "apps/egg/commands.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace egg::app {
namespace {

TEST(LayoutBench, TheFinestEdgeLengthOfItsRangeRuns) {
  std::vector<std::string> args = {"egg",  "bench",     "layout", "--edge-length",
                                   "0.03", "--repeats", "1",      "--json"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = runCli(static_cast<int>(argv.size()), argv.data());
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_EQ(code, kExitOk) << err;
  EXPECT_EQ(err.find("bench_layout.json"), std::string::npos) << err;
  const auto figures = nlohmann::json::parse(out);
  EXPECT_EQ(figures["patches"], 4);
  EXPECT_GT(figures["patch_vertices_total"].get<int>(), 4 * 10000) << "a 0.03 m mesh of 6 x 6 m";
}

}  // namespace
}  // namespace egg::app
