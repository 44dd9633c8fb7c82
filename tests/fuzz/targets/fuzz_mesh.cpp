// libFuzzer target: one mesh loader, chosen by EGG_FUZZ_EXT (".obj", ".stl", ".ply", ".off",
// ".gltf",
// ".glb"), through the same path as `egg run` (issue 17). Built with -DEGG_FUZZ=ON and clang.
#include "tests/fuzz/fuzz_entry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  egg::fuzz::mesh(EGG_FUZZ_EXT, data, size);
  return 0;
}
