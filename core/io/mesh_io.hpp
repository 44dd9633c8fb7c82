#pragma once
// Mesh files in and out (docs/architecture.md "Stage table", row "surface": `{"file": "roof.obj",
// "scale_to_m": 0.001}`). Import goes through assimp and returns a raw TriangleSoup (duplicate
// vertices and all): checking and repair are prepareMesh's job (core/mesh/validate.hpp). Export
// writes atomically.
// Precision: this assimp build stores coordinates as 32-bit floats, so a file keeps ~7 significant
// digits (a 100 m roof to ~10 um); georeferenced coordinates should be shifted before export.
// FBX: we do not ask assimp to convert units (AI_CONFIG_FBX_CONVERT_TO_M stays off), so coordinates
// arrive in the file's unit; pass scale_to_m for it (0.01 for the common centimetres).
#include "core/mesh/mesh.hpp"
#include "core/mesh/validate.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace egg {

struct MeshImportOptions {
  // Factor from file units to metres (0.001 for a file in millimetres).
  double scaleToM = 1.0;

  void validate() const;  // throws InvalidInput naming the field
};

// Reads every triangle of every mesh in the file (OBJ, STL, PLY, OFF, glTF/GLB, FBX and whatever
// else assimp reads), with each node's transform applied, scaled to metres. Polygons are
// triangulated; points and lines are ignored. Throws IoError naming the file and the reason when
// the file is missing, unreadable, or holds no triangles.
TriangleSoup readMeshFile(const std::filesystem::path& path, const MeshImportOptions& options = {});

// readMeshFile then prepareMesh: the validated, repaired surface of a file. An invalid mesh is an
// InvalidInput whose message starts with the file name and goes on to name the element.
TriMesh loadMeshFile(const std::filesystem::path& path, const MeshImportOptions& importOptions,
                     const MeshCheckOptions& checkOptions, MeshRepairDiagnostics& diagnostics);

struct MeshExportOptions {
  // Factor from metres to file units (1000 writes millimetres).
  double scaleFromM = 1.0;
  // STL and PLY: binary (true) or ASCII (false).
  bool binary = true;

  void validate() const;  // throws InvalidInput naming the field
};

// Writes OBJ, PLY, STL, glTF (.gltf + .bin) or GLB, chosen by the extension (case-insensitive).
// Files are written to a temporary directory next to the target and renamed into place, so a
// failure never leaves a half-written file. Throws IoError naming the file and the reason.
void writeMeshFile(const std::filesystem::path& path, const TriangleSoup& soup,
                   const MeshExportOptions& options = {});
void writeMeshFile(const std::filesystem::path& path, const TriMesh& mesh,
                   const MeshExportOptions& options = {});

// Lower-case extensions with the dot (".obj", ...).
std::vector<std::string> importableExtensions();
std::vector<std::string> exportableExtensions();

}  // namespace egg
