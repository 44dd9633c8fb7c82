#include "apps/commands/scene.hpp"

#include "apps/commands/report.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/json_check.hpp"
#include "core/materials/materials.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace egg::app {
namespace {

using nlohmann::json;

// Deepest nesting of objects and arrays a scene file may have (the real ones nest 4 levels).
constexpr int kMaxSceneDepth = 64;
// Largest scene file read (a layout of kMaxPatches patches is a few MB).
constexpr std::size_t kMaxSceneBytes = 64u << 20;
// Most patches a given layout may have (each is minutes of work at most; 10,000 ran for hours).
constexpr std::size_t kMaxPatches = 1000;

// A JSON value for a message: at most ~200 characters, never recursing deeper than a few levels,
// so that a huge or deeply nested value neither floods stderr nor overflows the stack.
void renderBrief(const json& v, int depth, std::string& out, std::size_t limit) {
  if (out.size() > limit) return;
  if (v.is_string()) {
    const std::string& text = v.get_ref<const std::string&>();
    out += json(text.substr(0, limit)).dump(-1, ' ', false, json::error_handler_t::replace);
  } else if (v.is_array() || v.is_object()) {
    const bool array = v.is_array();
    out += array ? "[" : "{";
    if (depth >= 4 && !v.empty()) {
      out += "...";
    } else {
      bool first = true;
      for (auto it = v.begin(); it != v.end() && out.size() <= limit; ++it) {
        if (!first) out += ", ";
        first = false;
        if (!array) out += json(it.key().substr(0, limit)).dump(-1, ' ', false, json::error_handler_t::replace) + ": ";
        renderBrief(it.value(), depth + 1, out, limit);
      }
    }
    out += array ? "]" : "}";
  } else {
    out += v.dump();
  }
}

std::string brief(const json& v, std::size_t limit = 200) {
  std::string out;
  renderBrief(v, 0, out, limit);
  if (out.size() > limit) out = out.substr(0, limit) + "...";
  return out;
}

// Reads one JSON object, remembering its dotted path for messages and which keys were consumed,
// so that anything left over is reported as an unknown key.
class Section {
 public:
  Section(const json& node, std::string path, std::string origin)
      : node_(node), path_(std::move(path)), origin_(std::move(origin)) {
    if (!node_.is_object()) fail("", "must be an object");
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const std::string field = abbreviate(dotted(key));
    throw InvalidInput(abbreviate(origin_) + ": " + field + (field.empty() ? "" : ": ") + what);
  }

  std::string dotted(const std::string& key) const {
    if (path_.empty()) return key;
    return key.empty() ? path_ : path_ + "." + key;
  }

  bool has(const std::string& key) {
    known_.insert(key);
    return node_.contains(key);
  }

  const json& raw(const std::string& key) {
    known_.insert(key);
    return node_.at(key);
  }

  double number(const std::string& key, double fallback, double lo, double hi) {
    if (!has(key)) return fallback;
    const json& v = node_.at(key);
    if (!v.is_number()) fail(key, "must be a number, got " + brief(v));
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi) {
      std::ostringstream msg;
      msg << "must lie in [" << lo << ", " << hi << "], got " << x;
      fail(key, msg.str());
    }
    return x;
  }

  double positive(const std::string& key, double fallback, double hi = 1e9) {
    const double x = number(key, fallback, 0.0, hi);
    if (x <= 0.0) fail(key, "must be positive");
    return x;
  }

  int integer(const std::string& key, int fallback, int lo, int hi) {
    if (!has(key)) return fallback;
    const json& v = node_.at(key);
    if (!v.is_number_integer()) fail(key, "must be an integer, got " + brief(v));
    // An unsigned above LLONG_MAX would wrap to a negative long long: compare it as unsigned.
    if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi))
      fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + brief(v));
    const long long x = v.get<long long>();
    if (x < lo || x > hi) fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
    return static_cast<int>(x);
  }

  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const json& v = node_.at(key);
    if (!v.is_boolean()) fail(key, "must be true or false, got " + brief(v));
    return v.get<bool>();
  }

  std::string text(const std::string& key, const std::string& fallback) {
    if (!has(key)) return fallback;
    const json& v = node_.at(key);
    if (!v.is_string()) fail(key, "must be a string, got " + brief(v));
    return v.get<std::string>();
  }

  std::array<double, 2> pair(const std::string& key, std::array<double, 2> fallback, double lo, double hi) {
    if (!has(key)) return fallback;
    const json& v = node_.at(key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
      fail(key, "must be an array of two numbers, got " + brief(v));
    }
    std::array<double, 2> out{v[0].get<double>(), v[1].get<double>()};
    for (double x : out) {
      if (!std::isfinite(x) || x < lo || x > hi) fail(key, "values must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return out;
  }

  Section child(const std::string& key) {
    known_.insert(key);
    static const json empty = json::object();
    return Section(node_.contains(key) ? node_.at(key) : empty, dotted(key), origin_);
  }

  // Call after reading: every key present must have been asked for.
  void rejectUnknownKeys() const {
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      if (!known_.count(it.key())) {
        std::string allowed;
        for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
        fail(it.key(), "unknown key (allowed here: " + allowed + ")");
      }
    }
  }

 private:
  const json& node_;
  std::string path_;
  std::string origin_;
  std::set<std::string> known_;
};

