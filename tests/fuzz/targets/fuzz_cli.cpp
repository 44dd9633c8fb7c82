// libFuzzer target: the command-line parsers of every `egg` command (issue 40), one argument per
// line of the input, nothing run. Built with -DEGG_FUZZ=ON and clang; see scripts/fuzz.sh.
#include "tests/fuzz/fuzz_entry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  egg::fuzz::commandLine(data, size);
  return 0;
}
