#pragma once
// `egg bench fem`: the FE check (CalculiX) of scenes through the pipeline.
#include <string>
#include <vector>

namespace egg::app {

struct FemBenchArgs {
  std::vector<std::string> scenes;  // samples/<name>.json or scene files
  int maxFeElements = 0;            // 0: the scene's own loads.max_fe_elements
  int repeats = 1;
  bool json = false;
};

// Exit code 0, or 1 when a scene's FE check failed (ccx's error, no structure to check).
int runFemBench(const FemBenchArgs& args);

}  // namespace egg::app
