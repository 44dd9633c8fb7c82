#pragma once
// The entry points the fuzz targets (targets/*.cpp, libFuzzer, built with -DEGG_FUZZ=ON and clang)
// and the corpus replay test (test_fuzz_corpus.cpp, every build) share (issue 17): bytes in, and
// either the input is accepted or a typed egg::Error says why. Anything else (another exception, a
// crash, a sanitizer report, a hang) is a bug.
#include "apps/bench/sweep.hpp"
#include "apps/egg/commands.hpp"
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
#include <vector>

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

// A folder of this process for the inputs that must be files, removed when the process ends.
inline const std::filesystem::path& scratch() {
  struct Folder {
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("egg_fuzz_" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(dir); }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  };
  static const Folder folder;
  return folder.dir;
}

// The mesh loader of the extension `ext` (".obj", ".stl", ".ply", ".off", ".gltf", ".glb"): assimp
// reads files by name, so the bytes go to a file of this process first. Then the whole surface
// path of `egg run`: readMeshFile and prepareMesh. True when the mesh is accepted.
inline bool mesh(const std::string& ext, const uint8_t* data, size_t size) {
  const std::filesystem::path& dir = scratch();
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

// The sweep file parser and expander (issue 40) on the bytes of a sweep file, beside a small valid
// base scene (base.json, which its "base" may name), in dry-run mode: every variant expanded and
// checked as a scene, nothing written. True when the sweep is valid.
inline bool sweep(const uint8_t* data, size_t size) {
  const std::filesystem::path& dir = scratch();
  static const bool baseWritten = [&] {
    std::ofstream(dir / "base.json")
        << R"({"name": "b", "surface": {"sample": "bump", "edge_length_m": 0.5},
              "grid": {"members_per_family": 5}, "lamella": {"width_m": 0.1,
              "thickness_m": 0.01}, "outputs": ["report"]})";
    return true;
  }();
  (void)baseWritten;
  {
    std::ofstream out(dir / "sweep.json", std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    app::SweepExpandOptions options;
    options.sweepFile = dir / "sweep.json";
    options.out = dir / "out";
    options.eggBinary = "/usr/bin/egg";
    options.dryRun = true;
    app::expandSweep(options);
    return true;
  } catch (const Error&) {
    return false;
  }
}

// The command-line parsers of every command (issue 40): the bytes split at newlines into at most
// 64 arguments after "egg", parsed as `egg` parses them, nothing run. True when the line is valid.
inline bool commandLine(const uint8_t* data, size_t size) {
  std::vector<std::string> args{"egg"};
  std::string current;
  for (size_t i = 0; i < size && args.size() < 65; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n') {
      args.push_back(current);
      current.clear();
    } else if (c != '\0') {
      current += c;
    }
  }
  if (args.size() < 65) args.push_back(current);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return app::checkCommandLine(static_cast<int>(argv.size()), argv.data()) == app::kExitOk;
}

}  // namespace egg::fuzz
