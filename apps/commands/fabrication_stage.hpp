#pragma once
// The scene's side of the fabrication stage (fabrication/fabricate.hpp): its options and which
// files to write, read from the scene, so the pipeline wires the stage in a few calls:
//   auto options = fabricationOptionsFromScene(scene);
//   auto result = fabrication::fabricate(patches, options);   // patches: {id, &grid, deployed?}
//   auto files = fabrication::writeFabricationFiles(result, runDir, fabricationOutputsFromScene(scene));
//   report["fabrication"] = fabrication::fabricationReport(result, files);
#include "apps/commands/scene.hpp"
#include "fabrication/fabricate.hpp"

namespace egg::app {

// Lamella width/thickness (m in the scene, mm here) and material, and every fabrication.* key.
fabrication::FabricationOptions fabricationOptionsFromScene(const Scene& scene);

// The outputs "cut_files", "stickers" and "supports" of the scene.
fabrication::FabricationOutputs fabricationOutputsFromScene(const Scene& scene);

// Whether the stage runs at all: fabrication.enabled and at least one of its outputs asked for.
bool fabricationWanted(const Scene& scene);

}  // namespace egg::app
