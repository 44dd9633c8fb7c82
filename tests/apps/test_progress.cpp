#include "apps/commands/progress.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  // ctest runs with stderr redirected: an enabled bar stays hidden there, and a disabled one always.
  ProgressLine off(false);
  EXPECT_FALSE(off.shown());
  ProgressLine on(true);
  EXPECT_EQ(on.shown(), ProgressLine::stderrIsTerminal());
}

}  // namespace
}  // namespace egg::app
