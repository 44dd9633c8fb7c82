#include "apps/bench/stress_suite.hpp"
#include "core/timing.hpp"
#include "samples/generators/obj_grid.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>

namespace egg::app {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void save(const fs::path& p, const samples::ObjText& obj) {
  std::ofstream f(p);
  f << obj.text;
  if (!f) throw std::runtime_error("cannot write " + p.string());
}

// The base scene: bump_small (samples/scenes) with report and cut files.
json baseScene(const std::string& name) {
  json s = json::parse(R"({
  "surface": {"sample": "bump", "params": {"length": 10, "width": 10, "height": 2, "sigma": 2}, "edge_length_m": 0.4},
  "patching": {"workflow": 2, "eta_max": 1.0015, "slope_bounds": [0.1, 10.0], "max_patch_size_m": 15},
  "grid": {"members_per_family": "auto", "map_resolution": 100, "alpha_bar": "min"},
  "lamella": {"width_m": 0.2, "thickness_m": 0.02, "material": "poplar_plywood"},
  "simulation": {"enabled": true, "gravity": true, "friction_mu": 0.1, "notches": true},
  "fabrication": {"enabled": true, "sheet_mm": [2500, 1250], "bolt_diameter_mm": 8},
  "outputs": ["report", "cut_files"]})");
  s["name"] = name;
  return s;
}
json meshScene(const std::string& name) {
  json s = baseScene(name);
  s["surface"] = {{"file", "mesh.obj"}};
  return s;
}
// A bump at span 10 f metres: every length scales, the lamella too (w:t stays 10). Eight members
// per family at every scale: "auto" spaces members 8 widths apart, so this 20 mm lamella would
// get ~60 per family (30k unknowns per patch: tens of seconds at any scale, which an earlier
// session took for a scale effect; 1.5k unknowns here, 3-5 s for the whole run at 0.1, 10 and
// 220 m alike, 1.7-2.0 factorisations per Newton iteration at each).
json scaledScene(const std::string& name, double f) {
  json s = baseScene(name);
  s["grid"]["members_per_family"] = 8;
  s["surface"]["params"] = {
      {"length", 10 * f}, {"width", 10 * f}, {"height", 2 * f}, {"sigma", 2 * f}};
  s["surface"]["edge_length_m"] = 0.4 * f;
  s["patching"]["max_patch_size_m"] = 15 * f;
  s["lamella"]["width_m"] = 0.02 * f;
  s["lamella"]["thickness_m"] = 0.002 * f;
  s["fabrication"] = {{"enabled", false}};  // an 8 mm bolt does not fit a 2 mm lamella
  s["outputs"] = {"report"};
  return s;
}

}  // namespace

