#pragma once
// Checks of a mesh file before assimp reads it: what assimp accepts silently (OFF
// indices out of range), hangs on (malformed PLY headers), or exhausts memory or the stack on
// (header counts beyond the file, deep glTF node trees). Used by mesh_io.cpp only.
#include <assimp/types.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace egg {

namespace mesh_precheck {
inline std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }
}  // namespace mesh_precheck

// Reads the file once (its size bounded) and checks it by extension; throws IoError or
// InvalidInput naming the file, line and element. Returns the vertex positions of an OBJ file in
// file order, as floats the way assimp stores them (empty for other formats).
std::vector<aiVector3D> precheckMeshFile(const std::filesystem::path& path);

}  // namespace egg
