#include "apps/commands/report.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() / ("egg_report_test_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
  }
  void TearDown() override { fs::remove_all(root); }
  fs::path root;
};

TEST(RunReport, HasEveryRequiredKeyAndExplainsStagesThatDidNotRun) {
  RunReport report(nlohmann::json{{"name", "t"}});
  report.stageRan("surface", 0.5);
  report.section("surface") = {{"vertices", 4}};
  report.stageSkipped("simulation", "the scene disables it");
  const auto doc = report.finish(1.25);
  for (const char* key : {"scene", "units", "surface", "stages", "patches", "coverage", "propagation", "simulation",
                          "fabrication", "timings"}) {
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

TEST_F(TempDir, StagedDirectoryAppearsOnlyOnCommitAndReplacesTheOldRun) {
  const fs::path out = root / "run";
  {
    StagedDirectory staged(out);
    writeFileAtomically(staged.staging() / "report.json", "{}");
    EXPECT_FALSE(fs::exists(out));
    staged.commit();
  }
  EXPECT_TRUE(fs::exists(out / "report.json"));
  {
    StagedDirectory staged(out);
    writeFileAtomically(staged.staging() / "other.txt", "x");
    staged.commit();
  }
  EXPECT_FALSE(fs::exists(out / "report.json"));  // replaced whole
  EXPECT_TRUE(fs::exists(out / "other.txt"));
  {
    StagedDirectory abandoned(out);
    writeFileAtomically(abandoned.staging() / "half.txt", "x");
  }  // no commit: as if an exception had been thrown
  EXPECT_TRUE(fs::exists(out / "other.txt"));
  EXPECT_FALSE(fs::exists(out / "half.txt"));
  int entries = 0;
  for (const auto& e : fs::directory_iterator(root)) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 1) << "no staging folder left behind";
}

TEST_F(TempDir, RefusesToReplaceAFolderThatIsNotARunFolder) {
  const fs::path precious = root / "precious";
  fs::create_directories(precious);
  writeFileAtomically(precious / "thesis.tex", "years of work");
  EXPECT_THROW(StagedDirectory staged(precious), InvalidInput);
  EXPECT_EQ(readAll(precious / "thesis.tex"), "years of work");
  // An empty folder and an earlier run folder are fine.
  fs::create_directories(root / "empty");
  EXPECT_NO_THROW({
    StagedDirectory staged(root / "empty");
    staged.commit();
  });
  EXPECT_TRUE(fs::exists(root / "empty" / kRunMarker));
  EXPECT_NO_THROW(StagedDirectory again(root / "empty"));
}

}  // namespace
}  // namespace egg::app
