#pragma once
// Rhino .3dm of the structure model, written by the npm package rhino3dm (export/js, pinned in its
// package-lock.json) run by Node.js as a child process: C++ writes a plain JSON description of the
// layers and objects, js/write3dm.mjs turns it into a File3dm. Layers: "surface", one per patch
// ("P3", holding its bolts) with one sublayer per family ("P3-U", "P3-V"), "supports". One named
// mesh object per lamella (its solid ribbon, vertex colours by deviation) with user strings id,
// patch, family, index, length_m, spatial_length_m, max_deviation_m, sheet.
#include "export/model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace egg::exporter {

// The folder of the Node.js scripts: $EGG_EXPORT_JS when set, else the source tree's export/js.
std::filesystem::path exportJsDir();
// The node program: the first `node` on PATH, else /usr/bin/node; empty when there is none.
std::filesystem::path nodeProgram();

// Why the 3dm cannot be written on this machine (no Node.js, rhino3dm not installed: run
// scripts/install-deps.sh), empty when it can.
std::string rhinoUnavailableReason();

// The description js/write3dm.mjs reads: {units, layers[{name, parent}], objects[{name, layer,
// kind: "mesh", vertices, faces, colours?, user{}}]}.
nlohmann::json rhinoDescription(const StructureModel& model);

// Writes `path` through node (atomically: a temporary file beside it, renamed when node
// succeeded). Throws Error with node's output when node fails or runs past timeLimitS, WriteError
// when the file cannot be put in place. Returns the seconds node ran (the rest is the description).
double write3dm(const StructureModel& model, const std::filesystem::path& path,
                double timeLimitS = 300.0);

}  // namespace egg::exporter
