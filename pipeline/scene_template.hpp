#pragma once
// `egg init`: a starting scene for a user's own surface (issue 39). Every key at its default, in
// the reference's order, each section annotated with "$comment" lines (what each key does, its
// unit and range), and the few values that depend on the surface suggested from it: the lamella
// section and Workflow 2's largest patch.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

struct StartingSceneOptions {
  std::string surface;                // a sample name or a mesh file, as the user gave it
  std::optional<double> scaleToM;     // a mesh file's coordinates times this are metres
  std::filesystem::path sceneFolder;  // where the scene will live: a mesh path is relative to it
  std::string schema;                 // the scene's "$schema" (empty: none)
};

// The surface's measures the suggestions are made from.
struct SurfaceMeasures {
  double planXM = 0, planYM = 0, riseM = 0;  // bounding box sides
  double spanM = 0;                          // the longer plan side (docs/acceptance.md)
  double planDiagonalM = 0;
  // 95th percentile over interior vertices of the larger |principal curvature| [1/m]: the
  // curvature a lamella is bent to when deployed, at most (a geodesic's normal curvature).
  double bendingCurvaturePerM = 0;
};

struct StartingScene {
  nlohmann::ordered_json scene;  // the file's content
  SurfaceMeasures measures;
  double thicknessM = 0, widthM = 0;  // the suggested section
  double maxPatchSizeM = 0;           // the suggested patching.max_patch_size_m
  std::vector<std::string> warnings;  // from loading the surface (repairs made)
};

// Loads the surface (its errors are bad input naming it; a mesh of implausible size for metres
// names the scale_to_m that fixes it) and writes the starting scene. Throws InvalidInput / IoError.
StartingScene startingScene(const StartingSceneOptions& options);

// The suggested lamella thickness [m]: the thickest stock plywood thickness whose deployment
// bending stress E kappa t / 2 stays at half the material's bending strength (the k_mod / gamma_M
// of a permanent load, docs/acceptance.md) at curvature `kappa`.
double suggestedThicknessM(double bendingCurvaturePerM, double youngsModulusPa,
                           double bendingStrengthPa);

// Workflow 2's largest patch [m]: two thirds of the plan diagonal (near a 2 x 2 start) in 5 m
// steps, within [40, 100] m (the default and the Yas sample's).
double suggestedMaxPatchSizeM(double planDiagonalM);

}  // namespace egg::pipeline
