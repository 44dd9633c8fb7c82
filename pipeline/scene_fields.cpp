// The scene's keys, each declared once: section by section, in the order the parser reads them.
// A new knob is one line here (and its member in the library's Options struct).
#include "pipeline/scene_fields.hpp"

#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "pipeline/run_folder.hpp"
#include "pipeline/stages.hpp"
#include "samples/generators/samples.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace egg::pipeline {

using nlohmann::json;

namespace field {

std::string numberText(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

std::string range(double lo, double hi) {
  return "[" + numberText(lo) + ", " + numberText(hi) + "]";
}

std::string alternatives(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += i == 0 ? "" : i + 1 == names.size() ? " or " : ", ";
    out += "\"" + names[i] + "\"";
  }
  return out;
}

json numberSchema(double lo, double hi) {
  return {{"type", "number"}, {"minimum", lo}, {"maximum", hi}};
}

json positiveSchema(double hi) {
  return {{"type", "number"}, {"exclusiveMinimum", 0}, {"maximum", hi}};
}

json integerSchema(long long lo, long long hi) {
  return {{"type", "integer"}, {"minimum", lo}, {"maximum", hi}};
}

json pairSchema(double lo, double hi) {
  return {{"type", "array"}, {"items", numberSchema(lo, hi)}, {"minItems", 2}, {"maxItems", 2}};
}

json stringSchema() { return {{"type", "string"}, {"minLength", 1}}; }

}  // namespace field

namespace {

// Most patches a given layout may have (each is minutes of work at most; 10,000 ran for hours).
constexpr std::size_t kMaxPatches = 1000;

Eigen::Vector3d point3(const json& v, const JsonSection& where, const std::string& key) {
  if (!v.is_array() || v.size() != 3)
    where.fail(key, "a corner must be [x, y, z], got " + brief(v));
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      where.fail(key, "corner coordinates must be finite numbers, got " + brief(v));
    p[i] = v[i].get<double>();
  }
  return p;
}

