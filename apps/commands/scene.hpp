#pragma once
// The scene file read by `egg run` (DESIGN.md "Scene file"). Every key but `surface` has a
// default; an unknown key is an error so that a typo never passes silently.
#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace egg::app {

struct SurfaceSpec {
  std::string sample;                        // a procedural sample name, or empty when `file` is set
  std::map<std::string, double> params;      // sample parameters (see `egg surface --list`)
  double edge_length_m = 1.0;                // target triangle edge length (default: defaultSampleEdgeLength)
  std::filesystem::path file;                // a mesh file (resolved against the scene's folder)
  double scale_to_m = 1.0;                   // multiply file coordinates by this to get metres
  bool keep_largest_component = false;       // drop smaller components with a warning instead of failing
};

struct PatchingSpec {
  int workflow = 2;                          // Workflow 1 or 2 of Section 3.4.3
  bool workflow_given = false;               // the scene names a workflow (a layout without one is taken as given)
  double eta_max = 1.0015;                   // uniqueness threshold of Section 2.3.3 / 3.4.1
  std::array<double, 2> slope_bounds{0.1, 10.0};  // k_min, k_max of Problem 2.3
  double max_patch_size_m = 40.0;            // largest patch diagonal Workflow 2 may propose
  std::array<int, 2> block_grid{0, 0};       // Workflow 2's grid of patches, given ({0, 0}: screened)
  // A given layout, in either form of the scene file: four corners [x, y, z] per patch (corners that
  // coincide are one corner), or "corners" plus patches as quads of corner indices (which can say
  // that a corner lies on another patch's side: a T-junction). Both forms fill all three fields.
  std::vector<std::array<Eigen::Vector3d, 4>> patches;
  std::vector<Eigen::Vector3d> corners;
  std::vector<std::array<int, 4>> quads;
  // Smooth a patch whose eta fails (Section 2.3.3). Default: yes for a given layout (it cannot be
  // changed), no in Workflow 1, which splits instead (smoothing alters the design, 3.1).
  std::optional<bool> smoothing;
  int max_splits = 64;                       // Workflow 1: splits before it gives up
  double min_patch_size_m = 0.0;             // Workflow 1: no patch side shorter than this (0 = 4 mesh edges)
};

struct GridSpec {
  std::optional<int> members_per_family;     // empty = "auto" (Section 2.4.4)
  // "auto" members: target spacing between members = this x the lamella width (Section 2.4.4;
  // default = MemberOptions::spacingFactor, test_scene checks that the two agree).
  double member_spacing_factor = 8.0;
  int map_resolution = 100;                  // samples per boundary of the distance maps
  // Adaptive distance-map rows (core/egg/map_refinement.hpp): the largest miss allowed of a row
  // interpolated between exact source fields, as a fraction of the family's shorter side;
  // 0 = every row exact. Default = DistanceMapOptions::toleranceRelative (patch_maps.hpp, where
  // it is justified; test_scene checks that the two agree).
  double map_tolerance_relative = 1e-4;
  // Distance maps on a coarse proxy of at most this many vertices when the patch mesh is larger
  // (core/egg/map_proxy.hpp); 0 = on the patch itself. Default = DistanceMapOptions::proxyVertices.
  int map_proxy_vertices = 600;
  std::string alpha_bar = "min";             // "min" | "max" | "unrolled" | "value"
  double alpha_bar_rad = 0.0;                // used when alpha_bar == "value"
  // Smallest inner angle of the planar quad: convexity alone (criterion iv) lets the quad fold
  // flat, with the cut lamellas lying on top of each other; this keeps the flat grid buildable.
  double min_planar_angle_rad = 0.15;
};

struct LamellaSpec {
  double width_m = 0.25;                     // section width w (strong axis)
  double thickness_m = 0.04;                 // section thickness t (weak axis)
  std::string material = "poplar_plywood";   // a material of fabrication's table
};