std::vector<PipelineStressCase> pipelineStressCases() {
  std::vector<PipelineStressCase> cases;
  auto add = [&](std::string name, std::string kind, std::string description,
                 json scene) -> PipelineStressCase& {
    cases.push_back({name, kind, description, std::move(scene), {}, false, true, 60.0});
    return cases.back();
  };
  {
    json s = baseScene("wt5");
    s["lamella"]["width_m"] = 0.1;
    add("wt_5", "width_thickness", "bump 10 m, lamella 100 x 20 mm", s);
    s = baseScene("wt100");
    s["lamella"]["thickness_m"] = 0.002;
    add("wt_100", "width_thickness", "bump 10 m, lamella 200 x 2 mm", s);
  }
  {
    // The scene names a catalogue material: birch plywood (4 GPa) is the softest there; the rod
    // suite covers 0.5 GPa.
    json s = baseScene("E_birch");
    s["lamella"]["material"] = "birch_plywood";
    add("E_4GPa_birch", "youngs_modulus", "bump 10 m, birch plywood E 4 GPa", s);
    s = baseScene("E_steel");
    s["lamella"]["material"] = "steel_s235";
    add("E_210GPa_steel", "youngs_modulus", "bump 10 m, steel S235 E 210 GPa", s);
  }
  add("scale_0.1m", "scale", "bump 0.1 m, lamella 0.2 x 0.02 mm (all lengths x 0.01)",
      scaledScene("s01", 0.01));
  add("scale_220m", "scale", "bump 220 m, lamella 440 x 44 mm (all lengths x 22)",
      scaledScene("s220", 22.0));
  {
    json s = baseScene("flat");
    s["surface"]["params"]["height"] = 0.01;
    add("nearly_flat", "nearly_flat", "bump 10 m, 10 mm high", s);
  }
  {
    json s = baseScene("peak");
    s["surface"]["params"]["height"] = 3.0;
    s["surface"]["params"]["sigma"] = 0.7;
    add("sharp_k_peak", "sharp_k_peak", "bump 10 m, 3 m high, sigma 0.7 m (eta far above 1.0015)",
        s);
  }
  {
    json s = baseScene("amax");
    s["grid"]["alpha_bar"] = "max";
    add("alpha_bar_max", "near_collapsed_quads", "bump 10 m, alpha_bar at its upper bound", s);
    s = baseScene("asmall");
    s["grid"]["alpha_bar"] = 0.05;
    add("alpha_bar_0.05", "near_collapsed_quads",
        "bump 10 m, alpha_bar 0.05 rad (quads nearly collapsed)", s);
  }
  {
    // Deployment (issue 42): the path from the flat grid, soft and stiff sections, and a sharp bump
    // whose long notches end with bolts pressing on them.
    for (const auto& [name, material] :
         {std::pair<std::string, std::string>{"deploy_soft_birch", "birch_plywood"},
          {"deploy_stiff_steel", "steel_s235"}}) {
      json s = baseScene(name);
      s["lamella"]["material"] = material;
      s["outputs"] = {"report", "deployment"};
      add(name, "deployment", "bump 10 m, " + material + ", deployed from the flat grid", s);
    }
    json s = baseScene("deploy_peak");
    s["surface"]["params"]["height"] = 3.0;
    s["surface"]["params"]["sigma"] = 1.2;
    s["outputs"] = {"report", "deployment"};
    add("deploy_sharp_peak", "deployment",
        "bump 10 m, 3 m high, sigma 1.2 m, deployed from the flat grid (long notches)", s);
    // Nine patches deployed one by one, then joined (self-weight, joints, shoring let go).
    s = baseScene("deploy_joined");
    s["patching"]["max_patch_size_m"] = 6;
    s["grid"]["members_per_family"] = 6;
    s["deployment"] = {{"steps", 6}};
    s["outputs"] = {"report", "deployment"};
    // About 25 s on two idle cores (nine patch paths, then the joining): twice that as a margin.
    add("deploy_joined_patches", "deployment",
        "bump 10 m in 9 patches, each deployed from its flat grid, then joined", s)
        .timeLimitS = 120.0;
  }
  add("sliver_triangles", "sliver_triangles", "bump 10 m as 200 x 4 cells (triangles 50:1)",
      meshScene("sliver"))
      .writeMesh = [](const fs::path& p) {
    samples::ObjText o;
    samples::addHeightFieldGrid(o, 200, 4, 10, 10, samples::gaussianBump(2, 2));
    save(p, o);
  };
  add("holes", "holes", "bump 10 m, 40 x 40 cells, two round holes r 1.2 m", meshScene("holes"))
      .writeMesh = [](const fs::path& p) {
    samples::ObjText o;
    samples::addHeightFieldGrid(
        o, 40, 40, 10, 10, samples::gaussianBump(2, 2), [](double x, double y) {
          return std::hypot(x - 2.5, y - 2.5) < 1.2 || std::hypot(x + 2.5, y + 2.5) < 1.2;
        });
    save(p, o);
  };
  add("disconnected", "disconnected", "two bumps 10 m apart, keep_largest_component false",
      meshScene("disc"))
      .writeMesh = [](const fs::path& p) {
    samples::ObjText o;
    samples::addHeightFieldGrid(o, 20, 20, 10, 10, samples::gaussianBump(2, 2));
    samples::addHeightFieldGrid(o, 20, 20, 10, 10, samples::gaussianBump(2, 2), {}, 20.0);
    save(p, o);
  };
  cases.back().scene["surface"]["keep_largest_component"] = false;
  add("non_manifold", "non_manifold", "bump 10 m plus a fin: one edge with three faces",
      meshScene("nonman"))
      .writeMesh = [](const fs::path& p) {
    samples::ObjText o;
    samples::addHeightFieldGrid(o, 20, 20, 10, 10, samples::gaussianBump(2, 2));
    // the interior edge (10,10)-(11,10) of the 21 x 21 vertex grid gets a third face
    const int a = 10 * 21 + 10 + 1, b = a + 1;
    o.text += "v 0.25 0 5\n";
    o.vertices += 1;
    o.text += fmt::format("f {} {} {}\n", a, b, o.vertices);
    save(p, o);
  };
  PipelineStressCase& big =
      add("million_faces", "million_faces",
          "bump 100 m, 708 x 707 cells = 1,001,112 faces: surface load + curvature (egg surface "
          "--stats) "
          "+ one geodesic field (egg geodesic); patching and later stages skipped at this size",
          meshScene("million"));
  big.surfaceOnly = true;
  big.timeLimitS = 300.0;
  big.writeMesh = [](const fs::path& p) {
    samples::ObjText o;
    samples::addHeightFieldGrid(o, 708, 707, 100, 100, samples::gaussianBump(20, 20));
    save(p, o);
  };
  return cases;
}