json pointJson(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

const json kPointSchema = {
    {"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", 3}, {"maxItems", 3}};

// A patch: four corners [x, y, z], or four indices into "corners".
json patchesSchema() {
  const json index = {{"type", "integer"}, {"minimum", 0}};
  const json corner = {{"anyOf", json::array({kPointSchema, index})}};
  const json patch = {{"type", "array"}, {"items", corner}, {"minItems", 4}, {"maxItems", 4}};
  return {{"type", "array"}, {"items", patch}, {"maxItems", kMaxPatches}};
}

json outputsSchema() {
  json names = json::array();
  for (const Output& output : outputTable()) names.push_back(output.name);
  return {{"type", "array"}, {"items", {{"enum", names}}}, {"uniqueItems", true}};
}

json sampleSchema() {
  json names = json::array();
  for (const auto& info : samples::listSamples()) names.push_back(info.name);
  return {{"enum", names}};
}

// --- top level --------------------------------------------------------------------------------

void readName(JsonSection& j, Scene& scene) {
  scene.name = j.text("name", scene.path.stem().string());
  // The name becomes the default run folder out/<name>: a plain, portable folder name, never a
  // path that climbs out of out/ or names out/ itself, short enough for the staging folder's name.
  if (const std::string problem = portableNameProblem(scene.name, kMaxRunFolderName);
      !problem.empty())
    j.fail("name", "must be a plain folder name (" + problem + "), got " + brief(json(scene.name)));
  if (scene.name.front() == '.')
    j.fail("name", "must be a plain name (no '/', '\\', not starting with '.'), got " +
                       brief(json(scene.name)));
}

void readOutputs(JsonSection& j, Scene& scene) {
  if (!j.has("outputs")) return;
  const json& v = j.raw("outputs");
  if (!v.is_array()) j.fail("outputs", "must be an array of names");
  std::vector<std::string> known;
  for (const Output& output : outputTable()) known.emplace_back(output.name);
  scene.outputs.clear();
  for (const auto& item : v) {
    if (!item.is_string() ||
        std::find(known.begin(), known.end(), item.get<std::string>()) == known.end()) {
      std::string list;
      for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
      j.fail("outputs", "unknown output " + brief(item) + " (known: " + list + ")");
    }
    scene.outputs.push_back(item.get<std::string>());
  }
}

// --- surface ----------------------------------------------------------------------------------

void readSample(JsonSection& j, Scene& scene) { scene.surface.sample = j.text("sample", ""); }

void readFile(JsonSection& j, Scene& scene) {
  if (!j.has("file")) return;
  const std::string file = j.text("file", "");
  if (file.empty()) j.fail("file", "must not be empty");
  const std::filesystem::path p(file);
  scene.surface.file = p.is_absolute() ? p : scene.path.parent_path() / p;
}

void readParams(JsonSection& j, Scene& scene) {
  if (!j.has("params")) return;
  const json& params = j.raw("params");
  if (!params.is_object()) j.fail("params", "must be an object of numbers");
  for (auto it = params.begin(); it != params.end(); ++it) {
    const json& v = it.value();
    if (v.is_boolean()) {
      scene.surface.params[it.key()] = v.get<bool>() ? 1.0 : 0.0;
    } else if (v.is_number() && std::isfinite(v.get<double>())) {
      scene.surface.params[it.key()] = v.get<double>();
    } else {
      j.fail("params." + it.key(), "must be a number or a boolean, got " + brief(v));
    }
  }
}

void checkSurface(JsonSection& j, Scene& scene) {
  const SurfaceSource& s = scene.surface;
  const bool sample = j.has("sample"), file = j.has("file");
  if (sample == file) j.fail("", "give exactly one of \"sample\" or \"file\"");
  if (file && !s.params.empty()) j.fail("params", "only applies to a sample, not to a mesh file");
}

bool isSample(const Scene& scene) { return !scene.surface.sample.empty(); }

// --- patching ---------------------------------------------------------------------------------

void readWorkflow(JsonSection& j, Scene& scene) {
  scene.patching.workflowGiven = j.has("workflow");
  scene.patching.workflow = j.integer("workflow", scene.patching.workflow, 1, 2);
}

void readBlockGrid(JsonSection& j, Scene& scene) {
  if (!j.has("block_grid")) return;
  const json& v = j.raw("block_grid");
  // Compared as 64-bit integers (get<int> wrapped 4294967297 to 1), an unsigned one as unsigned.
  const auto count = [](const json& x) {
    return x.is_number_integer() &&
           (x.is_number_unsigned() ? x.get<unsigned long long>() <= 16
                                   : x.get<long long>() >= 1 && x.get<long long>() <= 16) &&
           x.get<long long>() >= 1;
  };
  if (!v.is_array() || v.size() != 2 || !count(v[0]) || !count(v[1]))
    j.fail("block_grid",
           "must be two patch counts [along u, along v], each 1..16, got " + brief(v));
  scene.patching.workflow2.blockGrid = {v[0].get<int>(), v[1].get<int>()};
}

void readCorners(JsonSection& j, Scene& scene) {
  if (!j.has("corners")) return;
  const json& corners = j.raw("corners");
  if (!corners.is_array() || corners.empty())
    j.fail("corners", "must be a non-empty array of points [x, y, z]");
  if (corners.size() > 4 * kMaxPatches)
    j.fail("corners", "has " + std::to_string(corners.size()) + " corners; at most " +
                          std::to_string(4 * kMaxPatches));
  for (size_t i = 0; i < corners.size(); ++i)
    scene.patching.corners.push_back(point3(corners[i], j, "corners[" + std::to_string(i) + "]"));
}

void readPatches(JsonSection& j, Scene& scene) {
  PatchingChoice& out = scene.patching;
  if (!j.has("patches")) {
    if (!out.corners.empty())
      j.fail("corners", "given without \"patches\" (quads of corner indices)");
    return;
  }
  const json& patches = j.raw("patches");
  if (!patches.is_array())
    j.fail("patches",
           "must be an array of patches, each four corners [x, y, z] (or four corner indices)");
  if (patches.size() > kMaxPatches)
    j.fail("patches", "has " + std::to_string(patches.size()) + " patches; at most " +
                          std::to_string(kMaxPatches));
  const bool indexed = !out.corners.empty();
  for (size_t i = 0; i < patches.size(); ++i) {
    const std::string key = "patches[" + std::to_string(i) + "]";
    if (!patches[i].is_array() || patches[i].size() != 4)
      j.fail(key, "a patch must have exactly four corners");
    std::array<Eigen::Vector3d, 4> corners;
    std::array<int, 4> quad{};
    for (int c = 0; c < 4; ++c) {
      const json& v = patches[i][c];
      if (indexed) {
        if (!v.is_number_integer() || v.get<long long>() < 0 ||
            v.get<long long>() >= static_cast<long long>(out.corners.size()))
          j.fail(key, "with \"corners\" given, a patch is four indices into it (0 .. " +
                          std::to_string(out.corners.size() - 1) + "), got " + brief(v));
        quad[c] = static_cast<int>(v.get<long long>());
        corners[c] = out.corners[quad[c]];
      } else {
        corners[c] = point3(v, j, key);
        // Corners given twice (by neighbouring patches) are one corner of the layout.
        int found = -1;
        for (size_t k = 0; k < out.corners.size() && found < 0; ++k)
          if ((out.corners[k] - corners[c]).norm() <= 1e-9 * (1.0 + corners[c].norm()))
            found = static_cast<int>(k);
        if (found < 0)
          found = static_cast<int>(out.corners.size()), out.corners.push_back(corners[c]);
        quad[c] = found;
      }
    }
    // The same corner twice, or a patch given twice (its lamellas and mass counted twice).
    std::array<int, 4> sorted = quad;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      j.fail(key, "names one corner twice: a patch needs four distinct corners");
    for (size_t k = 0; k < out.quads.size(); ++k) {
      std::array<int, 4> other = out.quads[k];
      std::sort(other.begin(), other.end());
      if (other == sorted)
        j.fail(key, "has the corners of patches[" + std::to_string(k) + "]: a patch given twice");
    }
    out.patches.push_back(corners);
    out.quads.push_back(quad);
  }
}

void checkPatching(JsonSection& j, Scene& scene) {
  const PatchingChoice& p = scene.patching;
  if (scene.design().uniqueness.etaMax <= 1.0)
    j.fail("eta_max", "must be greater than 1 (a ratio of geodesic lengths)");
  const AlphaBarOptions& a = scene.design().alphaBar;
  if (a.slopeMin >= 1.0 || a.slopeMax <= 1.0)
    j.fail("slope_bounds", "must be [k_min, k_max] with k_min < 1 < k_max (Problem 2.3)");
  if (p.workflowGiven && p.workflow == 1 && p.quads.empty())
    j.fail("workflow", "Workflow 1 splits an initial layout: give it as \"patches\"");
  if (p.workflow2.blockGrid[0] > 0 && !p.quads.empty())
    j.fail("block_grid",
           "sets Workflow 2's grid of patches; this scene gives its layout as \"patches\"");
}

// --- grid -------------------------------------------------------------------------------------

void readMembersPerFamily(JsonSection& j, Scene& scene) {
  if (!j.has("members_per_family")) return;
  const json& v = j.raw("members_per_family");
  if (v.is_string() && v.get<std::string>() == "auto") {
    scene.design().members.count = 0;
  } else if (v.is_number_integer() && v.get<long long>() >= 2 && v.get<long long>() <= 10000) {
    scene.design().members.count = static_cast<int>(v.get<long long>());
  } else {
    j.fail("members_per_family", "must be \"auto\" or an integer in [2, 10000], got " + brief(v));
  }
}

void readAlphaBar(JsonSection& j, Scene& scene) {
  if (!j.has("alpha_bar")) return;
  const json& v = j.raw("alpha_bar");
  AlphaBarOptions& a = scene.design().alphaBar;
  if (v.is_string()) {
    const std::string mode = v.get<std::string>();
    if (mode == "min")
      a.choice = AlphaBarChoice::Min;
    else if (mode == "max")
      a.choice = AlphaBarChoice::Max;
    else if (mode == "unrolled")
      a.choice = AlphaBarChoice::Unrolled;
    else
      j.fail("alpha_bar",
             "must be \"min\", \"max\", \"unrolled\" or an angle in radians, got " + brief(v));
  } else if (v.is_number()) {
    const double angle = v.get<double>();
    if (!(angle > 0.0 && angle < M_PI)) j.fail("alpha_bar", "an angle must lie in (0, pi) radians");
    a.choice = AlphaBarChoice::Given;
    a.givenAlphaBar = angle;
  } else {
    j.fail("alpha_bar", "must be a string or a number, got " + brief(v));
  }
}

json alphaBarSchema() {
  const json modes = {{"enum", json::array({"min", "max", "unrolled"})}};
  const json angle = {{"type", "number"}, {"exclusiveMinimum", 0}, {"exclusiveMaximum", M_PI}};
  return {{"anyOf", json::array({modes, angle})}};
}

json alphaBarJson(const AlphaBarOptions& a) {
  switch (a.choice) {
    case AlphaBarChoice::Min: return "min";
    case AlphaBarChoice::Max: return "max";
    case AlphaBarChoice::Unrolled: return "unrolled";
    case AlphaBarChoice::Given: return a.givenAlphaBar;
  }
  return nullptr;
}

void checkGrid(JsonSection& j, Scene& scene) {
  const int proxy = scene.design().maps.proxyVertices;
  if (proxy > 0 && proxy < 8)
    j.fail("map_proxy_vertices",
           "must be 0 (maps on the patch itself) or at least 8, got " + std::to_string(proxy));
}

std::vector<SceneSection> makeSections() {
  using namespace field;
  std::vector<SceneSection> sections;

  sections.push_back(
      {"",
       "The scene itself.",
       {{"name", "string",
         "the scene's name: the default run folder out/<name> (default: the file's stem)", readName,
         [](const Scene& s) { return some(s.name); }, stringSchema()},
        {"outputs", "array of names",
         "what the run writes: report, plan, cut_files, stickers, supports, previews (default: "
         "these six), fem (the FE check: fem/), model (the 3D model: model.glb, model.3dm, "
         "model.obj, supports.glb/.stl)",
         readOutputs, [](const Scene& s) { return some(s.outputs); }, outputsSchema()}},
       {}});

  sections.push_back(
      {"surface",
       "The design surface (Section 4.4.1): a procedural sample or a mesh file. Required.",
       {{"sample", "string",
         "a procedural sample (`egg surface --list`); exactly one of sample and file", readSample,
         [](const Scene& s) { return isSample(s) ? some(s.surface.sample) : std::nullopt; },
         sampleSchema()},
        {"file", "string", "a mesh file (OBJ, STL, PLY, OFF, glTF), relative to the scene's folder",
         readFile,
         [](const Scene& s) { return isSample(s) ? std::nullopt : some(s.surface.file.string()); },
         stringSchema()},
        {"params",
         "object of numbers",
         "the sample's parameters (`egg surface --list`)",
         readParams,
         [](const Scene& s) { return isSample(s) ? some(s.surface.params) : std::nullopt; },
         {{"type", "object"},
          {"additionalProperties", {{"type", json::array({"number", "boolean"})}}}}},
        {"edge_length_m", "number in (0, 10000]",
         "target triangle edge length of a sample (default: the sample's own)",
         [](JsonSection& j, Scene& s) {
           s.surface.edgeLengthM = j.positive(
               "edge_length_m", isSample(s) ? defaultSampleEdgeLength(s.surface.sample) : 1.0, 1e4);
         },
         [](const Scene& s) { return isSample(s) ? some(s.surface.edgeLengthM) : std::nullopt; },
         positiveSchema(1e4)},
        {"scale_to_m", "number in (0, 1e+06]", "a mesh file's coordinates times this are metres",
         [](JsonSection& j, Scene& s) {
           s.surface.scaleToM = j.positive("scale_to_m", s.surface.scaleToM, 1e6);
         },
         [](const Scene& s) { return isSample(s) ? std::nullopt : some(s.surface.scaleToM); },
         positiveSchema(1e6)},
        boolean("keep_largest_component", EGG_AT(surface.keepLargestComponent),
                "keep the largest connected component of a mesh file (with a warning) instead of "
                "failing")},
       checkSurface});

  sections.push_back(
      {"patching",
       "How the surface is split into geodesic patches (Sections 3.3, 3.4) and each is checked.",
       {{"workflow", "integer in [1, 2]",
         "Workflow 1 (split a given layout) or 2 (propose one, then split), Section 3.4.3; a "
         "layout without it is taken as given",
         readWorkflow,
         [](const Scene& s) {
           return s.patching.workflowGiven || s.patching.quads.empty() ? some(s.patching.workflow)
                                                                       : std::nullopt;
         },
         integerSchema(1, 2)},
        number("eta_max", EGG_AT(design().uniqueness.etaMax), 1.0, 2.0,
               "largest ratio of geodesic lengths a patch may have (uniqueness, Sections 2.3.3, "
               "3.4.1)"),
        {"slope_bounds", "two numbers in [1e-06, 1e+06]",
         "[k_min, k_max] of the cladding functions' slopes (Problem 2.3)",
         [](JsonSection& j, Scene& s) {
           AlphaBarOptions& a = s.design().alphaBar;
           const auto bounds = j.pair("slope_bounds", {a.slopeMin, a.slopeMax}, 1e-6, 1e6);
           a.slopeMin = bounds[0], a.slopeMax = bounds[1];
         },
         [](const Scene& s) {
           return some(
               std::array<double, 2>{s.design().alphaBar.slopeMin, s.design().alphaBar.slopeMax});
         },
         pairSchema(1e-6, 1e6)},
        positive("max_patch_size_m", EGG_AT(patching.workflow2.maxPatchSizeM), 1e5,
                 "largest patch diagonal Workflow 2 proposes (handling on site, 3.5.3)"),
        {"block_grid",
         "two integers in [1, 16]",
         "Workflow 2's grid of patches [along u, along v] (default: screened)",
         readBlockGrid,
         [](const Scene& s) {
           return s.patching.workflow2.blockGrid[0] > 0 ? some(s.patching.workflow2.blockGrid)
                                                        : std::nullopt;
         },
         {{"type", "array"}, {"items", integerSchema(1, 16)}, {"minItems", 2}, {"maxItems", 2}}},
        integer("max_splits", EGG_AT(patching.layout.maxSplits), 0, 10000,
                "Workflow 1: splits before it gives up"),
        {"generalised_infill",
         "true or false",
         "close the cut-offs the quad patches leave (along holes and curved design boundaries) "
         "with generalised patches (Chapter 4); default: yes in the workflows, no for a given "
         "layout",
         [](JsonSection& j, Scene& s) {
           if (j.has("generalised_infill"))
             s.patching.generalisedInfill = j.boolean("generalised_infill", true);
         },
         [](const Scene& s) {
           return s.patching.generalisedInfill ? some(*s.patching.generalisedInfill) : std::nullopt;
         },
         {{"type", "boolean"}}},
        {"smoothing",
         "true or false",
         "smooth a patch whose eta fails (2.3.3); default: yes for a given layout, no in the "
         "workflows (they split)",
         [](JsonSection& j, Scene& s) {
           if (j.has("smoothing")) s.patching.smoothing = j.boolean("smoothing", true);
         },
         [](const Scene& s) {
           return s.patching.smoothing ? some(*s.patching.smoothing) : std::nullopt;
         },
         {{"type", "boolean"}}},
        number("min_patch_size_m", EGG_AT(patching.layout.minSideM), 0.0, 1e5,
               "Workflow 1: no split makes a side shorter than this (0: 2.5 mean edge lengths)"),
        {"corners",
         "array of [x, y, z]",
         "a given layout's corners on the surface, metres (with patches as index quads)",
         readCorners,
         [](const Scene& s) {
           json corners = json::array();
           for (const auto& c : s.patching.corners) corners.push_back(pointJson(c));
           return corners.empty() ? std::nullopt : some(corners);
         },
         {{"type", "array"},
          {"items", kPointSchema},
          {"minItems", 1},
          {"maxItems", 4 * kMaxPatches}}},
        {"patches", "array of four corners",
         "a given layout: per patch four corners [x, y, z], or four indices into corners (a corner "
         "may lie on another patch's side: a T-junction)",
         readPatches,
         [](const Scene& s) {
           return s.patching.quads.empty() ? std::nullopt : some(s.patching.quads);
         },
         patchesSchema()}},
       checkPatching});

  sections.push_back(
      {"grid",
       "Every patch's planar grid (Sections 2.4.3-2.4.6).",
       {{"members_per_family",
         "\"auto\" or an integer in [2, 10000]",
         "members of each family, boundary members included; auto: from the spacing below (2.4.4)",
         readMembersPerFamily,
         [](const Scene& s) {
           return s.design().members.count > 0 ? some(s.design().members.count) : some("auto");
         },
         {{"anyOf", json::array({{{"const", "auto"}}, integerSchema(2, 10000)})}}},
        number("member_spacing_factor", EGG_AT(design().members.spacingFactor), 2.0, 1000.0,
               "auto members: target spacing between members = this x the lamella width (2.4.4)"),
        integer("map_resolution", EGG_AT(design().maps.resolution), 8, 2000,
                "samples per side of the distance maps (2.4.1)"),
        number("map_tolerance_relative", EGG_AT(design().maps.toleranceRelative), 0.0, 0.1,
               "largest miss of a map row interpolated between exact ones, over the shorter side; "
               "0: every row exact"),
        integer("map_proxy_vertices", EGG_AT(design().maps.proxyVertices), 0, 10000000,
                "distance maps on a coarse proxy of at most this many vertices (0: on the patch "
                "itself)"),
        number("min_planar_angle_rad", EGG_AT(design().alphaBar.minPlanarAngle), 0.0, 0.78,
               "smallest inner angle of the planar quad, so that the cut grid does not fold flat "
               "(criterion iv)"),
        {"alpha_bar", "\"min\", \"max\", \"unrolled\" or radians in (0, pi)",
         "which alpha_bar of the feasible range the grid is built at (Problem 2.3)", readAlphaBar,
         [](const Scene& s) { return some(alphaBarJson(s.design().alphaBar)); }, alphaBarSchema()}},
       checkGrid});

  addStructureSections(sections);  // scene_fields_structure.cpp
  return sections;
}

}  // namespace

const std::vector<SceneSection>& sceneSections() {
  static const std::vector<SceneSection> sections = makeSections();
  return sections;
}

}  // namespace egg::pipeline
