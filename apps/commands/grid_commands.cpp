// `egg bench grid`: wall time of the single-patch EGG solve (Chapter 2) and its parts per patch,
// on bump patches of increasing resolution (the paper reports 0.68-5.62 s per patch).
#include "apps/commands/commands.hpp"

#include "core/egg/solve_patch.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <memory>
#include <vector>

namespace egg::app {
namespace {

struct GridBenchArgs {
  std::vector<int> sizes{600, 1100, 2000, 3400};  // approximate patch vertex counts
  int resolution = 100;                           // distance map samples per side
  double height = 1.0;                            // bump height (m); the patch is 6 x 6 m
  std::string csv;
  bool json = false;
};

int runGridBench(const GridBenchArgs& args) {
  fmt::print("egg bench grid: bump (height {} m, sigma 1.5 m) patch 6 x 6 m, distance maps {} x {}, alpha_bar = min,\n"
             "lamellas 0.1 m at spacing 0.6 m; times in seconds (wall, all threads)\n",
             args.height, args.resolution, args.resolution);
  fmt::print("{:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>6} {:>6} {:>10} {:>18}\n", "vertices", "t_patch",
             "t_eta", "t_maps", "t_sqp", "t_member", "t_trace", "t_grid", "u x v", "fields", "max_notch", "alpha_bar range");
  nlohmann::json rows = nlohmann::json::array();
  for (int size : args.sizes) {
    if (size < 50) throw InvalidInput("egg bench grid: --sizes must be at least 50 vertices");
    const double patchArea = 50.0;  // calibrated on the bump sample: 6 x 6 m patch, ~requested vertices
    const double edge = std::sqrt(patchArea / (0.866 * size));
    const TriMesh mesh = samples::generateSample(
        "bump", {{"height", args.height}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, edge);
    EggOptions options;
    options.maps.resolution = args.resolution;
    options.members.lamellaWidthM = 0.1;
    options.members.spacingFactor = 6.0;
    const auto r = solveEgg(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, options);
    const auto& t = r.seconds;
    // Distance fields: 2 n for the maps plus those spent matching member lengths (load-independent).
    const int fields = 2 * args.resolution + r.grid.propagations;
    fmt::print("{:>8} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.4f} {:>8.3f} {:>8.3f} {:>3}x{:<2} {:>6} {:>10.4f} [{:.4f}, {:.4f}]\n",
               r.patch.mesh.n_vertices(), t.patch, t.uniqueness, t.distanceMaps, t.sqp, t.members, t.tracing, t.total,
               r.grid.u.size(), r.grid.v.size(), fields, r.grid.maxNotch, r.alphaBar.alphaMin, r.alphaBar.alphaMax);
    rows.push_back({{"vertices", r.patch.mesh.n_vertices()},
                    {"t_patch_s", t.patch},
                    {"t_uniqueness_s", t.uniqueness},
                    {"t_distance_maps_s", t.distanceMaps},
                    {"t_sqp_s", t.sqp},
                    {"t_members_s", t.members},
                    {"t_tracing_s", t.tracing},
                    {"t_grid_s", t.total},
                    {"distance_fields", fields},
                    {"members_u", r.grid.u.size()},
                    {"members_v", r.grid.v.size()},
                    {"max_notch_m", r.grid.maxNotch},
                    {"alpha_bar_range_rad", {r.alphaBar.alphaMin, r.alphaBar.alphaMax}},
                    {"smoothing_rounds", r.uniqueness.smoothingRounds}});
  }
  if (!args.csv.empty()) {
    std::ostringstream file;
    file << "vertices,t_patch_s,t_uniqueness_s,t_distance_maps_s,t_sqp_s,t_members_s,t_tracing_s,t_grid_s,members_u,"
            "members_v,max_notch_m\n";
    for (const auto& r : rows)
      file << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r["vertices"].get<size_t>(), r["t_patch_s"].get<double>(),
                          r["t_uniqueness_s"].get<double>(), r["t_distance_maps_s"].get<double>(), r["t_sqp_s"].get<double>(),
                          r["t_members_s"].get<double>(), r["t_tracing_s"].get<double>(), r["t_grid_s"].get<double>(),
                          r["members_u"].get<size_t>(), r["members_v"].get<size_t>(), r["max_notch_m"].get<double>());
    writeFileAtomically(args.csv, file.str());
  }
  if (args.json) std::cout << rows.dump(2) << "\n";
  return kExitOk;
}

}  // namespace

void registerGridBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<GridBenchArgs>();
  auto* cmd = bench.add_subcommand("grid",
                                   "Single-patch EGG solve (patch, eta, distance maps, SQP, members, tracing) per patch "
                                   "size: wall time of each part");
  cmd->add_option("--sizes", args->sizes, "approximate patch vertex counts")->delimiter(',');
  cmd->add_option("--resolution", args->resolution, "distance map samples per side")->check(CLI::Range(3, 2000));
  cmd->add_option("--height", args->height, "bump height in metres")->check(CLI::NonNegativeNumber);
  cmd->add_option("--csv", args->csv, "also write the table as CSV");
  cmd->add_flag("--json", args->json, "also print the table as JSON");
  cmd->callback([args, &action] { action = [args] { return runGridBench(*args); }; });
}

}  // namespace egg::app