Eigen::Vector3d point3(const json& v, const Section& where, const std::string& key) {
  if (!v.is_array() || v.size() != 3) where.fail(key, "a corner must be [x, y, z], got " + brief(v));
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) where.fail(key, "corner coordinates must be finite numbers, got " + brief(v));
    p[i] = v[i].get<double>();
  }
  return p;
}

void readSurface(Section s, Scene& scene) {
  SurfaceSpec& out = scene.surface;
  const bool hasSample = s.has("sample");
  const bool hasFile = s.has("file");
  if (hasSample == hasFile) s.fail("", "give exactly one of \"sample\" or \"file\"");
  out.sample = s.text("sample", "");
  const std::string file = s.text("file", "");
  if (hasFile) {
    if (file.empty()) s.fail("file", "must not be empty");
    std::filesystem::path p(file);
    out.file = p.is_absolute() ? p : scene.path.parent_path() / p;
  }
  out.edge_length_m = s.positive("edge_length_m", hasSample ? defaultSampleEdgeLength(out.sample) : 1.0, 1e4);
  out.scale_to_m = s.positive("scale_to_m", out.scale_to_m, 1e6);
  out.keep_largest_component = s.boolean("keep_largest_component", out.keep_largest_component);
  if (s.has("params")) {
    const json& params = s.raw("params");
    if (!params.is_object()) s.fail("params", "must be an object of numbers");
    for (auto it = params.begin(); it != params.end(); ++it) {
      const json& v = it.value();
      if (v.is_boolean()) {
        out.params[it.key()] = v.get<bool>() ? 1.0 : 0.0;
      } else if (v.is_number() && std::isfinite(v.get<double>())) {
        out.params[it.key()] = v.get<double>();
      } else {
        s.fail("params." + it.key(), "must be a number or a boolean, got " + brief(v));
      }
    }
  }
  if (hasFile && !out.params.empty()) s.fail("params", "only applies to a sample, not to a mesh file");
  s.rejectUnknownKeys();
}

