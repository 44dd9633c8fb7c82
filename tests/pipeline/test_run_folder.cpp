#include "pipeline/run_folder.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace egg::pipeline {
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

pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

void makeRun(const fs::path& out, const std::string& content) {
  StagedDirectory staged(out);
  writeFileAtomically(staged.staging() / "report.json", content);
  fs::create_directories(staged.staging() / "patch_000");
  writeFileAtomically(staged.staging() / "patch_000" / "grid.json", content);
  staged.commit();
}

size_t entries(const fs::path& folder) {
  return static_cast<size_t>(
      std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

// Issue 17: --out onto an earlier run folder deleted everything in it, the user's files and the
// run's own scene included (`egg run run/scene.json --out run`).
TEST_F(TempDir, AnEarlierRunHoldingFilesTheToolDidNotWriteIsNeverReplaced) {
  const fs::path out = root / "run";
  makeRun(out, "{}");
  EXPECT_EQ(runFolderReplaceProblem(out), "");
  EXPECT_NO_THROW(makeRun(out, "{\"again\": 1}"));  // a pure earlier run is replaced
  writeFileAtomically(out / "scene.json", "{\"surface\": {}}");
  try {
    StagedDirectory staged(out);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readAll(out / "scene.json"), "{\"surface\": {}}");
  fs::remove(out / "scene.json");
  // An edited result is the user's now.
  writeFileAtomically(out / "patch_000" / "grid.json", "{\"edited\": true}");
  EXPECT_THROW(StagedDirectory staged(out), InvalidInput);
  EXPECT_EQ(readAll(out / "patch_000" / "grid.json"), "{\"edited\": true}");
}

// Issue 40: an empty folder made in an earlier run folder was deleted with it, silently. The run's
// own folders are in its marker; an empty one of the run's (preview/ with no figure) is still its.
TEST_F(TempDir, AnEmptyFolderSomeoneMadeInTheRunFolderIsTheirs) {
  const fs::path out = root / "run";
  {
    StagedDirectory staged(out);
    fs::create_directories(staged.staging() / "preview");  // empty, but the run's
    writeFileAtomically(staged.staging() / "report.json", "{}");
    staged.commit();
  }
  EXPECT_EQ(runFolderReplaceProblem(out), "");
  fs::create_directories(out / "my notes");
  const std::string problem = runFolderReplaceProblem(out);
  EXPECT_NE(problem.find("holds the folder my notes"), std::string::npos) << problem;
  EXPECT_THROW(StagedDirectory staged(out), InvalidInput);
  EXPECT_TRUE(fs::is_directory(out / "my notes"));
  fs::remove(out / "my notes");
  EXPECT_NO_THROW(makeRun(out, "{}"));
}

TEST_F(TempDir, AFileAddedDuringTheRunStopsTheCommit) {
  const fs::path out = root / "run";
  makeRun(out, "{}");
  StagedDirectory staged(out);
  writeFileAtomically(staged.staging() / "report.json", "new");
  writeFileAtomically(out / "notes.txt", "added while the run was busy");
  EXPECT_THROW(staged.commit(), InvalidInput);
  EXPECT_EQ(readAll(out / "notes.txt"), "added while the run was busy");
}

TEST_F(TempDir, AMarkerWithoutTheFileListIsNotEnough) {
  const fs::path out = root / "old";
  fs::create_directories(out);
  writeFileAtomically(out / kRunMarker,
                      "eggshell run folder: replaced whole by the next egg run\n");
  writeFileAtomically(out / "report.json", "{}");
  EXPECT_THROW(StagedDirectory staged(out), InvalidInput);
  EXPECT_TRUE(fs::exists(out / "report.json"));
}

// Issue 17: a name "\u0000" made the run folder "out/." and deleted everything in out/.
TEST_F(TempDir, TargetNamesMustBePortableAndNeverNameTheParent) {
  writeFileAtomically(root / "user.txt", "precious");
  EXPECT_THROW(StagedDirectory staged(root / std::string(1, '\0')), InvalidInput);
  EXPECT_THROW(StagedDirectory staged(root / "."), InvalidInput);  // root itself: not a run folder
  EXPECT_THROW(StagedDirectory staged(root / "a\nb"), InvalidInput);
  EXPECT_THROW(StagedDirectory staged(fs::path("/")), InvalidInput);
  // 238-255 characters failed late (the staging name did not fit NAME_MAX): now a clear error
  // first.
  try {
    StagedDirectory staged(root / std::string(240, 'n'));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("too long"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW({
    StagedDirectory staged(root / std::string(kMaxRunFolderName, 'n'));
    staged.commit();
  });
  fs::create_symlink(root / std::string(kMaxRunFolderName, 'n'), root / "link");
  EXPECT_THROW(StagedDirectory staged(root / "link"), InvalidInput);
  EXPECT_EQ(readAll(root / "user.txt"), "precious");
}

// Issue 17: a kill between the two renames of the commit left the earlier run only in
// .NAME.previous-*; staging folders of killed runs stayed forever.
TEST_F(TempDir, InterruptedRunsAreRecoveredAndTheirLeftoversCleaned) {
  const fs::path out = root / "run";
  makeRun(out, "earlier");
  const pid_t dead = deadPid();
  // The state a kill after the first rename leaves: no target, the earlier run aside.
  const fs::path aside = root / (".run.previous-" + std::to_string(dead) + "-abcdefgh");
  fs::rename(out, aside);
  // And a staging folder of a killed run, one of a live run, and a user's folder that looks alike.
  const fs::path killed = root / (".run.staging-" + std::to_string(dead) + "-abcdefgh");
  fs::create_directories(killed);
  writeFileAtomically(killed / kRunMarker, "eggshell run in progress (staging folder)\n");
  writeFileAtomically(killed / "report.json", "half");
  const fs::path live = root / (".run.staging-" + std::to_string(::getppid()) + "-abcdefgh");
  fs::create_directories(live);
  writeFileAtomically(live / kRunMarker, "x");
  const fs::path lookalike = root / (".run.staging-" + std::to_string(dead) + "-zzzzzzzz");
  fs::create_directories(lookalike);
  writeFileAtomically(lookalike / "mine.txt", "not eggshell's");
  {
    StagedDirectory staged(out);
    EXPECT_EQ(readAll(out / "report.json"), "earlier")
        << "the earlier run is back before the new one starts";
    EXPECT_FALSE(staged.recoveryNotes().empty());
  }
  EXPECT_FALSE(fs::exists(aside));
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(lookalike / "mine.txt"));
  EXPECT_EQ(readAll(out / "report.json"), "earlier");
  // A kill after the second rename: the new run in place, the old one still aside: removed.
  const fs::path stale = root / (".run.previous-" + std::to_string(dead) + "-bcdefghi");
  makeRun(root / "tmp", "older");
  fs::rename(root / "tmp", stale);
  { StagedDirectory staged(out); }
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(readAll(out / "report.json"), "earlier");
}

// Issue 40: a run in another PID namespace (a container, another host on a shared disk) has a PID
// that means nothing here; its staging folder was deleted as a dead run's. Its lock says it is at
// work: the folder stays while the lock is held (here by another open of it, as that run's would
// be), and goes once it is released.
TEST_F(TempDir, AStagingFolderAtWorkElsewhereIsLeftAloneWhateverItsPid) {
  const fs::path out = root / "run";
  const pid_t dead = deadPid();  // "their" PID: no process of that number here
  const fs::path theirs = root / (".run.staging-" + std::to_string(dead) + "-abcdefgh");
  fs::create_directories(theirs);
  writeFileAtomically(theirs / kRunMarker, "eggshell run in progress (staging folder)\n");
  {
    const LiveLock atWork(theirs);
    ASSERT_TRUE(atWork.held());
    EXPECT_TRUE(leftoverInUse(theirs, dead));
    StagedDirectory staged(out);
    EXPECT_TRUE(fs::exists(theirs / kRunMarker)) << "a live run's folder was removed";
    // Our own staging folder carries our lock: seen at work from outside too.
    EXPECT_TRUE(leftoverInUse(staged.staging(), dead));
  }
  EXPECT_FALSE(leftoverInUse(theirs, dead));
  { StagedDirectory staged(out); }
  EXPECT_FALSE(fs::exists(theirs)) << "released, it is an interrupted run's leftover";
  // Temporary files likewise: one locked while it is written is not cleaned up under it.
  const fs::path temp = root / (temporaryFilePrefix() + std::to_string(dead) + "-abcdefgh");
  writeFileAtomically(root / "seed.txt", "x");
  std::ofstream(temp) << "half";
  {
    const LiveLock writing(temp);
    writeFileAtomically(root / "other.txt", "y");  // cleans the folder's dead leftovers first
    EXPECT_TRUE(fs::exists(temp));
  }
  writeFileAtomically(root / "other.txt", "z");
  EXPECT_FALSE(fs::exists(temp));
}

}  // namespace
}  // namespace egg::pipeline
