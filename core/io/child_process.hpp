#pragma once
// Running a function in a child process with a time limit: a hang is caught, a crash does not take
// the caller down, and peak memory is the child's own (the stress suites run every case so).
#include <filesystem>
#include <functional>
#include <string>

namespace egg {

struct ChildOutcome {
  bool timedOut = false;
  int exitCode = -1;  // valid when signal == 0 and !timedOut
  int signal = 0;     // the signal that ended the child (a crash), 0 if it exited
  double seconds = 0.0;
  double peakRssMb = 0.0;  // the child's own peak resident set (wait4 rusage)
  std::string output;      // the child's stdout and stderr, interleaved
};

// Forks; the child sends stdout and stderr to a file, runs `body` and exits with its return code
// (an escaping exception: code 3 with its message). Killed (with its process group) after
// timeLimit_s. Never throws for what the child does. A body that limits the child's memory
// (RLIMIT_AS) before an exec must not allocate after it: build argv in the caller.
ChildOutcome runChild(const std::function<int()>& body, double timeLimitS,
                      const std::filesystem::path& logFile);

}  // namespace egg
