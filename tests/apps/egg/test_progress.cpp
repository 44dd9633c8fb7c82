#include "apps/egg/progress.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

namespace egg::app {
namespace {

TEST(Progress, BarFillsInProportionAndClamps) {
  EXPECT_EQ(progressText(0.0, "surface", 0.0, 10), "[..........]   0% surface (0.0 s)");
  EXPECT_EQ(progressText(0.45, "patching", 1.26, 10), "[####......]  45% patching (1.3 s)");
  EXPECT_EQ(progressText(1.0, "done", 12.34, 4), "[####] 100% done (12.3 s)");
  EXPECT_EQ(progressText(7.0, "x", 0.0, 4), "[####] 100% x (0.0 s)");
  EXPECT_EQ(progressText(-1.0, "x", 0.0, 4), "[....]   0% x (0.0 s)");
  EXPECT_EQ(progressText(std::nan(""), "x", 0.0, 4), "[....]   0% x (0.0 s)");
}

TEST(Progress, QuietWhenNotATerminal) {
  // ctest runs with stderr redirected: an enabled bar stays hidden there, and a disabled one
  // always.
  ProgressLine off(false);
  EXPECT_FALSE(off.shown());
  ProgressLine on(true);
  EXPECT_EQ(on.shown(), ProgressLine::stderrIsTerminal());
}

// Not on a terminal: a line when a stage starts, none for its sub-steps, and one more when a stage
// has gone on for the heartbeat interval.
TEST(Progress, ALogGetsALinePerStageAndAHeartbeat) {
  std::ostringstream out;
  StageLog log(out, 0.05);
  log.update(0.0, "surface: loading");
  log.update(0.1, "surface: curvature");  // same stage: nothing
  log.update(0.2, "patching");
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  log.update(0.5, "patching: block 3");  // past the heartbeat: "still"
  const std::string text = out.str();
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << text;
  EXPECT_NE(lines[0].find("  0% surface: loading"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find(" 20% patching"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(" 50% patching: block 3 (still)"), std::string::npos) << lines[2];
  EXPECT_EQ(lines[0].rfind("egg: ", 0), 0u);
}

// On a real terminal (a pseudo-terminal here): update draws "\r<line>", clear wipes it with as
// many spaces and returns the cursor, so a table row printed next takes the line's place.
TEST(Progress, ClearWipesTheLineOnATerminal) {
  int master = -1;
  const pid_t child = ::forkpty(&master, nullptr, nullptr, nullptr);
  ASSERT_GE(child, 0);
  if (child == 0) {
    {
      ProgressLine bar(true);
      bar.update(0.5, "case 1 of 2: x");
      bar.clear();
    }
    ::_exit(ProgressLine::stderrIsTerminal() ? 0 : 3);
  }
  std::string out;
  char buffer[256];
  for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;)
    out.append(buffer, static_cast<size_t>(n));
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(master);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0) << "the child's stderr was not a terminal";
  const std::string line = progressText(0.5, "case 1 of 2: x", 0.0);
  ASSERT_EQ(out.size(), 1 + line.size() + 1 + line.size() + 1) << out;
  EXPECT_EQ(out.substr(0, 1 + line.size() - 7),
            "\r" + line.substr(0, line.size() - 7));  // the time may differ
  EXPECT_EQ(out.substr(1 + line.size()),
            "\r" + std::string(line.size(), ' ') + "\r");  // nothing left, no newline
}

}  // namespace
}  // namespace egg::app
