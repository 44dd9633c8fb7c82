#include "core/io/child_process.hpp"

#include "core/timing.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

namespace egg {

namespace fs = std::filesystem;

ChildOutcome runChild(const std::function<int()>& body, double timeLimitS,
                      const fs::path& logFile) {
  ChildOutcome out;
  std::fflush(nullptr);
  const Stopwatch watch;
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    out.output = "fork failed";
    out.exitCode = 127;
    return out;
  }
  if (pid == 0) {
    setpgid(0, 0);  // own group: a timeout kills the child and anything it started
    // Its own group also keeps a terminal's Ctrl-C from it, so it must not outlive us: the kernel
    // kills it when the thread that forked it ends (egg killed, interrupted or crashed; runChild
    // is called from the thread that runs the stage, which lives as long as the run). A parent
    // that died before this line is caught by the getppid check.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(125);
    const int fd = open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    int code = 3;
    try {
      code = body();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "uncaught exception: %s\n", e.what());
    }
    std::fflush(nullptr);
    _exit(code);
  }
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t r = wait4(pid, &status, WNOHANG, &usage);
    const double elapsed = watch.seconds();
    if (r == pid) break;
    if (elapsed > timeLimitS) {
      out.timedOut = true;
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  out.seconds = watch.seconds();
  out.peakRssMb = usage.ru_maxrss / 1024.0;  // kB on Linux
  if (!out.timedOut) {
    if (WIFSIGNALED(status))
      out.signal = WTERMSIG(status);
    else if (WIFEXITED(status))
      out.exitCode = WEXITSTATUS(status);
  }
  std::ifstream in(logFile);
  std::stringstream text;
  text << in.rdbuf();
  out.output = text.str();
  return out;
}

}  // namespace egg
