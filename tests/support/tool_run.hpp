#pragma once
// Runs an external program for a test (the readers people open our outputs with: ezdxf,
// rsvg-convert, python3-jsonschema, headless Chromium, ...) and captures what it printed.
#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

namespace egg::test {

struct ToolRun {
  int status = -1;
  std::string output;
};

// Runs a shell command, capturing stdout and stderr.
inline ToolRun runTool(const std::string& command) {
  ToolRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    run.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline bool haveTool(const std::string& name) { return runTool("command -v " + name).status == 0; }

}  // namespace egg::test
