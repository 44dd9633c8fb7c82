#pragma once
// Turning what the user names into a validated surface mesh: a procedural sample, a mesh file
// (through assimp), or a scene file's `surface` section. Shared by every subcommand that takes
// a SURFACE argument (docs/architecture.md "The `egg` command").
#include "core/mesh/mesh.hpp"
#include "pipeline/scene.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

struct RunState;

struct LoadedSurface {
  TriMesh mesh;
  std::string description;            // "sample great_court, edge 1 m" or the file path
  std::vector<std::string> warnings;  // repairs made (merged vertices, dropped components)
  double seconds = 0.0;
};

// Loads and validates the surface a scene describes. Throws InvalidInput / IoError naming the
// sample, file or element at fault.
LoadedSurface loadSurface(const SurfaceSource& spec);

// SURFACE argument of the CLI: a sample name, a mesh file, or a scene file (*.json: its surface).
// `edgeLengthM` overrides the edge length of a sample (default: the sample's own default).
LoadedSurface loadSurfaceArgumentDetailed(const std::string& argument,
                                          std::optional<double> edgeLengthM = std::nullopt);

// Convenience for commands that only need the mesh.
TriMesh loadSurfaceArgument(const std::string& argument);

// Statistics of a loaded surface (vertices, faces, bounding box, area, edge lengths, Gaussian
// curvature range with the injectivity bound of Eq. 2.1, validation). Used by `egg surface
// --stats` and by report.json's "surface" section.
nlohmann::json surfaceSummary(const LoadedSurface& surface);

// Stage table row: loads the scene's surface (Section 4.4.1) into the run; everything downstream
// measures on this mesh.
void surfaceStage(RunState& state);
}  // namespace egg::pipeline
