// `egg bench grid`: wall time of the single-patch EGG solve (Chapter 2) and its parts per patch,
// on bump patches of increasing resolution (the paper reports 0.68-5.62 s per patch).
#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/timing.hpp"

#include "core/egg/map_proxy.hpp"
#include "core/egg/solve_patch.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

namespace egg::app {
namespace {

// With --json, stdout carries only the JSON document; the human table goes to stderr.
std::FILE* tableStream(bool json) { return json ? stderr : stdout; }

struct GridBenchArgs {
  std::vector<int> sizes{600, 1100, 2000, 3400};  // approximate patch vertex counts
  int resolution = 100;                           // distance map samples per side
  double height = 1.0;                            // bump height (m); the patch is 6 x 6 m
  int repeats = 3;                                // solves per size; the table shows medians
  std::vector<double> mapTolerances;  // relative tolerances of the adaptive maps' error-vs-time
                                      // table (empty = none)
  std::vector<int> mapProxies;  // proxy vertex counts for the same table (0 = maps on the patch)
  std::vector<double>
      mapProxyTolerances;  // proxy adaptive-row tolerances for the proxy rows (empty = default)
  std::string csv;
  bool json = false;
};

// The parts of t_grid in table order; t_grid itself is the wall time of the whole solve.
constexpr int kParts = 6;
const char* const kPartNames[kParts] = {"patch", "eta", "maps", "sqp", "members", "trace"};
std::array<double, kParts> partsOf(const EggTimings& t) {
  return {t.patch, t.uniqueness, t.distanceMaps, t.sqp, t.members, t.tracing};
}

// Largest change of a family's member positions (metres along the start and end sides) against
// the reference; NaN when the member count differs.
double memberShift(const FamilyMembers& a, const FamilyMembers& reference, double startLength,
                   double endLength) {
  if (a.x1.size() != reference.x1.size()) return std::nan("");
  double shift = 0.0;
  for (size_t k = 0; k < a.x1.size(); ++k)
    shift = std::max({shift, std::abs(a.x1[k] - reference.x1[k]) * startLength,
                      std::abs(a.x2[k] - reference.x2[k]) * endLength});
  return shift;
}

// Largest change of the cladding function x2 = F(x1) against the reference over 201 samples of x1,
// in metres along the end side; NaN when either is not bijective.
double claddingShift(const CladdingFunction& a, const CladdingFunction& reference,
                     double endLength) {
  if (!a.bijective() || !reference.bijective()) return std::nan("");
  double shift = 0.0;
  for (int k = 0; k <= 200; ++k)
    shift = std::max(shift, std::abs(a.evaluate(k / 200.0) - reference.evaluate(k / 200.0)));
  return shift * endLength;
}

double largestDifference(const DistanceMap& a, const DistanceMap& b) {
  double d = 0.0;
  for (size_t k = 0; k < a.values.size(); ++k) d = std::max(d, std::abs(a.values[k] - b.values[k]));
  return d;
}

// One row of the error-vs-time table: maps on the patch at `tolerance` (proxy 0), or on a proxy
// of `proxy` vertices whose adaptive rows refine to `proxyTolerance`.
struct MapVariant {
  double tolerance = 0.0;
  int proxy = 0;
  double proxyTolerance = 0.0;
};

// Error against run time of the adaptive distance maps (DistanceMapOptions::toleranceRelative)
// and of maps on a coarse proxy (DistanceMapOptions::proxyVertices): per size, the exact maps on
// the patch (tolerance 0, a field at every sample, no proxy) are the reference of the same run;
// every variant is solved `repeats` times and compared with it.
nlohmann::json runMapToleranceTable(const GridBenchArgs& args, const TriMesh& mesh,
                                    const EggOptions& base) {
  const std::array<Eigen::Vector3d, 4> corners{
      Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}};
  std::vector<MapVariant> variants{{0.0, 0, 0.0}};
  for (double t : args.mapTolerances)
    if (t > 0.0) variants.push_back({t, 0, 0.0});
  std::vector<double> proxyTolerances = args.mapProxyTolerances;
  if (proxyTolerances.empty())
    proxyTolerances.push_back(DistanceMapOptions{}.proxyToleranceRelative);
  for (int proxy : args.mapProxies)
    for (double pt : proxy > 0 ? proxyTolerances : std::vector<double>{0.0})
      variants.push_back({DistanceMapOptions{}.toleranceRelative, proxy, pt});
  nlohmann::json rows = nlohmann::json::array();
  std::optional<EggResult> reference;
  for (const MapVariant& variant : variants) {
    const double tolerance = variant.tolerance;
    EggOptions options = base;
    options.maps.toleranceRelative = tolerance;
    options.maps.proxyVertices = variant.proxy;
    options.maps.proxyToleranceRelative = variant.proxyTolerance;
    std::vector<double> maps, totals, cpu;
    std::optional<EggResult> last;
    for (int run = 0; run < args.repeats; ++run) {
      const double cpuStart = processCpuSeconds();
      last = solveEgg(mesh, corners, options);
      cpu.push_back(processCpuSeconds() - cpuStart);
      maps.push_back(last->seconds.distanceMaps);
      totals.push_back(last->seconds.total);
    }
    if (!reference) reference = last;
    const EggResult& r = *last;
    const EggResult& e = *reference;
    const double mapError =
        std::max(largestDifference(r.maps.u, e.maps.u), largestDifference(r.maps.v, e.maps.v));
    const Patch& p = r.patch;
    const double shorterSide = *std::min_element(p.sideLengths.begin(), p.sideLengths.end());
    const double shift =
        std::max(memberShift(r.membersU, e.membersU, familySideLength(p, Family::U, false),
                             familySideLength(p, Family::U, true)),
                 memberShift(r.membersV, e.membersV, familySideLength(p, Family::V, false),
                             familySideLength(p, Family::V, true)));
    const double claddingChange = std::max(claddingShift(r.alphaBar.claddingU, e.alphaBar.claddingU,
                                                         familySideLength(p, Family::U, true)),
                                           claddingShift(r.alphaBar.claddingV, e.alphaBar.claddingV,
                                                         familySideLength(p, Family::V, true)));
    const bool sameCount = r.membersU.x1.size() == e.membersU.x1.size() &&
                           r.membersV.x1.size() == e.membersV.x1.size();
    const double etaChange = std::max(std::abs(r.uniqueness.etaU - e.uniqueness.etaU),
                                      std::abs(r.uniqueness.etaV - e.uniqueness.etaV));
    // The proxy's actual size (the maps use it only when the patch is larger than the option).
    const bool onProxy = variant.proxy > 0 && static_cast<int>(p.mesh.n_vertices()) > variant.proxy;
    const int proxyVertices =
        onProxy ? static_cast<int>(makeMapProxy(p, variant.proxy).patch.mesh.n_vertices()) : 0;
    // A patch no larger than the proxy is its own proxy: its rows refine to the proxy tolerance.
    const double rowTolerance = !onProxy && variant.proxy > 0 ? variant.proxyTolerance : tolerance;
    nlohmann::json row{
        {"vertices", p.mesh.n_vertices()},
        {"tolerance_relative", rowTolerance},
        {"proxy_vertices_option", variant.proxy},
        {"proxy_vertices", proxyVertices},
        {"proxy_tolerance_relative", onProxy ? variant.proxyTolerance : 0.0},
        {"t_distance_maps_s", median(maps)},
        {"t_grid_s", median(totals)},
        {"cpu_grid_s", median(cpu)},
        {"map_fields", r.maps.propagations},
        {"max_map_error_m", mapError},
        {"max_map_error_relative", mapError / shorterSide},
        {"eta_change", etaChange},
        {"alpha_bar_change_rad", std::abs(r.alphaBar.alphaBar - e.alphaBar.alphaBar)},
        {"alpha_max_change_rad", std::abs(r.alphaBar.alphaMax - e.alphaBar.alphaMax)},
        {"cladding_change_m", claddingChange},
        {"member_counts_equal", sameCount},
        {"max_notch_change_m", std::abs(r.grid.maxNotch - e.grid.maxNotch)}};
    if (sameCount) row["member_shift_m"] = shift;
    // The bench patch is symmetric about the diagonal c0-c2, which swaps the families: on the
    // smooth surface D_u = D_v and the members coincide, so what differs is mesh noise.
    const double uvMap = largestDifference(r.maps.u, r.maps.v);
    const double uvMember =
        memberShift(r.membersU, r.membersV, familySideLength(p, Family::U, false),
                    familySideLength(p, Family::U, true));
    row["uv_map_asymmetry_m"] = uvMap;
    if (std::isfinite(uvMember)) row["uv_member_asymmetry_m"] = uvMember;
    fmt::print(tableStream(args.json),
               "{:>8} {:>9.1e} {:>6} {:>8.1e} {:>8.3f} {:>8.3f} {:>8.3f} {:>6} {:>10.2e} {:>10.2e} "
               "{:>10.2e} {:>10.2e} {:>10.2e} {:>10} {:>10.2e} {:>10.2e} {:>10}\n",
               p.mesh.n_vertices(), rowTolerance, proxyVertices,
               onProxy ? variant.proxyTolerance : 0.0, median(maps), median(totals), median(cpu),
               r.maps.propagations, mapError, etaChange,
               std::abs(r.alphaBar.alphaBar - e.alphaBar.alphaBar),
               std::abs(r.alphaBar.alphaMax - e.alphaBar.alphaMax), claddingChange,
               sameCount ? fmt::format("{:.2e}", shift) : std::string("count"),
               std::abs(r.grid.maxNotch - e.grid.maxNotch), uvMap,
               std::isfinite(uvMember) ? fmt::format("{:.2e}", uvMember) : std::string("count"));
    rows.push_back(row);
  }
  return rows;
}

int runGridBench(const GridBenchArgs& args) {
  fmt::print(
      tableStream(args.json),
      "egg bench grid: bump (height {} m, sigma 1.5 m) patch 6 x 6 m, distance maps {} x {} "
      "(adaptive rows,\n"
      "tolerance {} x the shorter side; on a proxy of {} vertices, rows to {}, when the patch is "
      "larger), alpha_bar = min,\n"
      "lamellas 0.1 m at spacing 0.6 m; wall seconds (all threads), median of {} solves per size;\n"
      "cpu_grid = CPU seconds of the solve over all threads (load-independent work);\n"
      "t_maps includes the proxy's decimation and the eta check's curvature, peak and p1 fields "
      "(run\n"
      "alongside the maps), t_eta the check itself; share = part / t_grid; fields = propagations "
      "on the\n"
      "patch, its surface or its proxy, full fields and directed ones alike (sides + maps + eta + "
      "tracing)\n",
      args.height, args.resolution, args.resolution, DistanceMapOptions{}.toleranceRelative,
      DistanceMapOptions{}.proxyVertices, DistanceMapOptions{}.proxyToleranceRelative,
      args.repeats);
  fmt::print(tableStream(args.json),
             "{:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>6} {:>6} {:>10} {:>18}\n",
             "vertices", "t_patch", "t_eta", "t_maps", "t_sqp", "t_member", "t_trace", "t_grid",
             "cpu_grid", "u x v", "fields", "max_notch", "alpha_bar range");
  nlohmann::json rows = nlohmann::json::array();
  std::vector<std::array<double, kParts>> shares;
  std::vector<TriMesh> meshes;
  EggOptions baseOptions;
  for (int size : args.sizes) {
    if (size < 50 || size > 200000)
      throw InvalidInput("egg bench grid: --sizes must lie in [50, 200000] vertices");
    // Calibrated on the bump sample: a surface meshed for `density` vertices per 50 m^2 gives a
    // 6 x 6 m patch of about 0.861 density + 141 vertices (the inserted boundary adds the offset).
    const int density = std::max(50, static_cast<int>(std::lround((size - 141) / 0.861)));
    const double patchArea = 50.0;
    const double edge = std::sqrt(patchArea / (0.866 * density));
    const TriMesh mesh = samples::generateSample(
        "bump", {{"height", args.height}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, edge);
    EggOptions options;
    options.maps.resolution = args.resolution;
    options.members.lamellaWidthM = 0.1;
    options.members.spacingFactor = 6.0;
    std::array<std::vector<double>, kParts> parts;
    std::vector<double> totals, cpu;
    std::optional<EggResult> last;
    for (int run = 0; run < args.repeats; ++run) {
      const double cpuStart = processCpuSeconds();
      last =
          solveEgg(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, options);
      const auto p = partsOf(last->seconds);
      for (int k = 0; k < kParts; ++k) parts[k].push_back(p[k]);
      totals.push_back(last->seconds.total);
      cpu.push_back(processCpuSeconds() - cpuStart);
    }
    const EggResult& r = *last;
    std::array<double, kParts> t{};
    for (int k = 0; k < kParts; ++k) t[k] = median(parts[k]);
    const double total = median(totals), cpuTotal = median(cpu);
    std::array<double, kParts> share{};
    for (int k = 0; k < kParts; ++k) share[k] = total > 0 ? t[k] / total : 0.0;
    shares.push_back(share);
    const int fields = r.propagations;  // load-independent work measure
    fmt::print(tableStream(args.json),
               "{:>8} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.4f} {:>8.3f} {:>8.3f} {:>8.3f} "
               "{:>3}x{:<2} {:>6} {:>10.4f} [{:.4f}, {:.4f}]\n",
               r.patch.mesh.n_vertices(), t[0], t[1], t[2], t[3], t[4], t[5], total, cpuTotal,
               r.grid.u.size(), r.grid.v.size(), fields, r.grid.maxNotch, r.alphaBar.alphaMin,
               r.alphaBar.alphaMax);
    nlohmann::json row{{"vertices", r.patch.mesh.n_vertices()},
                       {"repeats", args.repeats},
                       {"t_patch_s", t[0]},
                       {"t_uniqueness_s", t[1]},
                       {"t_distance_maps_s", t[2]},
                       {"t_sqp_s", t[3]},
                       {"t_members_s", t[4]},
                       {"t_tracing_s", t[5]},
                       {"t_grid_s", total},
                       {"t_grid_runs_s", totals},
                       {"cpu_grid_s", cpuTotal},
                       {"cpu_grid_runs_s", cpu},
                       {"distance_fields", fields},
                       {"members_u", r.grid.u.size()},
                       {"members_v", r.grid.v.size()},
                       {"max_notch_m", r.grid.maxNotch},
                       {"alpha_bar_range_rad", {r.alphaBar.alphaMin, r.alphaBar.alphaMax}},
                       {"smoothing_rounds", r.uniqueness.smoothingRounds},
                       {"alpha_bar_evaluations", r.alphaBar.evaluations},
                       {"alpha_bar_status", r.alphaBar.status}};
    rows.push_back(row);
    meshes.push_back(mesh);
    baseOptions = options;
  }
  nlohmann::json toleranceRows = nlohmann::json::array();
  if (!args.mapTolerances.empty() || !args.mapProxies.empty()) {
    fmt::print(tableStream(args.json),
               "distance maps: error against time (adaptive rows, tol = "
               "DistanceMapOptions::toleranceRelative, times the\n"
               "family's shorter side; proxy = vertices of the coarse copy the maps were computed "
               "on (--map-proxy, 0 = the patch),\n"
               "ptol = its rows' tolerance); reference = exact maps on the patch (tolerance 0, {} "
               "fields per family) of the same run; t_* medians\n"
               "of {} solves; map_err = max |D - D_exact| over both maps; d_eta = largest change "
               "of eta_u, eta_v (the check\n"
               "measures its distances on the patch, so ~0 unless a proxy picked other samples or "
               "smoothing took another path); d_alpha = |alpha_bar - exact| (alpha_bar_min), "
               "d_amax = |alpha_bar_max - exact|; d_F = largest\n"
               "change of the cladding functions F_u, F_v (metres along the end side, 201 samples "
               "of x1); d_member =\n"
               "largest member end shift along its side (\"count\" if the member count changed); "
               "d_notch = change of max notch;\n"
               "uv_map, uv_member = max |D_u - D_v| and largest u/v member mismatch of that solve: "
               "the patch is symmetric\n"
               "about its diagonal c0-c2, so on the smooth surface both are 0 and the exact row "
               "shows the mesh's own noise\n",
               args.resolution, args.repeats);
    fmt::print(tableStream(args.json),
               "{:>8} {:>9} {:>6} {:>8} {:>8} {:>8} {:>8} {:>6} {:>10} {:>10} {:>10} {:>10} {:>10} "
               "{:>10} {:>10} {:>10} {:>10}\n",
               "vertices", "tol_rel", "proxy", "ptol", "t_maps", "t_grid", "cpu_grid", "fields",
               "map_err_m", "d_eta", "d_alpha", "d_amax", "d_F_m", "d_member_m", "d_notch_m",
               "uv_map_m", "uv_member");
    for (const TriMesh& mesh : meshes)
      for (auto& row : runMapToleranceTable(args, mesh, baseOptions)) toleranceRows.push_back(row);
  }
  fmt::print(tableStream(args.json), "share of t_grid:\n{:>8}", "vertices");
  for (const char* name : kPartNames) fmt::print(tableStream(args.json), " {:>8}", name);
  fmt::print(tableStream(args.json), "\n");
  for (size_t k = 0; k < shares.size(); ++k) {
    fmt::print(tableStream(args.json), "{:>8}", rows[k]["vertices"].get<size_t>());
    for (double s : shares[k]) fmt::print(tableStream(args.json), " {:>7.1f}%", 100.0 * s);
    fmt::print(tableStream(args.json), "\n");
  }
  if (!args.csv.empty()) {
    std::ostringstream file;
    file << "vertices,t_patch_s,t_uniqueness_s,t_distance_maps_s,t_sqp_s,t_members_s,t_tracing_s,t_"
            "grid_s,members_u,"
            "members_v,max_notch_m,distance_fields\n";
    for (const auto& r : rows)
      file << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", r["vertices"].get<size_t>(),
                          r["t_patch_s"].get<double>(), r["t_uniqueness_s"].get<double>(),
                          r["t_distance_maps_s"].get<double>(), r["t_sqp_s"].get<double>(),
                          r["t_members_s"].get<double>(), r["t_tracing_s"].get<double>(),
                          r["t_grid_s"].get<double>(), r["members_u"].get<size_t>(),
                          r["members_v"].get<size_t>(), r["max_notch_m"].get<double>(),
                          r["distance_fields"].get<int>());
    writeFileAtomically(args.csv, file.str());
  }
  // One shape whatever the options: an object; "map_tolerance" is an empty array without
  // --map-tolerance.
  if (args.json)
    std::cout << nlohmann::json{{"sizes", rows}, {"map_tolerance", toleranceRows}}.dump(2) << "\n";
  return kExitOk;
}

}  // namespace

void registerGridBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<GridBenchArgs>();
  auto* cmd = bench.add_subcommand(
      "grid",
      "Single-patch EGG solve (patch, eta, distance maps, SQP, members, tracing) per patch "
      "size: wall time of each part");
  cmd->add_option("--sizes", args->sizes, "approximate patch vertex counts")
      ->delimiter(',')
      ->check(CLI::Range(50, 200000));
  cmd->add_option("--resolution", args->resolution, "distance map samples per side")
      ->check(CLI::Range(3, 2000));
  cmd->add_option("--map-tolerance", args->mapTolerances,
                  "also tabulate error against time of the adaptive distance maps for these "
                  "tolerances (relative to "
                  "the family's shorter side, comma-separated; the exact maps of the same run are "
                  "the reference)")
      ->delimiter(',')
      ->check(finiteRange(0.0, 1.0));
  cmd->add_option("--map-proxy", args->mapProxies,
                  "also tabulate error against time of distance maps on a coarse proxy of the "
                  "patch with at most "
                  "these many vertices (comma-separated; 0 = on the patch; same table and "
                  "reference as --map-tolerance)")
      ->delimiter(',')
      ->check(CLI::Range(0, 10000000));
  cmd->add_option("--map-proxy-tolerance", args->mapProxyTolerances,
                  "relative adaptive-row tolerances of the proxy rows (comma-separated; default: "
                  "the default of "
                  "DistanceMapOptions::proxyToleranceRelative)")
      ->delimiter(',')
      ->check(finiteRange(1e-12, 1.0));
  cmd->add_option("--repeats", args->repeats, "solves per size (medians are shown)")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--height", args->height, "bump height in metres")
      ->check(finiteRange(0.0, 100.0));
  cmd->add_option("--csv", args->csv, "also write the table as CSV");
  cmd->add_flag("--json", args->json,
                "also print the tables as JSON: {\"sizes\": [...], \"map_tolerance\": [...]} "
                "(map_tolerance also holds the --map-proxy rows)");
  cmd->callback([args, &action] { action = [args] { return runGridBench(*args); }; });
}

}  // namespace egg::app
