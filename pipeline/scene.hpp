#pragma once
// The scene file read by `egg run` (docs/scene-reference.md, generated from scene_fields.cpp).
// The scene holds the libraries' own Options structs; every key is declared once, in the field
// list of its section (scene_fields.cpp), which reads it, writes it back and documents it. Every
// key but `surface` has a default; an unknown key is an error so that a typo never passes.
#include "core/egg/solve_patch.hpp"
#include "core/rods/simulation.hpp"
#include "fabrication/options.hpp"
#include "patching/workflow1.hpp"
#include "patching/workflow2.hpp"
#include "pipeline/acceptance.hpp"

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace egg::pipeline {

// "surface": the design surface (Section 4.4.1), a procedural sample or a mesh file.
struct SurfaceSource {
  std::string sample;                    // a sample name, or empty when `file` is set
  std::map<std::string, double> params;  // sample parameters (see `egg surface --list`)
  double edgeLengthM = 1.0;              // target triangle edge length of a sample
  std::filesystem::path file;            // a mesh file (resolved against the scene's folder)
  double scaleToM = 1.0;                 // file coordinates times this are metres
  bool keepLargestComponent = false;     // drop smaller components with a warning, not fail
};

// "patching": how the surface is split into patches (Sections 3.3, 3.4) and each one designed.
struct PatchingChoice {
  int workflow = 2;  // Workflow 1 or 2 of Section 3.4.3
  bool workflowGiven =
      false;  // the scene names a workflow (a layout without one is taken as given)
  // Smooth a patch whose eta fails (Section 2.3.3). Default: yes for a given layout (it cannot be
  // changed), no in the workflows, which split instead (smoothing alters the design, 3.1).
  std::optional<bool> smoothing;
  // A given layout: corners on the surface and patches as quads of corner indices (a corner may
  // lie on another patch's side: a T-junction); `patches` holds each quad's four points.
  std::vector<Eigen::Vector3d> corners;
  std::vector<std::array<int, 4>> quads;
  std::vector<std::array<Eigen::Vector3d, 4>> patches;
  patching::Workflow2Options workflow2;  // max_patch_size_m, block_grid
  // max_splits, min_patch_size_m; `layout.design` is every patch's EggOptions (eta_max,
  // slope_bounds and the "grid" section's keys). Its lamella width and smoothing are derived
  // (eggOptions()).
  patching::LayoutDesignOptions layout;
  // Close the cut-offs the quad patches leave (along holes and curved design boundaries) with
  // generalised patches (Chapter 4, patching/infill.hpp). Default: yes in the workflows, no for a
  // given layout (its patches are taken as they are).
  std::optional<bool> generalisedInfill;
};

// "lamella": the section and material every member is cut from.
struct Lamella {
  double widthM = 0.25;                     // section width w (strong axis)
  double thicknessM = 0.04;                 // section thickness t (weak axis)
  std::string material = "poplar_plywood";  // a material of core/materials
};

// Where the deployed grid is held (Sections 2.4.6, 3.5.3).
enum class SupportChoice {
  Auto,            // anchors for one patch, design_boundary for several
  Anchors,         // corners and boundary curvature extrema
  DesignBoundary,  // those plus every connection on a side no other patch shares
};
const char* toString(SupportChoice choice);

// "simulation": the deployment with discrete elastic rods (Section 2.5).
struct SimulationChoice {
  bool enabled = true;
  SupportChoice supports = SupportChoice::Auto;
  // With design_boundary supports, patch by patch: also hold each patch at every connection of the
  // sides it shares with a neighbour (the thesis' patches were simulated apart on supports along
  // their boundaries, Fig. 3.17).
  bool holdSharedSides = true;
  // With propagated members: also simulate the whole structure, neighbours bolted (3.5.3).
  bool joinPatches = true;
  // The rod solver's own options. A scene simulates a built structure: self-weight on, bolts
  // tightened at the weightless equilibrium before it carries its weight (the library's defaults
  // are weightless).
  rods::SimulationOptions rods = [] {
    rods::SimulationOptions options;
    options.model.gravity = true;
    options.fastenBoltsUnderLoad = true;
    return options;
  }();
};

// "fabrication": what the workshop cuts (Sections 3.5, 3.6.1).
struct FabricationChoice {
  bool enabled = true;
  // The lamella's width, thickness and material are derived (fabricationOptions()).
  fabrication::FabricationOptions options;
};

// "loads": the FE check's load cases (verification stage, docs/verification.md). Self-weight is
// always a case; these add cases of their own (with self-weight).
struct LoadsChoice {
  double uniformKnM2 = 0.0;  // snow or live load on the plan area; 0: no such case
  double pointLoadKn = 0.0;  // downwards at each named connection; 0: no such case
  std::vector<std::string> pointLoadConnections;  // FE bolt names, e.g. "P0_C12", "J3"
  int bucklingModes = 3;       // linear buckling factors of the governing case; 0: none
  double ccxTimeLimitS = 600;  // per ccx run
  int maxFeElements = 20000;  // above: the decks are written, ccx is not run (docs/verification.md)
  int maxNonlinearFeElements = 1000;  // above: first-order (linear static) cases
};

// The deployment stage (output "deployment", docs/deployment.md).
struct DeploymentChoice {
  int steps = 10;  // equal support moves from the flat grid to the deployed one
  // A bolt pressing on a notch end harder than this is jammed; 0: the bolt's embedment capacity in
  // the lamella (docs/deployment.md).
  double jamForceN = 0.0;
  double snapEnergyDrop = 0.05;  // energy drop over one finest step that is a snap-through
  double timeLimitS = 900.0;     // wall-clock limit of one path of one patch (and of the joining)
  bool joinPatches = true;       // then join the standing patches as the joined simulation did
};

struct Scene {
  std::filesystem::path path;  // where it was read from (for messages, relative files)
  std::string name;
  SurfaceSource surface;
  PatchingChoice patching;
  Lamella lamella;
  SimulationChoice simulation;
  FabricationChoice fabrication;
  AcceptanceLimits acceptance;  // the verdict's limits (acceptance.hpp, docs/acceptance.md)
  LoadsChoice loads;
  DeploymentChoice deployment;
  std::vector<std::string> outputs{"report",   "plan",     "cut_files",
                                   "stickers", "supports", "previews"};

  bool wants(const std::string& output) const;
  // Every patch's design options (patching.layout.design) as the scene sets them, the lamella
  // width and smoothing derived.
  EggOptions eggOptions() const;
  // The shorthand of the field lists for patching.layout.design.
  EggOptions& design() { return patching.layout.design; }
  const EggOptions& design() const { return patching.layout.design; }
  // fabrication.options with the lamella's width and thickness (mm) and material.
  fabrication::FabricationOptions fabricationOptions() const;
};

// A layout the scene gives without naming a workflow is taken as it is.
bool layoutIsGiven(const Scene& scene);

// The edge length a sample is meshed at when the scene or command line gives none (metres).
double defaultSampleEdgeLength(const std::string& sample);

// Reads and validates a scene file. Throws IoError (missing/unreadable file) or InvalidInput
// naming the file and the field ("scene.json: grid.alpha_bar: ...").
Scene loadScene(const std::filesystem::path& path);
// A bench's scene argument: a scene file (*.json) as given, else samples/<name>.json.
std::filesystem::path benchSceneFile(const std::string& name);

// Same from the text of a scene file (what loadScene reads): JSON nested at most 64 levels, a
// number that overflows a double named by its field. `origin` names it in messages.
Scene parseSceneText(const std::string& text, const std::filesystem::path& origin);

// Same from an already parsed document; `origin` names it in messages and anchors relative paths.
Scene parseScene(const nlohmann::json& document, const std::filesystem::path& origin);

// The scene back as JSON (what the report echoes under "scene"): every key with its value.
nlohmann::json sceneToJson(const Scene& scene);

// The scene reference (docs/scene-reference.md): every section and key with its type, range,
// default and what it does, from the same field lists the parser reads.
std::string sceneReferenceMarkdown();
// The JSON Schema (draft 2020-12) of a scene file, from the same field lists: types, ranges,
// enums, defaults and docs, unknown keys refused (docs/scene.schema.json, `egg scene-schema`).
nlohmann::json sceneJsonSchema();

}  // namespace egg::pipeline