void readPatching(Section s, PatchingSpec& out) {
  out.workflow_given = s.has("workflow");
  out.workflow = s.integer("workflow", out.workflow, 1, 2);
  out.eta_max = s.number("eta_max", out.eta_max, 1.0, 2.0);
  if (out.eta_max <= 1.0) s.fail("eta_max", "must be greater than 1 (a ratio of geodesic lengths)");
  out.slope_bounds = s.pair("slope_bounds", out.slope_bounds, 1e-6, 1e6);
  if (out.slope_bounds[0] >= 1.0 || out.slope_bounds[1] <= 1.0) {
    s.fail("slope_bounds", "must be [k_min, k_max] with k_min < 1 < k_max (Problem 2.3)");
  }
  out.max_patch_size_m = s.positive("max_patch_size_m", out.max_patch_size_m, 1e5);
  if (s.has("block_grid")) {
    const json& v = s.raw("block_grid");
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer() || v[0].get<int>() < 1 ||
        v[0].get<int>() > 16 || v[1].get<int>() < 1 || v[1].get<int>() > 16)
      s.fail("block_grid", "must be two patch counts [along u, along v], each 1..16, got " + brief(v));
    out.block_grid = {v[0].get<int>(), v[1].get<int>()};
  }
  out.max_splits = s.integer("max_splits", out.max_splits, 0, 10000);
  if (s.has("smoothing")) out.smoothing = s.boolean("smoothing", true);
  out.min_patch_size_m = s.number("min_patch_size_m", out.min_patch_size_m, 0.0, 1e5);
  if (s.has("corners")) {
    const json& corners = s.raw("corners");
    if (!corners.is_array() || corners.empty()) s.fail("corners", "must be a non-empty array of points [x, y, z]");
    if (corners.size() > 4 * kMaxPatches)
      s.fail("corners", "has " + std::to_string(corners.size()) + " corners; at most " + std::to_string(4 * kMaxPatches));
    for (size_t i = 0; i < corners.size(); ++i) out.corners.push_back(point3(corners[i], s, "corners[" + std::to_string(i) + "]"));
  }
  if (s.has("patches")) {
    const json& patches = s.raw("patches");
    if (!patches.is_array()) s.fail("patches", "must be an array of patches, each four corners [x, y, z] (or four corner indices)");
    if (patches.size() > kMaxPatches)
      s.fail("patches", "has " + std::to_string(patches.size()) + " patches; at most " + std::to_string(kMaxPatches));
    const bool indexed = !out.corners.empty();
    for (size_t i = 0; i < patches.size(); ++i) {
      const std::string key = "patches[" + std::to_string(i) + "]";
      if (!patches[i].is_array() || patches[i].size() != 4) s.fail(key, "a patch must have exactly four corners");
      std::array<Eigen::Vector3d, 4> corners;
      std::array<int, 4> quad{};
      for (int c = 0; c < 4; ++c) {
        const json& v = patches[i][c];
        if (indexed) {
          if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() >= static_cast<long long>(out.corners.size()))
            s.fail(key, "with \"corners\" given, a patch is four indices into it (0 .. " + std::to_string(out.corners.size() - 1) +
                            "), got " + brief(v));
          quad[c] = static_cast<int>(v.get<long long>());
          corners[c] = out.corners[quad[c]];
        } else {
          corners[c] = point3(v, s, key);
          // Corners given twice (by neighbouring patches) are one corner of the layout.
          int found = -1;
          for (size_t k = 0; k < out.corners.size() && found < 0; ++k)
            if ((out.corners[k] - corners[c]).norm() <= 1e-9 * (1.0 + corners[c].norm())) found = static_cast<int>(k);
          if (found < 0) found = static_cast<int>(out.corners.size()), out.corners.push_back(corners[c]);
          quad[c] = found;
        }
      }
      out.patches.push_back(corners);
      out.quads.push_back(quad);
    }
  } else if (!out.corners.empty()) {
    s.fail("corners", "given without \"patches\" (quads of corner indices)");
  }
  if (out.workflow_given && out.workflow == 1 && out.quads.empty())
    s.fail("workflow", "Workflow 1 splits an initial layout: give it as \"patches\"");
  if (out.block_grid[0] > 0 && !out.quads.empty())
    s.fail("block_grid", "sets Workflow 2's grid of patches; this scene gives its layout as \"patches\"");
  s.rejectUnknownKeys();
}

void readGrid(Section s, GridSpec& out) {
  if (s.has("members_per_family")) {
    const json& v = s.raw("members_per_family");
    if (v.is_string() && v.get<std::string>() == "auto") {
      out.members_per_family.reset();
    } else if (v.is_number_integer() && v.get<long long>() >= 2 && v.get<long long>() <= 10000) {
      out.members_per_family = static_cast<int>(v.get<long long>());
    } else {
      s.fail("members_per_family", "must be \"auto\" or an integer in [2, 10000], got " + brief(v));
    }
  }
  out.member_spacing_factor = s.number("member_spacing_factor", out.member_spacing_factor, 2.0, 1000.0);
  out.map_resolution = s.integer("map_resolution", out.map_resolution, 8, 2000);
  out.map_tolerance_relative = s.number("map_tolerance_relative", out.map_tolerance_relative, 0.0, 0.1);
  out.map_proxy_vertices = s.integer("map_proxy_vertices", out.map_proxy_vertices, 0, 10000000);
  if (out.map_proxy_vertices > 0 && out.map_proxy_vertices < 8)
    s.fail("map_proxy_vertices", "must be 0 (maps on the patch itself) or at least 8, got " + std::to_string(out.map_proxy_vertices));
  out.min_planar_angle_rad = s.number("min_planar_angle_rad", out.min_planar_angle_rad, 0.0, 0.78);
  if (s.has("alpha_bar")) {
    const json& v = s.raw("alpha_bar");
    if (v.is_string()) {
      const std::string mode = v.get<std::string>();
      if (mode != "min" && mode != "max" && mode != "unrolled") {
        s.fail("alpha_bar", "must be \"min\", \"max\", \"unrolled\" or an angle in radians, got " + brief(v));
      }
      out.alpha_bar = mode;
    } else if (v.is_number()) {
      const double a = v.get<double>();
      if (!(a > 0.0 && a < M_PI)) s.fail("alpha_bar", "an angle must lie in (0, pi) radians");
      out.alpha_bar = "value";
      out.alpha_bar_rad = a;
    } else {
      s.fail("alpha_bar", "must be a string or a number, got " + brief(v));
    }
  }
  s.rejectUnknownKeys();
}

