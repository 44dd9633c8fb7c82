#pragma once
// Runs one of export/js's check scripts on a file with Node.js: the exit code and what it printed.
#include "export/rhino_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

namespace egg::exporter::testing {

struct NodeOutcome {
  int exitCode = -1;
  std::string output;
};

inline NodeOutcome runNodeScript(const std::string& script, const std::string& arguments) {
  const std::string command =
      nodeProgram().string() + " " + (exportJsDir() / script).string() + " " + arguments + " 2>&1";
  NodeOutcome out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.output.append(buffer, n);
  const int status = ::pclose(pipe);
  out.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

// Why the node checks cannot run here (skip the test with it), empty when they can.
inline std::string nodeChecksUnavailable() {
  if (const std::string why = rhinoUnavailableReason(); !why.empty()) return why;
  if (!std::filesystem::exists(exportJsDir() / "node_modules" / "gltf-validator"))
    return "the npm package gltf-validator is not installed (scripts/install-deps.sh)";
  return "";
}

}  // namespace egg::exporter::testing
