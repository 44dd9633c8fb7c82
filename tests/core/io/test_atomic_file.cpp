#include "core/io/atomic_file.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <chrono>
#include <cstdlib>

namespace egg {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, ReplacesWholeAndLeavesNoTemporaries) {
  const fs::path root =
      fs::temp_directory_path() / ("egg_atomic_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  writeFileAtomically(root / "a.txt", "first");
  writeFileAtomically(root / "a.txt", "second");
  EXPECT_EQ(readAll(root / "a.txt"), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
  fs::remove_all(root);
}

TEST(AtomicFile, MissingFolderIsAnIoErrorNamingThePath) {
  try {
    writeFileAtomically("/nonexistent_egg_dir/sub/a.txt", "x");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_egg_dir/sub/a.txt"), std::string::npos);
  }
}

TEST(AtomicFile, SuffixesDiffer) {
  EXPECT_EQ(temporarySuffix().size(), 8u);
  EXPECT_NE(temporarySuffix(), temporarySuffix());
}

// A PID that belonged to a process that has exited (a child reaped at once).
pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

class IoSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() / ("egg_io_safety_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
  }
  void TearDown() override { fs::remove_all(root); }
  fs::path root;
};

// Issue 17: `geodesic --out /dev/null` replaced the device node with a regular file.
TEST_F(IoSafety, ACharacterDeviceOrFifoOrFolderIsRefusedNotReplaced) {
  ASSERT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_THROW(writeFileAtomically("/dev/null", "x"), WriteError);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const fs::path fifo = root / "pipe.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    writeFileAtomically(fifo, "x");
    FAIL() << "expected WriteError";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("FIFO"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  fs::create_directories(root / "folder.csv");
  EXPECT_THROW(writeFileAtomically(root / "folder.csv", "x"), WriteError);
  EXPECT_TRUE(fs::is_directory(root / "folder.csv"));
  // A symbolic link to a regular file is written through, the link kept.
  writeFileAtomically(root / "real.csv", "old");
  fs::create_symlink(root / "real.csv", root / "link.csv");
  writeFileAtomically(root / "link.csv", "new");
  EXPECT_TRUE(fs::is_symlink(root / "link.csv"));
  EXPECT_EQ(readAll(root / "real.csv"), "new");
}

// Issue 17: a kill left temporary files behind that no later write removed.
TEST_F(IoSafety, TemporaryFilesOfDeadProcessesAreCleanedOthersKept) {
  const pid_t dead = deadPid();
  const fs::path leftover = root / (temporaryFilePrefix() + std::to_string(dead) + "-abcdefgh");
  const fs::path live = root / (temporaryFilePrefix() + std::to_string(::getppid()) + "-abcdefgh");
  const fs::path user = root / ".egg-tmp-notes.txt";
  for (const auto& p : {leftover, live, user}) std::ofstream(p) << "x";
  writeFileAtomically(root / "a.txt", "a");
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_TRUE(fs::exists(live));  // its process runs: maybe writing right now
  EXPECT_TRUE(fs::exists(user));  // not one of ours
  EXPECT_EQ(leftoverPid(leftover.filename().string(), temporaryFilePrefix()), dead);
  EXPECT_EQ(leftoverPid("x.egg-tmp-12-a", temporaryFilePrefix()), -1);
  EXPECT_EQ(leftoverPid(".egg-tmp--a", temporaryFilePrefix()), -1);
}

// Issue 17: a FIFO as scene or mesh file blocked forever; a folder was an internal error.
TEST_F(IoSafety, InputsMustBeRegularFilesAndAreReadWithoutBlocking) {
  const fs::path fifo = root / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  try {
    readRegularFile(fifo, 1000, "scene file");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("FIFO"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_THROW(readRegularFile(root, 1000, "scene file"), IoError);
  EXPECT_THROW(readRegularFile("/dev/zero", 1000, "scene file"), IoError);
  EXPECT_THROW(readRegularFile(root / "missing", 1000, "scene file"), IoError);
  writeFileAtomically(root / "big", std::string(2000, 'x'));
  EXPECT_THROW(readRegularFile(root / "big", 1000, "scene file"), IoError);
  EXPECT_EQ(readRegularFile(root / "big", 2000, "scene file").size(), 2000u);
  EXPECT_NO_THROW(checkRegularInputFile(root / "big", 2000, "mesh file"));
  EXPECT_THROW(checkRegularInputFile(fifo, 2000, "mesh file"), IoError);
}

// Issue 17: a disk filling up during the write must fail and leave nothing behind.
TEST_F(IoSafety, AFullDiskFailsTheWriteAndLeavesNoFile) {
  ::signal(SIGXFSZ, SIG_IGN);  // over the limit, write() fails with EFBIG instead of a signal
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 1000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    writeFileAtomically(root / "big.csv", std::string(5000, 'x'));
  } catch (const WriteError&) {
    threw = true;
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  EXPECT_TRUE(threw);
  EXPECT_TRUE(fs::is_empty(root)) << "no partial or temporary file";
}

TEST(AtomicFile, PortableNamesAndAbbreviatedMessages) {
  EXPECT_EQ(portableNameProblem("great_court", 200), "");
  EXPECT_NE(portableNameProblem(std::string(1, '\0'), 200), "");
  EXPECT_NE(portableNameProblem("a\nb", 200), "");
  EXPECT_NE(portableNameProblem("a/b", 200), "");
  EXPECT_NE(portableNameProblem("..", 200), "");
  EXPECT_NE(portableNameProblem("", 200), "");
  EXPECT_NE(portableNameProblem(std::string(201, 'a'), 200), "");
  EXPECT_EQ(portableNameProblem(std::string(200, 'a'), 200), "");
  const std::string huge(10000000, 'x');
  EXPECT_LT(abbreviate(huge).size(), 260u);
  EXPECT_NE(abbreviate(huge).find("10000000 characters"), std::string::npos);
  EXPECT_EQ(abbreviate(std::string("a\0b", 3)), "a\\x00b");
}

// A bench's or the stress suite's working folder: new each time, the process's own (0700), and a
// clear error when $TMPDIR is unusable, never a predictable path that could already exist.
TEST(PrivateTempFolder, IsNewOwnedAndFailsClearlyWithoutTmpdir) {
  const std::filesystem::path a = makePrivateTempFolder("egg-test-private");
  const std::filesystem::path b = makePrivateTempFolder("egg-test-private");
  EXPECT_NE(a, b);
  EXPECT_TRUE(std::filesystem::is_directory(a));
  EXPECT_EQ(std::filesystem::status(a).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_all);
  EXPECT_EQ(a.filename().string().rfind("egg-test-private-", 0), 0u);
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  ::setenv("TMPDIR", "/nonexistent-egg-tmpdir", 1);
  try {
    makePrivateTempFolder("egg-test-private");
    ADD_FAILURE() << "no error without a temporary folder";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("TMPDIR"), std::string::npos) << e.what();
  }
  if (old)
    ::setenv("TMPDIR", saved.c_str(), 1);
  else
    ::unsetenv("TMPDIR");
}

}  // namespace
}  // namespace egg