void readLamella(Section s, LamellaSpec& out) {
  out.width_m = s.positive("width_m", out.width_m, 10.0);
  out.thickness_m = s.positive("thickness_m", out.thickness_m, 10.0);
  out.material = s.text("material", out.material);
  try {
    materialByName(out.material);
  } catch (const InvalidInput& e) {
    s.fail("material", abbreviate(e.what(), 400));
  }
  if (out.thickness_m > out.width_m) s.fail("thickness_m", "must not exceed width_m (a lamella bends about its weak axis)");
  s.rejectUnknownKeys();
}

void readSimulation(Section s, SimulationSpec& out) {
  out.enabled = s.boolean("enabled", out.enabled);
  out.gravity = s.boolean("gravity", out.gravity);
  out.friction_mu = s.number("friction_mu", out.friction_mu, 0.0, 2.0);
  out.notches = s.boolean("notches", out.notches);
  out.compare_without_notches = s.boolean("compare_without_notches", out.compare_without_notches);
  out.supports = s.text("supports", out.supports);
  if (out.supports != "auto" && out.supports != "anchors" && out.supports != "design_boundary")
    s.fail("supports", "must be \"auto\", \"anchors\" or \"design_boundary\", got \"" + out.supports + "\"");
  out.hold_shared_sides = s.boolean("hold_shared_sides", out.hold_shared_sides);
  out.join_patches = s.boolean("join_patches", out.join_patches);
  out.fasten_bolts = s.boolean("fasten_bolts", out.fasten_bolts);
  out.newton_tolerance = s.number("newton_tolerance", out.newton_tolerance, 1e-16, 1e-2);
  out.time_limit_s = s.number("time_limit_s", out.time_limit_s, 0.1, 1e6);
  s.rejectUnknownKeys();
}

void readFabrication(Section s, FabricationSpec& out) {
  out.enabled = s.boolean("enabled", out.enabled);
  out.sheet_mm = s.pair("sheet_mm", out.sheet_mm, 1.0, 1e5);
  out.bolt_diameter_mm = s.positive("bolt_diameter_mm", out.bolt_diameter_mm, 1000.0);
  out.kerf_mm = s.number("kerf_mm", out.kerf_mm, 0.0, 100.0);
  out.margin_mm = s.number("margin_mm", out.margin_mm, 0.0, 1e4);
  if (2.0 * out.margin_mm >= std::min(out.sheet_mm[0], out.sheet_mm[1])) s.fail("margin_mm", "leaves no room on the sheet");
  out.min_notch_mm = s.number("min_notch_mm", out.min_notch_mm, 0.0, 1e4);
  out.stock_length_mm = s.positive("stock_length_mm", out.stock_length_mm, 1e6);
  auto optionalNumber = [&](const char* key, std::optional<double>& value, double lo, double hi) {
    if (s.has(key)) value = s.number(key, 0.0, lo, hi);
  };
  optionalNumber("end_overhang_mm", out.end_overhang_mm, 0.0, 1e4);
  optionalNumber("splice_clearance_mm", out.splice_clearance_mm, 0.0, 1e5);
  optionalNumber("min_splice_clearance_mm", out.min_splice_clearance_mm, 0.0, 1e5);
  optionalNumber("label_height_mm", out.label_height_mm, 0.1, 1000.0);
  out.splice_joint = s.text("splice_joint", out.splice_joint);
  if (out.splice_joint != "plate" && out.splice_joint != "scarf" && out.splice_joint != "plate_or_scarf")
    s.fail("splice_joint", "must be \"plate\", \"scarf\" or \"plate_or_scarf\", got \"" + out.splice_joint + "\"");
  out.scarf_slope = s.number("scarf_slope", out.scarf_slope, 4.0, 40.0);
  out.scarf_efficiency = s.number("scarf_efficiency", out.scarf_efficiency, 0.01, 1.0);
  out.sticker_margin_mm = s.number("sticker_margin_mm", out.sticker_margin_mm, 0.0, 1000.0);
  if (s.has("sticker_sheet_mm")) out.sticker_sheet_mm = s.pair("sticker_sheet_mm", out.sheet_mm, 1.0, 1e5);
  optionalNumber("ground_height_m", out.ground_height_m, -1e5, 1e5);
  optionalNumber("support_block_mm", out.support_block_mm, 1.0, 1e5);
  out.supports_at_boundary_connections = s.boolean("supports_at_boundary_connections", out.supports_at_boundary_connections);
  s.rejectUnknownKeys();
}

