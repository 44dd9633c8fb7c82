#pragma once
// The entry points the fuzz targets (targets/*.cpp, libFuzzer, built with -DEGG_FUZZ=ON and clang)
// and the corpus replay test (test_fuzz_corpus.cpp, every build) share (issue 17): bytes in, and
// either the input is accepted or a typed egg::Error says why. Anything else (another exception, a
// crash, a sanitizer report, a hang) is a bug.
#include "core/errors.hpp"
#include "core/io/mesh_io.hpp"
#include "core/mesh/validate.hpp"
#include "pipeline/scene.hpp"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace egg::fuzz {

// The scene parser on the text of a scene file. True when it is a valid scene.
inline bool scene(const uint8_t* data, size_t size) {
  try {
    pipeline::parseSceneText(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    return true;
  } catch (const Error&) {
    return false;
  }
}

// The mesh loader of the extension `ext` (".obj", ".stl", ".ply", ".off", ".gltf", ".glb"): assimp
// reads files by name, so the bytes go to a file of this process first. Then the whole surface
// path of `egg run`: readMeshFile and prepareMesh. True when the mesh is accepted.
inline bool mesh(const std::string& ext, const uint8_t* data, size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d =
        std::filesystem::temp_directory_path() / ("egg_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::filesystem::path file = dir / ("input" + ext);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    MeshRepairDiagnostics diagnostics;
    loadMeshFile(file, {}, {}, diagnostics);
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace egg::fuzz
