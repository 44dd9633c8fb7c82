// `egg sweep SWEEP.json --out DIR` and `egg sweep --collect DIR` (see sweep.hpp).
#include "apps/bench/sweep.hpp"

#include "apps/egg/commands.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "pipeline/scene.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <algorithm>
#include <iostream>
#include <memory>
#include <system_error>

namespace egg::app {
using namespace egg::pipeline;

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string shellQuote(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

constexpr std::size_t kMaxSweepBytes = 1 << 20;
constexpr std::size_t kMaxVariants = 100000;

// "material.section.width_m" or "/material/section/width_m" -> a JSON pointer.
json::json_pointer pointerOf(const std::string& key, const std::string& where) {
  std::string p = key;
  if (p.empty()) throw InvalidInput(where + ": an empty parameter key");
  if (p[0] != '/') {
    std::string out;
    for (char c : p) out += c == '.' ? '/' : c;
    p = "/" + out;
  }
  try {
    return json::json_pointer(p);
  } catch (const json::exception& e) {
    throw InvalidInput(fmt::format("{}: key '{}': {}", where, abbreviate(key, 80), e.what()));
  }
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// One axis of the grid: one key, or a zip group of keys that vary together.
struct Axis {
  std::vector<std::string> keys;
  std::vector<std::vector<json>> values;  // per key
  size_t size() const { return values.front().size(); }
};

Axis axisOf(const json& group, const std::string& where) {
  if (!group.is_object() || group.empty())
    throw InvalidInput(where + ": must be an object {\"key\": [values], ...}");
  Axis axis;
  for (const auto& [key, list] : group.items()) {
    if (!list.is_array() || list.empty())
      throw InvalidInput(fmt::format("{}: key '{}': must be a non-empty list of values", where,
                                     abbreviate(key, 80)));
    if (!axis.values.empty() && list.size() != axis.size())
      throw InvalidInput(fmt::format("{}: key '{}': {} values, but the group's other keys have {}",
                                     where, abbreviate(key, 80), list.size(), axis.size()));
    axis.keys.push_back(key);
    axis.values.emplace_back(list.begin(), list.end());
  }
  return axis;
}

// Relative paths in the base scene are relative to its folder: made absolute so the variant
// scene, written elsewhere, still finds them (scene.cpp resolves surface.file that way).
void anchorFiles(json& node, const fs::path& folder) {
  if (node.is_object()) {
    for (auto& [key, value] : node.items()) {
      const bool fileKey =
          key == "file" || (key.size() > 5 && key.compare(key.size() - 5, 5, "_file") == 0);
      if (fileKey && value.is_string() && !value.get<std::string>().empty() &&
          fs::path(value.get<std::string>()).is_relative())
        value = (folder / value.get<std::string>()).lexically_normal().string();
      else
        anchorFiles(value, folder);
    }
  } else if (node.is_array()) {
    for (auto& value : node) anchorFiles(value, folder);
  }
}

}  // namespace

SweepExpansion expandSweep(const SweepExpandOptions& options) {
  const std::string where = options.sweepFile.string();
  json sweep;
  try {
    sweep = json::parse(readRegularFile(options.sweepFile, kMaxSweepBytes, "sweep file"));
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e400
    throw InvalidInput(where + ": not JSON: " + e.what());
  }
  if (!sweep.is_object()) throw InvalidInput(where + ": must be a JSON object");
  for (const auto& [key, value] : sweep.items())
    if (key != "base" && key != "parameters" && key != "zip")
      throw InvalidInput(
          fmt::format("{}: unknown key '{}' (base, parameters, zip)", where, abbreviate(key, 80)));
  if (!sweep.contains("base") || !sweep["base"].is_string())
    throw InvalidInput(where + ": base: must name the base scene file");
  const fs::path basePath =
      fs::path(sweep["base"].get<std::string>()).is_absolute()
          ? fs::path(sweep["base"].get<std::string>())
          : options.sweepFile.parent_path() / sweep["base"].get<std::string>();
  const Scene baseScene = loadScene(basePath);  // a bad base stops here, naming its file
  json base = json::parse(readRegularFile(basePath, 1 << 24, "scene file"));
  anchorFiles(base, fs::absolute(basePath).parent_path());

  std::vector<Axis> axes;
  if (sweep.contains("parameters")) {
    if (!sweep["parameters"].is_object())
      throw InvalidInput(where + ": parameters: must be an object {\"key\": [values]}");
    for (const auto& [key, list] : sweep["parameters"].items())
      axes.push_back(axisOf(json{{key, list}}, where + ": parameters"));
  }
  if (sweep.contains("zip")) {
    if (!sweep["zip"].is_array()) throw InvalidInput(where + ": zip: must be a list of groups");
    for (size_t g = 0; g < sweep["zip"].size(); ++g)
      axes.push_back(axisOf(sweep["zip"][g], fmt::format("{}: zip[{}]", where, g)));
  }
  if (axes.empty()) throw InvalidInput(where + ": no parameters to sweep");
  SweepExpansion expansion;
  std::vector<json::json_pointer> pointers;
  size_t total = 1;
  for (const auto& axis : axes) {
    total *= axis.size();
    if (total > kMaxVariants)
      throw InvalidInput(fmt::format("{}: more than {} variants", where, kMaxVariants));
    for (const auto& key : axis.keys) {
      const auto pointer = pointerOf(key, where);
      if (!base.contains(pointer))
        throw InvalidInput(fmt::format("{}: key '{}' is not in the base scene {}", where,
                                       abbreviate(key, 80), basePath.string()));
      if (std::find(pointers.begin(), pointers.end(), pointer) != pointers.end())
        throw InvalidInput(fmt::format("{}: key '{}' is swept twice", where, abbreviate(key, 80)));
      pointers.push_back(pointer);
      expansion.keys.push_back(pointer.to_string());
    }
  }

  const fs::path out = fs::absolute(options.out).lexically_normal();
  // Paths go into jobs.txt (one job per line) and slurm.sh's #SBATCH lines, which sbatch reads
  // itself, unquoted: a control character (a newline above all) would split a job or inject a
  // line there (issue 40). Refused, naming the option.
  const auto refuseControl = [](const std::string& path, const char* option) {
    for (unsigned char c : path)
      if (c < 0x20 || c == 0x7f)
        throw InvalidInput(
            fmt::format("{} \"{}\": a path with a control character cannot go "
                        "into jobs.txt and slurm.sh",
                        option, abbreviate(path, 80)));
  };
  refuseControl(out.string(), "--out");
  refuseControl(fs::absolute(options.eggBinary).string(), "the egg binary's path");
  std::error_code ec;
  if (fs::exists(out) && !fs::is_directory(out))
    throw InvalidInput(out.string() + ": exists and is not a folder");
  if (fs::is_directory(out) && !fs::is_empty(out) && !options.force)
    throw InvalidInput(out.string() + ": exists and is not empty (--force writes into it)");
  // --force replaces an earlier sweep's scenes/ only: a scenes/ folder with anything else in it
  // (the user's own scenes, the base scene among them) is refused before anything is written.
  if (fs::is_directory(out / "scenes")) {
    for (const auto& entry : fs::directory_iterator(out / "scenes")) {
      const std::string name = entry.path().filename().string();
      const bool variant = entry.is_regular_file() && !entry.is_symlink() && name.size() >= 9 &&
                           name[0] == 'v' && name.compare(name.size() - 5, 5, ".json") == 0 &&
                           std::all_of(name.begin() + 1, name.end() - 5,
                                       [](char c) { return c >= '0' && c <= '9'; });
      if (!variant)
        throw InvalidInput(fmt::format(
            "{}: holds {}, which no sweep wrote; --force replaces only an earlier sweep's "
            "vNNN.json files there (choose another --out)",
            (out / "scenes").string(), abbreviate(name, 80)));
    }
  }
  // Variant v (0-based) of the odometer: the base with its values, named, files anchored, checked
  // as a scene; `row` gets its values as JSON text.
  const auto variantScene = [&](size_t v, const std::string& id, std::vector<std::string>& row) {
    json scene = base;
    size_t rest = v;
    // The last axis varies fastest (odometer order).
    std::vector<size_t> index(axes.size());
    for (size_t a = axes.size(); a-- > 0;) index[a] = rest % axes[a].size(), rest /= axes[a].size();
    size_t column = 0;
    for (size_t a = 0; a < axes.size(); ++a)
      for (size_t k = 0; k < axes[a].keys.size(); ++k, ++column) {
        scene[pointers[column]] = axes[a].values[k][index[a]];
        row.push_back(axes[a].values[k][index[a]].dump());
      }
    // A swept name is the user's label for the variant; otherwise the base's name and the id.
    if (std::find(pointers.begin(), pointers.end(), json::json_pointer("/name")) == pointers.end())
      scene["name"] = baseScene.name + "-" + id;
    // Swept relative files (surface.file) are relative to the base scene's folder, like the
    // base's own: the variant scene lives in scenes/ and would look for them there.
    anchorFiles(scene, fs::absolute(basePath).parent_path());
    try {
      parseScene(scene, out / "scenes" / (id + ".json"));  // every variant must be a valid scene
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: variant {}: {}", where, id, e.what()));
    }
    return scene;
  };
  if (options.dryRun) {
    for (size_t v = 0; v < total; ++v) {
      const std::string id = fmt::format("v{:03d}", v + 1);
      std::vector<std::string> row;
      variantScene(v, id, row);
      expansion.variants.push_back(id);
      expansion.values.push_back(std::move(row));
    }
    return expansion;
  }
  // Everything goes to a staging folder beside DIR first: a bad variant writes nothing.
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  fs::create_directories(parent);
  // A killed sweep left its staging folder (.egg-tmp-PID-*, thousands of scenes) beside DIR;
  // those no process is at work on go now (issue 40).
  removeDeadLeftovers(parent, temporaryFilePrefix(), true);
  const fs::path staging =
      parent / (temporaryFilePrefix() + std::to_string(::getpid()) + "-" + temporarySuffix());
  fs::create_directories(staging / "scenes");
  const LiveLock atWork(staging);
  try {
    std::string jobs, csv = "variant";
    for (const auto& key : expansion.keys) csv += "," + csvField(key);
    csv += "\n";
    const std::string egg = fs::absolute(options.eggBinary).string();
    for (size_t v = 0; v < total; ++v) {
      const std::string id = fmt::format("v{:03d}", v + 1);
      std::vector<std::string> row;
      const json scene = variantScene(v, id, row);
      const fs::path sceneFile = out / "scenes" / (id + ".json");
      writeFileAtomically(staging / "scenes" / (id + ".json"), scene.dump(2) + "\n");
      jobs += fmt::format("{} run {} -o {} -q\n", shellQuote(egg), shellQuote(sceneFile.string()),
                          shellQuote((out / "runs" / id).string()));
      csv += id;
      for (const auto& value : row) csv += "," + csvField(value);
      csv += "\n";
      expansion.variants.push_back(id);
      expansion.values.push_back(row);
    }
    writeFileAtomically(staging / "jobs.txt", jobs);
    writeFileAtomically(staging / "variants.csv", csv);
    writeFileAtomically(
        staging / "slurm.sh",
        fmt::format("#!/bin/bash\n# egg sweep: one array task per line of jobs.txt (submit with "
                    "sbatch slurm.sh).\n"
                    "#SBATCH --job-name=egg-sweep\n#SBATCH --array=1-{}\n#SBATCH "
                    "--output={}/slurm-%A_%a.out\n"
                    "cd {} || exit 1\nsed -n \"${{SLURM_ARRAY_TASK_ID}}p\" jobs.txt | bash\n",
                    total, out.string(), shellQuote(out.string())));
    fs::permissions(staging / "slurm.sh", fs::perms::owner_exec | fs::perms::group_exec,
                    fs::perm_options::add);
    if (!fs::exists(out)) {
      fs::rename(staging, out);
    } else {
      // --force into an existing DIR: only the files this command writes are replaced.
      fs::remove_all(out / "scenes");  // an earlier sweep's vNNN.json only (checked above)
      for (const char* name : {"scenes", "jobs.txt", "variants.csv", "slurm.sh"})
        fs::rename(staging / name, out / name);
      fs::remove_all(staging);
    }
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  return expansion;
}

void registerSweepCommand(CLI::App& parent, Action& action) {
  struct Args {
    std::string sweep, out, collect;
    bool force = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = parent.add_subcommand(
      "sweep",
      "Expand a parameter grid over a base scene into scenes and a job list for GNU parallel or "
      "Slurm (--out DIR), or merge the runs' reports (--collect DIR)");
  cmd->add_option("sweep", args->sweep,
                  "Sweep file: {\"base\": scene, \"parameters\": {key: [values]}, \"zip\": [{key: "
                  "[values], ...}]}");
  cmd->add_option("--out,-o", args->out, "Folder for scenes/, jobs.txt, variants.csv, slurm.sh");
  cmd->add_flag("--force", args->force, "Write into an existing non-empty --out folder");
  cmd->add_option("--collect", args->collect,
                  "Merge DIR/runs/*/report.json into DIR/sweep.csv and DIR/sweep.svg");
  cmd->callback([args, &action] {
    action = [args]() {
      if (!args->collect.empty()) {
        if (!args->sweep.empty() || !args->out.empty())
          throw InvalidInput("egg sweep: --collect DIR takes no sweep file and no --out");
        const int missing = collectSweep(args->collect);
        std::cout << fmt::format("egg sweep: wrote {} and {}\n",
                                 (fs::path(args->collect) / "sweep.csv").string(),
                                 (fs::path(args->collect) / "sweep.svg").string());
        return missing == 0 ? kExitOk : kExitFailure;
      }
      if (args->sweep.empty() || args->out.empty())
        throw InvalidInput("egg sweep: give SWEEP.json --out DIR, or --collect DIR");
      SweepExpandOptions options{args->sweep, args->out, fs::read_symlink("/proc/self/exe"),
                                 args->force};
      const SweepExpansion expansion = expandSweep(options);
      std::cout << fmt::format(
          "egg sweep: {} variants; run them with\n  parallel --joblog {} < {}\nor\n  sbatch "
          "{}\nthen egg sweep --collect {}\n",
          expansion.variants.size(), shellQuote((fs::path(args->out) / "joblog.txt").string()),
          shellQuote((fs::path(args->out) / "jobs.txt").string()),
          shellQuote((fs::path(args->out) / "slurm.sh").string()), shellQuote(args->out));
      return kExitOk;
    };
  });
}

}  // namespace egg::app