namespace {
bool finiteNumber(const json& j, const std::string& key) {
  return !j.contains(key) || (j[key].is_number() && std::isfinite(j[key].get<double>()));
}
}  // namespace

PipelineStressRow classify(const PipelineStressCase& c, const ChildOutcome& o, const json& report) {
  PipelineStressRow row;
  row.name = c.name;
  row.kind = c.kind;
  row.seconds = o.seconds;
  row.peakRssMb = o.peakRssMb;
  static const std::regex nonFinite(R"(\b(nan|-?inf)\b)", std::regex::icase);
  bool finite = !std::regex_search(o.output, nonFinite);
  if (report.is_object()) {
    if (report.contains("stages"))
      for (const auto& [stage, s] : report["stages"].items()) {
        finite = finite && finiteNumber(s, "seconds");
        if (s.value("ran", false)) row.stages += (row.stages.empty() ? "" : ",") + stage;
      }
    if (report.contains("simulation")) {
      const json& sim = report["simulation"];
      for (const char* k : {"rmse_m", "max_error_m", "nrmse"})
        finite = finite && finiteNumber(sim, k);
      row.iterations = sim.value("iterations", 0);
      if (sim.contains("rmse_m") && sim["rmse_m"].is_number())
        row.rmseM = sim["rmse_m"].get<double>();
      if (sim.contains("max_error_m") && sim["max_error_m"].is_number())
        row.maxErrorM = sim["max_error_m"].get<double>();
    }
    if (report.contains("deployment") && report["deployment"].contains("patches"))
      for (const json& p : report["deployment"]["patches"])
        for (const char* k : {"peak_stress_ratio", "end_stress_ratio", "max_support_force_n"})
          finite = finite && (p.contains("failure") || finiteNumber(p, k));
    if (report.contains("deployment") && report["deployment"].contains("joined") &&
        report["deployment"]["joined"].value("ran", false) &&
        !report["deployment"]["joined"].contains("failure"))
      for (const char* k : {"peak_stress_ratio", "end_stress_ratio", "max_join_force_n"})
        finite = finite && finiteNumber(report["deployment"]["joined"], k);
    if (report.contains("patches") && report["patches"].is_array())
      for (const json& p : report["patches"])
        for (const char* k : {"eta_u", "eta_v", "alpha_bar_rad", "area_m2"})
          finite = finite && finiteNumber(p, k);
  }
  auto firstLine = [](const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
      if (line.find("error") != std::string::npos || line.find("egg:") != std::string::npos)
        return line.substr(0, 160);
      else if (!line.empty())
        last = line;
    return last.substr(0, 160);
  };
  if (o.timedOut)
    row.result = fmt::format("TIMEOUT after {:.0f} s", c.timeLimitS);
  else if (o.signal != 0)
    row.result = fmt::format("CRASH (signal {})", o.signal);
  else if (!finite)
    row.result = "NON-FINITE: " + firstLine(o.output);
  else if (o.exitCode == 0) {
    row.ok = true;
    row.result = "converged";
  } else if (o.exitCode == 1 && report.is_object() && report.contains("failures")) {
    row.ok = true;
    row.result = "stopped: " + report["failures"][0].get<std::string>().substr(0, 160);
  } else {
    const std::string message = firstLine(o.output);
    row.ok = !message.empty() && o.exitCode != 3;  // 3: an exception escaped the command
    row.result = fmt::format("exit {}: {}", o.exitCode, message.empty() ? "NO MESSAGE" : message);
  }
  return row;
}

