#include "apps/egg/commands.hpp"
#include "pipeline/surface_stage.hpp"

#include "core/errors.hpp"
#include "core/io/mesh_io.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace egg::app {
using namespace egg::pipeline;
namespace {

void printStats(const nlohmann::json& s) {
  std::cout << fmt::format("surface   {}\n", s["source"].get<std::string>());
  std::cout << fmt::format("vertices  {}\nfaces     {}\n", s["vertices"].get<size_t>(),
                           s["faces"].get<size_t>());
  const auto& b = s["bbox_m"];
  const auto& lo = s["bbox_min_m"];
  const auto& hi = s["bbox_max_m"];
  std::cout << fmt::format(
      "bbox      {:.3f} x {:.3f} x {:.3f} m  (x {:.3f}..{:.3f}, y {:.3f}..{:.3f}, z "
      "{:.3f}..{:.3f})\n",
      b[0].get<double>(), b[1].get<double>(), b[2].get<double>(), lo[0].get<double>(),
      hi[0].get<double>(), lo[1].get<double>(), hi[1].get<double>(), lo[2].get<double>(),
      hi[2].get<double>());
  std::cout << fmt::format("area      {:.3f} m2\nmean edge {:.4f} m\nmin angle {:.2f} deg\n",
                           s["area_m2"].get<double>(), s["mean_edge_m"].get<double>(),
                           s["min_angle_rad"].get<double>() * 180.0 / M_PI);
  if (s.contains("gaussian_curvature")) {
    const auto& k = s["gaussian_curvature"];
    std::cout << fmt::format(
        "K         {:.6g} .. {:.6g} 1/m2; injectivity bound pi/sqrt(K_max) = {} m\n",
        k["min_per_m2"].get<double>(), k["max_per_m2"].get<double>(),
        k["injectivity_bound_m"].is_null()
            ? std::string("inf")
            : fmt::format("{:.3f}", k["injectivity_bound_m"].get<double>()));
  }
  std::cout << fmt::format("boundary  {} edges, {} component(s)\n", s["boundary_edges"].get<int>(),
                           s["components"].get<int>());
  const bool ok = s["validation"]["ok"].get<bool>();
  std::cout << "valid     " << (ok ? "yes" : "no") << "\n";
  for (const auto& issue : s["validation"]["issues"])
    std::cout << "  - " << issue.get<std::string>() << "\n";
  for (const auto& w : s["warnings"]) std::cout << "warning: " << w.get<std::string>() << "\n";
}

}  // namespace

void registerSurfaceCommand(CLI::App& parent, Action& action) {
  struct Args {
    std::string surface;
    bool stats = false;
    bool json = false;
    bool list = false;
    std::string exportPath;
    double edgeLength = 0.0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = parent.add_subcommand("surface",
                                        "Load a design surface (sample, mesh file or scene), "
                                        "validate it, print statistics or export it.");
  cmd->add_option("surface", args->surface,
                  "Sample name, mesh file (OBJ, STL, PLY, OFF, glTF, FBX) or scene file");
  cmd->add_flag("--stats", args->stats,
                "Print vertices, faces, bounding box, area, curvature range and validation");
  cmd->add_flag("--json", args->json, "Machine-readable output");
  cmd->add_flag("--list", args->list, "List the procedural samples and their parameters");
  cmd->add_option("--export", args->exportPath,
                  "Write the mesh (OBJ, PLY, STL, glTF, GLB by extension)");
  cmd->add_option("--edge-length", args->edgeLength,
                  "Target edge length of a generated sample, metres")
      ->check(finiteRange(1e-3, 1e4));
  cmd->callback([args, &action] {
    action = [args]() {
      if (args->list) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& info : samples::listSamples()) {
          list.push_back({{"name", info.name},
                          {"description", info.description},
                          {"params", info.defaults},
                          {"params_help", info.parameterHelp},
                          {"default_edge_length_m", defaultSampleEdgeLength(info.name)}});
        }
        if (args->json) {
          std::cout << list.dump(2) << "\n";
        } else {
          for (const auto& s : list) {
            std::cout << s["name"].get<std::string>() << " — "
                      << s["description"].get<std::string>() << "\n";
            for (auto it = s["params"].begin(); it != s["params"].end(); ++it) {
              const auto& help = s["params_help"];
              std::cout << "    " << it.key() << " = " << it.value().dump()
                        << (help.contains(it.key())
                                ? "  (" + help[it.key()].get<std::string>() + ")"
                                : "")
                        << "\n";
            }
          }
        }
        return kExitOk;
      }
      if (args->surface.empty())
        throw InvalidInput("egg surface: name a sample, mesh file or scene (see --list)");
      const LoadedSurface surface = loadSurfaceArgumentDetailed(
          args->surface,
          args->edgeLength > 0.0 ? std::optional<double>(args->edgeLength) : std::nullopt);
      if (!args->exportPath.empty()) writeMeshFile(args->exportPath, surface.mesh);
      if (args->stats || args->exportPath.empty()) {
        const nlohmann::json stats = surfaceSummary(surface);
        if (args->json) {
          std::cout << stats.dump(2) << "\n";
        } else {
          printStats(stats);
        }
        return stats["validation"]["ok"].get<bool>() ? kExitOk : kExitBadInput;
      }
      return kExitOk;
    };
  });
}

}  // namespace egg::app
