#pragma once
// `egg bench sim --joined`: the joined simulation of sample scenes at several thread counts.
#include <string>
#include <vector>

namespace egg::app {

struct JoinedSimBenchArgs {
  std::vector<std::string> samples;  // samples/<name>.json or scene files
  std::vector<int> threadCounts{1, 2};
  int repeats = 1;
  bool json = false;
};

// Exit code 0, or 1 when a joined run did not converge.
int runJoinedSimBench(const JoinedSimBenchArgs& args);

}  // namespace egg::app