json PipelineStressRow::toJson() const {
  return {{"case", name},       {"class", kind},
          {"stages", stages},   {"ok", ok},
          {"result", result},   {"iterations", iterations},
          {"rmse_m", rmseM},    {"max_error_m", maxErrorM},
          {"seconds", seconds}, {"peak_rss_mb", peakRssMb}};
}

PipelineStressRow runPipelineStressCase(const PipelineStressCase& c, const EggCommand& command,
                                        const fs::path& workDir) {
  const fs::path dir = workDir / c.name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  if (c.writeMesh) c.writeMesh(dir / "mesh.obj");
  json scene = c.scene;
  if (c.writeMesh) scene["surface"]["file"] = (dir / "mesh.obj").string();
  {
    std::ofstream f(dir / "scene.json");
    f << scene.dump(2);
  }
  if (!c.surfaceOnly) {
    const ChildOutcome o = runChild(
        [&] {
          return command({"run", (dir / "scene.json").string(), "-o", (dir / "out").string(), "-q",
                          "-j", "1"});
        },
        c.timeLimitS, dir / "log.txt");
    json report;
    std::ifstream r(dir / "out" / "report.json");
    if (r) report = json::parse(r, nullptr, false);
    if (report.is_discarded()) report = json();
    return classify(c, o, report);
  }
  // Large mesh: load + curvature, then one geodesic field, each a child (a fifth and four fifths of
  // the limit).
  ChildOutcome a = runChild(
      [&] {
        return command({"surface", (dir / "mesh.obj").string(), "--stats", "--json"});
      },
      (c.geodesic ? 0.2 : 1.0) * c.timeLimitS, dir / "surface.txt");
  ChildOutcome total = a;
  std::string stages = "surface,curvature";
  if (c.geodesic && !a.timedOut && a.signal == 0 && a.exitCode == 0) {
    ChildOutcome b = runChild(
        // The wavefront engine (the default): memory O(front) (~0.4 GB at this size instead of ~6
        // GB stored).
        [&] {
          return command({"geodesic", (dir / "mesh.obj").string(), "--source", "0,0,20", "--engine",
                          "wavefront", "--out", (dir / "d.csv").string(), "--json"});
        },
        0.8 * c.timeLimitS, dir / "geodesic.txt");
    total = b;
    total.seconds += a.seconds;
    total.peakRssMb = std::max(a.peakRssMb, b.peakRssMb);
    total.output = a.output + b.output;
    stages += ",geodesic";
  }
  PipelineStressRow row = classify(c, total, json());
  row.stages = stages;
  return row;
}

}  // namespace egg::app
