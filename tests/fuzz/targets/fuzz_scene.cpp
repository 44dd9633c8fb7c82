// libFuzzer target: the scene parser (issue 17). Built with -DEGG_FUZZ=ON and clang; see
// scripts/fuzz.sh.
#include "tests/fuzz/fuzz_entry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  egg::fuzz::scene(data, size);
  return 0;
}
