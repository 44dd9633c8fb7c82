// libFuzzer target: the sweep file parser and expander (issue 40), in dry-run mode. Built with
// -DEGG_FUZZ=ON and clang; see scripts/fuzz.sh.
#include "tests/fuzz/fuzz_entry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  egg::fuzz::sweep(data, size);
  return 0;
}