const std::vector<std::string>& knownOutputs() {
  static const std::vector<std::string> names{"report", "plan", "cut_files", "stickers", "supports", "previews"};
  return names;
}

}  // namespace

double defaultSampleEdgeLength(const std::string& sample) {
  // The architectural scenes are tens of metres across; the test surfaces a few metres. These
  // give meshes of a few thousand to ~15k vertices, enough for the 0.15 % eta test (Section 2.3.3).
  if (sample == "great_court" || sample == "lilium") return 1.0;
  if (sample == "yas") return 2.0;
  return 0.25;
}

bool Scene::wants(const std::string& output) const {
  return std::find(outputs.begin(), outputs.end(), output) != outputs.end();
}

Scene parseScene(const json& document, const std::filesystem::path& origin) {
  Scene scene;
  scene.path = origin;
  Section top(document, "", origin.string());
  scene.name = top.text("name", origin.stem().string());
  // The name becomes the default run folder out/<name>: it must be a plain, portable folder name,
  // never a path that climbs out of out/ or names out/ itself (a name "\u0000" once named "out/."),
  // and short enough that the staging folder's name beside it fits NAME_MAX.
  if (const std::string problem = portableNameProblem(scene.name, kMaxRunFolderName); !problem.empty())
    top.fail("name", "must be a plain folder name (" + problem + "), got " + brief(json(scene.name)));
  if (scene.name.front() == '.')
    top.fail("name", "must be a plain name (no '/', '\\', not starting with '.'), got " + brief(json(scene.name)));
  if (!top.has("surface")) top.fail("surface", "is required ({\"sample\": ...} or {\"file\": ...})");
  readSurface(top.child("surface"), scene);
  readPatching(top.child("patching"), scene.patching);
  readGrid(top.child("grid"), scene.grid);
  readLamella(top.child("lamella"), scene.lamella);
  readSimulation(top.child("simulation"), scene.simulation);
  readFabrication(top.child("fabrication"), scene.fabrication);
  if (top.has("outputs")) {
    const json& v = top.raw("outputs");
    if (!v.is_array()) top.fail("outputs", "must be an array of names");
    scene.outputs.clear();
    for (const auto& item : v) {
      const auto& names = knownOutputs();
      if (!item.is_string() || std::find(names.begin(), names.end(), item.get<std::string>()) == names.end()) {
        top.fail("outputs", "unknown output " + brief(item) + " (known: report, plan, cut_files, stickers, supports, previews)");
      }
      scene.outputs.push_back(item.get<std::string>());
    }
  }
  top.rejectUnknownKeys();
  return scene;
}

Scene parseSceneText(const std::string& text, const std::filesystem::path& origin) {
  const std::string where = abbreviate(origin.string());
  // One linear pass first: nesting, numbers that overflow a double, valid JSON, named by position.
  const JsonCheck check = checkJsonText(text, kMaxSceneDepth);
  if (!check.ok) throw InvalidInput(where + ": " + (check.path.empty() ? "" : check.path + ": ") + check.problem);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {
    throw InvalidInput(where + ": not valid JSON: " + abbreviate(e.what(), 400));
  }
  return parseScene(document, origin);
}

std::filesystem::path benchSceneFile(const std::string& name) {
  const bool file = name.size() > 5 && name.substr(name.size() - 5) == ".json";
  return file ? std::filesystem::path(name) : std::filesystem::path("samples") / (name + ".json");
}

Scene loadScene(const std::filesystem::path& path) {
  // A folder, a FIFO or a device is refused before any read (a FIFO would block forever).
  return parseSceneText(readRegularFile(path, kMaxSceneBytes, "scene file"), path);
}

