#include "export/rhino_writer.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/child_process.hpp"

#include <fmt/core.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

namespace egg::exporter {

namespace fs = std::filesystem;
using nlohmann::json;

#ifndef EGG_EXPORT_JS_DIR
#define EGG_EXPORT_JS_DIR "export/js"
#endif

fs::path exportJsDir() {
  if (const char* env = std::getenv("EGG_EXPORT_JS"); env && *env) return env;
  std::error_code ec;
  if (fs::is_directory(EGG_EXPORT_JS_DIR, ec)) return EGG_EXPORT_JS_DIR;  // a source build
  // An installed program (cmake --install, the .deb): share/eggshell/export/js beside bin/.
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / "../share/eggshell/export/js";
    if (fs::is_directory(installed, ec)) return installed.lexically_normal();
  }
  return EGG_EXPORT_JS_DIR;  // the message then names where it looked
}

fs::path nodeProgram() {
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
      if (dir.empty()) continue;
      const fs::path candidate = fs::path(dir) / "node";
      if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
  }
  if (::access("/usr/bin/node", X_OK) == 0) return "/usr/bin/node";
  return {};
}

std::string rhinoUnavailableReason() {
  if (nodeProgram().empty())
    return "Node.js is not installed (no `node` on PATH or /usr/bin/node; Debian package nodejs)";
  const fs::path dir = exportJsDir();
  std::error_code ec;
  if (!fs::is_regular_file(dir / "write3dm.mjs", ec))
    return "the 3dm writer script " + (dir / "write3dm.mjs").string() + " is missing";
  if (!fs::is_regular_file(dir / "node_modules" / "rhino3dm" / "rhino3dm.js", ec))
    return "the npm package rhino3dm is not installed in " + dir.string() +
           " (run scripts/install-deps.sh, which runs npm ci there)";
  return "";
}

namespace {

json meshJson(const ModelMesh& mesh) {
  json v = json::array(), f = json::array();
  for (const auto& p : mesh.vertices)
    for (int i = 0; i < 3; ++i) v.push_back(std::round(p[i] * 1e6) / 1e6);  // micrometres
  for (const auto& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) f.push_back(t[i]);
  return {{"kind", "mesh"}, {"vertices", std::move(v)}, {"faces", std::move(f)}};
}

}  // namespace