struct SimulationSpec {
  bool enabled = true;
  bool gravity = true;                       // self-weight from the material density (Section 3.5.2)
  double friction_mu = 0.1;                  // pseudo-friction coefficient of E_p (Section 2.5)
  bool notches = true;                       // bolts slide in their notches (RMS2 of Section 2.6.2)
  // Also simulate every patch with plain holes (RMS1 of Section 2.6.2): a second full run per
  // patch, only for the comparison, so off unless the scene asks for it.
  bool compare_without_notches = false;
  // Where the grid is held: "anchors" (corners and boundary curvature extrema, Section 2.4.6),
  // "design_boundary" (those plus every connection on a side of the layout no other patch shares,
  // 3.5.3), "auto" = anchors for one patch, design_boundary for several.
  std::string supports = "auto";
  // With design_boundary supports, patch by patch: also hold each patch at every connection of the
  // sides it shares with a neighbour (the thesis' patches were simulated apart on supports along
  // their boundaries, Fig. 3.17). false: those sides are free, as nothing holds them alone.
  bool hold_shared_sides = true;
  // With propagated members (several patches): also simulate the whole structure with the shared
  // boundary lamellas of neighbouring patches bolted at their coinciding member ends (3.5.3).
  bool join_patches = true;
  // Self-weight runs: bolts tightened at the weightless equilibrium before the grid carries its
  // weight (rods::SimulationOptions::fastenBoltsUnderLoad).
  bool fasten_bolts = true;
  // Newton stops when its decrement g^T H^-1 g falls below this x the energy scale (default =
  // rods::SolverOptions::tolerance; test_scene checks that the two agree). Larger is faster and
  // less exact: one of `egg bench pipeline`'s knobs.
  double newton_tolerance = 1e-10;
  // Wall-clock hang guard of each solve, seconds (default = rods::SolverOptions::timeLimit_s): a
  // solve that reaches it fails with that reason. The iteration limit, not this, decides results.
  double time_limit_s = 900.0;
};

// Defaults as fabrication::FabricationOptions (fabrication/options.hpp); the `std::optional` ones
// default to values derived from the lamella (see there). test_fabrication_stage checks they agree.
struct FabricationSpec {
  bool enabled = true;
  std::array<double, 2> sheet_mm{2500.0, 1250.0};  // stock sheet size for nesting; strips along the first side
  double bolt_diameter_mm = 8.0;
  double kerf_mm = 0.2;                      // gap the cutter removes between nested parts
  double margin_mm = 10.0;                   // unused border of every sheet
  double min_notch_mm = 1.0;                 // shorter notches are cut as plain holes (and counted)
  double stock_length_mm = 6000.0;           // longer lamellas are spliced, clear of holes and slots
  std::optional<double> end_overhang_mm;     // strip beyond the end connections (default half the width)
  std::optional<double> splice_clearance_mm;  // no hole or slot this close to a splice (default the width)
  std::optional<double> min_splice_clearance_mm;  // where no position is that clear: at least this (default 3.5 d)
  std::optional<double> label_height_mm;     // engraved text height (default 0.35 w, 1..30 mm)
  std::string splice_joint = "plate";        // "plate", "scarf" or "plate_or_scarf" (glued where no plate fits)
  double scarf_slope = 12.0;                 // scarf run per unit of thickness (1:12)
  double scarf_efficiency = 0.85;            // glued joint strength over the plain strip's
  double sticker_margin_mm = 2.0;            // PTFE sticker beyond the swept contact area
  std::optional<std::array<double, 2>> sticker_sheet_mm;  // PTFE foil sheet (default sheet_mm)
  std::optional<double> ground_height_m;     // ground plane z of the supports (default 0.1 m below the lowest)
  std::optional<double> support_block_mm;    // footprint side of a support block (default 3 w)
  bool supports_at_boundary_connections = false;  // a support at every boundary connection, not only at anchors
};

struct Scene {
  std::filesystem::path path;                // where it was read from (for messages, relative files)
  std::string name;
  SurfaceSpec surface;
  PatchingSpec patching;
  GridSpec grid;
  LamellaSpec lamella;
  SimulationSpec simulation;
  FabricationSpec fabrication;
  std::vector<std::string> outputs{"report", "plan", "cut_files", "stickers", "supports", "previews"};

  bool wants(const std::string& output) const;
};

// The edge length a sample is meshed at when the scene or command line gives none (metres).
double defaultSampleEdgeLength(const std::string& sample);

// Reads and validates a scene file. Throws IoError (missing/unreadable file) or InvalidInput
// naming the file and the field ("scene.json: grid.alpha_bar: ...").
Scene loadScene(const std::filesystem::path& path);
// A bench's scene argument: a scene file (*.json) as given, else samples/<name>.json (from the repository root).
std::filesystem::path benchSceneFile(const std::string& name);

// Same from the text of a scene file (what loadScene reads): JSON nested at most 64 levels, a
// number that overflows a double named by its field. `origin` names it in messages.
Scene parseSceneText(const std::string& text, const std::filesystem::path& origin);

// Same from an already parsed document; `origin` names it in messages and anchors relative paths.
Scene parseScene(const nlohmann::json& document, const std::filesystem::path& origin);

// The scene back as JSON (what the report echoes under "scene").
nlohmann::json sceneToJson(const Scene& scene);

}  // namespace egg::app
