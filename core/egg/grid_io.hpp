#pragma once
// Per-patch outputs (docs/architecture.md "Outputs"): grid JSON (members, connections, notches,
// anchors, planar and spatial coordinates), OBJ of the spatial grid, SVG preview of the planar
// grid. Every writer writes a temporary file next to the target and renames it, so a reader never
// sees a half-written file; failures throw IoError naming the file.
#include "core/egg/solve_patch.hpp"

#include <string>

namespace egg {

// The grid JSON document as text (metres and radians; keys carry their unit).
std::string gridJson(const EggResult& result, int patchId = 0);

void writeGridJson(const EggResult& result, const std::string& path, int patchId = 0);
// One object and group per member named by its lamella id, "P<patch>-U<i>" / "P<patch>-V<j>" (the
// cut sheets' and the 3D model's names).
void writeGridObj(const EggGrid& grid, const std::string& path, int patchId = 0);
// Planar grid preview: u members blue, v members orange, notches as thick strokes along the
// member (length |l|, towards the sliding direction), anchors as red squares.
void writePlanarSvg(const EggGrid& grid, const std::string& path);

}  // namespace egg