json rhinoDescription(const StructureModel& model) {
  model.validate();
  json layers = json::array(), objects = json::array();
  layers.push_back({{"name", "surface"}, {"parent", nullptr}});
  std::set<std::pair<int, char>> families;
  for (const auto& l : model.lamellas) families.insert({l.patch, l.family});
  for (int p : model.patches) {
    layers.push_back({{"name", fmt::format("P{}", p)}, {"parent", nullptr}});
    for (char f : {'U', 'V'})
      if (families.count({p, f}))
        layers.push_back(
            {{"name", fmt::format("P{}-{}", p, f)}, {"parent", fmt::format("P{}", p)}});
  }
  layers.push_back({{"name", "supports"}, {"parent", nullptr}});
  if (!model.surface.triangles.empty()) {
    json o = meshJson(model.surface);
    o.update({{"name", "surface"}, {"layer", "surface"}, {"user", {{"role", "design surface"}}}});
    objects.push_back(std::move(o));
  }
  const double maxDeviation = model.maxDeviationM();
  for (const auto& l : model.lamellas) {
    const Ribbon r = ribbonOf(l, model.widthM, model.thicknessM);
    json o = meshJson(r.mesh);
    json colours = json::array();
    for (int s : r.station) {
      const Eigen::Vector3d c = deviationColour(l.deviationM[s], maxDeviation);
      for (int i = 0; i < 3; ++i)  // back to sRGB bytes
        colours.push_back(static_cast<int>(std::lround(
            255.0 * (c[i] <= 0.0031308 ? 12.92 * c[i] : 1.055 * std::pow(c[i], 1 / 2.4) - 0.055))));
    }
    double worst = 0.0;
    for (double d : l.deviationM) worst = std::max(worst, d);
    o.update({{"name", l.id},
              {"layer", fmt::format("P{}-{}", l.patch, l.family)},
              {"colours", std::move(colours)},
              {"user",
               {{"id", l.id},
                {"patch", std::to_string(l.patch)},
                {"family", std::string(1, l.family)},
                {"index", std::to_string(l.index)},
                {"length_m", fmt::format("{:.4f}", l.lengthM)},
                {"spatial_length_m", fmt::format("{:.4f}", l.spatialLengthM)},
                {"max_deviation_m", fmt::format("{:.5f}", worst)},
                {"sheet", l.sheet}}}});
    objects.push_back(std::move(o));
  }
  std::map<int, int> boltCount;
  for (const auto& b : model.bolts) ++boltCount[b.patch];
  for (const auto& [patch, mesh] : boltMeshesByPatch(model)) {
    json o = meshJson(mesh);
    o.update({{"name", fmt::format("P{}-bolts", patch)},
              {"layer", fmt::format("P{}", patch)},
              {"user",
               {{"patch", std::to_string(patch)}, {"bolts", std::to_string(boltCount[patch])}}}});
    objects.push_back(std::move(o));
  }
  for (const auto& s : model.supports) {
    if (s.solid.triangles.empty()) continue;
    json o = meshJson(s.solid);
    o.update({{"name", s.id},
              {"layer", "supports"},
              {"user",
               {{"id", s.id},
                {"patch", std::to_string(s.patch)},
                {"connection", s.connection},
                {"kind", s.kind}}}});
    objects.push_back(std::move(o));
  }
  return {{"name", model.name},
          {"units", "m"},
          {"centreline_source", toString(model.source)},
          {"layers", std::move(layers)},
          {"objects", std::move(objects)}};
}

double write3dm(const StructureModel& model, const fs::path& path, double timeLimitS) {
  if (const std::string why = rhinoUnavailableReason(); !why.empty())
    throw Error(path.string() + ": cannot write the 3dm: " + why);
  const json description = rhinoDescription(model);
  const fs::path target = checkedOutputTarget(path);
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string stem =
      temporaryFilePrefix() + std::to_string(::getpid()) + "-" + temporarySuffix();
  const fs::path input = folder / (stem + ".json"), output = folder / (stem + ".3dm"),
                 log = folder / (stem + ".log");
  const auto cleanUp = [&] {
    std::error_code ignored;
    for (const fs::path& p : {input, output, log}) fs::remove(p, ignored);
  };
  double nodeSeconds = 0.0;
  try {
    writeFileAtomically(input, description.dump());
    const std::string node = nodeProgram().string();
    const std::string script = (exportJsDir() / "write3dm.mjs").string();
    const ChildOutcome run = runChild(
        [&] {
          ::execl(node.c_str(), node.c_str(), script.c_str(), input.c_str(), output.c_str(),
                  static_cast<char*>(nullptr));
          std::perror("exec node");
          return 127;
        },
        timeLimitS, log);
    if (run.timedOut || run.signal != 0 || run.exitCode != 0) {
      const std::string how = run.timedOut ? fmt::format("ran past {} s", timeLimitS)
                              : run.signal ? fmt::format("was killed by signal {}", run.signal)
                                           : fmt::format("exited with {}", run.exitCode);
      throw Error(fmt::format("{}: the 3dm writer ({} {}) {}: {}", path.string(), node, script, how,
                              run.output.substr(0, 2000)));
    }
    nodeSeconds = run.seconds;
    std::error_code ec;
    fs::rename(output, target, ec);
    if (ec) throw WriteError(path.string() + ": cannot put the 3dm in place: " + ec.message());
  } catch (...) {
    cleanUp();
    throw;
  }
  cleanUp();
  return nodeSeconds;
}

}  // namespace egg::exporter