json sceneToJson(const Scene& scene) {
  json surface;
  if (!scene.surface.sample.empty()) {
    surface["sample"] = scene.surface.sample;
    surface["params"] = scene.surface.params;
    surface["edge_length_m"] = scene.surface.edge_length_m;
  } else {
    surface["file"] = scene.surface.file.string();
    surface["scale_to_m"] = scene.surface.scale_to_m;
  }
  json corners = json::array();
  for (const auto& c : scene.patching.corners) corners.push_back({c.x(), c.y(), c.z()});
  json grid{{"map_resolution", scene.grid.map_resolution},
            {"map_tolerance_relative", scene.grid.map_tolerance_relative},
            {"map_proxy_vertices", scene.grid.map_proxy_vertices},
            {"min_planar_angle_rad", scene.grid.min_planar_angle_rad},
            {"member_spacing_factor", scene.grid.member_spacing_factor}};
  grid["members_per_family"] = scene.grid.members_per_family ? json(*scene.grid.members_per_family) : json("auto");
  grid["alpha_bar"] = scene.grid.alpha_bar == "value" ? json(scene.grid.alpha_bar_rad) : json(scene.grid.alpha_bar);
  const FabricationSpec& f = scene.fabrication;
  json fabrication{{"enabled", f.enabled},
                   {"sheet_mm", f.sheet_mm},
                   {"bolt_diameter_mm", f.bolt_diameter_mm},
                   {"kerf_mm", f.kerf_mm},
                   {"margin_mm", f.margin_mm},
                   {"min_notch_mm", f.min_notch_mm},
                   {"stock_length_mm", f.stock_length_mm},
                   {"sticker_margin_mm", f.sticker_margin_mm},
                   {"splice_joint", f.splice_joint},
                   {"scarf_slope", f.scarf_slope},
                   {"scarf_efficiency", f.scarf_efficiency},
                   {"supports_at_boundary_connections", f.supports_at_boundary_connections}};
  // Unset optional keys are left out (their defaults derive from the lamella).
  if (f.end_overhang_mm) fabrication["end_overhang_mm"] = *f.end_overhang_mm;
  if (f.splice_clearance_mm) fabrication["splice_clearance_mm"] = *f.splice_clearance_mm;
  if (f.min_splice_clearance_mm) fabrication["min_splice_clearance_mm"] = *f.min_splice_clearance_mm;
  if (f.label_height_mm) fabrication["label_height_mm"] = *f.label_height_mm;
  if (f.ground_height_m) fabrication["ground_height_m"] = *f.ground_height_m;
  if (f.support_block_mm) fabrication["support_block_mm"] = *f.support_block_mm;
  if (f.sticker_sheet_mm) fabrication["sticker_sheet_mm"] = *f.sticker_sheet_mm;
  json echo = {
      {"name", scene.name},
      {"path", scene.path.string()},
      {"surface", surface},
      {"patching",
       {{"eta_max", scene.patching.eta_max},
        {"slope_bounds", scene.patching.slope_bounds},
        {"max_patch_size_m", scene.patching.max_patch_size_m},
        {"max_splits", scene.patching.max_splits},
        {"min_patch_size_m", scene.patching.min_patch_size_m},
        {"corners", corners},
        {"patches", scene.patching.quads}}},
      {"grid", grid},
      {"lamella",
       {{"width_m", scene.lamella.width_m},
        {"thickness_m", scene.lamella.thickness_m},
        {"material", scene.lamella.material}}},
      {"simulation",
       {{"enabled", scene.simulation.enabled},
        {"gravity", scene.simulation.gravity},
        {"friction_mu", scene.simulation.friction_mu},
        {"notches", scene.simulation.notches},
        {"compare_without_notches", scene.simulation.compare_without_notches},
        {"supports", scene.simulation.supports},
        {"hold_shared_sides", scene.simulation.hold_shared_sides},
        {"join_patches", scene.simulation.join_patches},
        {"fasten_bolts", scene.simulation.fasten_bolts},
        {"newton_tolerance", scene.simulation.newton_tolerance},
        {"time_limit_s", scene.simulation.time_limit_s}}},
      {"fabrication", fabrication},
      {"outputs", scene.outputs},
  };
  // A layout without a workflow is taken as given: the echo leaves the key out, as the scene did.
  if (scene.patching.workflow_given || scene.patching.quads.empty()) echo["patching"]["workflow"] = scene.patching.workflow;
  if (scene.patching.block_grid[0] > 0) echo["patching"]["block_grid"] = scene.patching.block_grid;
  if (scene.patching.smoothing) echo["patching"]["smoothing"] = *scene.patching.smoothing;
  return echo;
}

}  // namespace egg::app
