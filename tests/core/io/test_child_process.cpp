// A function run in a child process: its exit code and output come back, a hang is killed at the
// time limit, a crash is a signal, and the peak memory is the child's own.
#include "core/io/child_process.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>
#include <vector>

namespace egg {
namespace {

// A log file in the temporary folder, removed when the test ends.
struct LogFile {
  explicit LogFile(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("egg_child_" + name + "_" + std::to_string(::getpid()) + ".txt")) {}
  ~LogFile() { std::filesystem::remove(path); }
  operator const std::filesystem::path&() const { return path; }
  std::filesystem::path path;
};

TEST(ChildProcess, ExitCodeAndOutputComeBack) {
  const ChildOutcome o = runChild(
      [] {
        std::printf("hello from the child\n");
        std::fprintf(stderr, "and its stderr\n");
        return 7;
      },
      10.0, LogFile("exit"));
  EXPECT_FALSE(o.timedOut);
  EXPECT_EQ(o.signal, 0);
  EXPECT_EQ(o.exitCode, 7);
  EXPECT_NE(o.output.find("hello from the child"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("and its stderr"), std::string::npos) << o.output;
  // An exception that escapes the body: exit code 3 with its message.
  const ChildOutcome thrown =
      runChild([]() -> int { throw std::runtime_error("boom"); }, 10.0, LogFile("throw"));
  EXPECT_EQ(thrown.exitCode, 3);
  EXPECT_NE(thrown.output.find("boom"), std::string::npos);
}

TEST(ChildProcess, AHangIsKilledAtTheTimeLimit) {
  const ChildOutcome o = runChild(
      [] {
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
        return 0;
      },
      0.3, LogFile("hang"));
  EXPECT_TRUE(o.timedOut);
  EXPECT_GE(o.seconds, 0.3);
  EXPECT_LT(o.seconds, 5.0);
}

TEST(ChildProcess, ACrashIsItsSignalAndTheMemoryIsTheChilds) {
  const ChildOutcome crash = runChild(
      [] {
        std::signal(SIGSEGV, SIG_DFL);  // not AddressSanitizer's handler (.ci/run's second build)
        ::raise(SIGSEGV);
        return 0;
      },
      10.0, LogFile("crash"));
  EXPECT_EQ(crash.signal, SIGSEGV);
  const ChildOutcome big = runChild(
      [] {
        std::vector<char> v(200u << 20, 1);
        return v[12345] == 1 ? 0 : 1;
      },
      10.0, LogFile("mem"));
  EXPECT_EQ(big.exitCode, 0);
  EXPECT_GT(big.peakRssMb, 190.0);
}

// egg killed while a child runs (ccx, Node.js): the child goes with it, not on for ever in its own
// process group. A middle process plays egg: it starts a hanging child through runChild, which
// writes its pid to a pipe; the middle process is then killed with SIGKILL.
TEST(ChildProcess, AChildDoesNotOutliveAKilledParent) {
  // Named and removed by this process: the middle one is killed before it could remove it.
  const LogFile log("orphan");
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t middle = ::fork();
  ASSERT_GE(middle, 0);
  if (middle == 0) {
    ::close(fds[0]);
    const int out = fds[1];
    runChild(
        [out] {
          const pid_t me = ::getpid();
          if (::write(out, &me, sizeof me) != sizeof me) return 1;
          for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
          return 0;
        },
        60.0, log.path);
    ::_exit(0);
  }
  ::close(fds[1]);
  pid_t child = 0;
  ASSERT_EQ(::read(fds[0], &child, sizeof child), static_cast<ssize_t>(sizeof child));
  ::close(fds[0]);
  ASSERT_GT(child, 0);
  EXPECT_EQ(::kill(child, 0), 0);  // running
  ::kill(middle, SIGKILL);
  int status = 0;
  ::waitpid(middle, &status, 0);
  bool gone = false;
  for (int i = 0; i < 200 && !gone; ++i) {  // up to 2 s; it is a zombie of init at most briefly
    gone = ::kill(child, 0) != 0;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(gone) << "child " << child << " outlived its killed parent";
  if (!gone) ::kill(child, SIGKILL);
}

}  // namespace
}  // namespace egg
