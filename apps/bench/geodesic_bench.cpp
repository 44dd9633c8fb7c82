// `egg bench geodesic`: the geodesic engines against CGAL's exact distance, error against time.
#include "apps/bench/bench_stats.hpp"
#include "apps/egg/commands.hpp"
#include "core/timing.hpp"
#include "pipeline/surface_stage.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/geodesic/exact_reference.hpp"
#include "core/io/atomic_file.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>
#include <sys/resource.h>
#include <time.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace egg::app {
using namespace egg::pipeline;
namespace {

// ---------------------------------------------------------------------------------------------
// Benchmark: ours vs CGAL exact on the `bump` sample at several sizes.

struct BenchArgs {
  std::vector<int> sizes = {1000, 4000, 16000};
  int sources = 200;
  int threads = 2;
  int timedSources = 8;
  std::vector<int> cgalSources = {3, 2, 1};
  std::vector<double> saddleTolerances;  // error-against-time table over these; empty = none
  std::string engineRows = "standard";   // stored vs front engine table: none, standard, large
  int engineSources = 5;                 // vertex sources per row of that table (the large row: 1)
  std::string csv;
  bool json = false;
};

// Surface points along the side x = xmin (or xmax) of the patch, evenly in y.
std::vector<SurfacePoint> sidePoints(const TriMesh& mesh, int count, bool maxSide) {
  const BoundingBox box = boundingBox(mesh);
  std::vector<SurfacePoint> points;
  for (int i = 0; i < count; ++i) {
    const double y = box.min.y() + (i + 0.5) / count * box.size().y();
    const double x = maxSide ? box.max.x() : box.min.x();
    points.push_back(geodesic::snapToSurface(mesh, Eigen::Vector3d(x, y, box.max.z() + 1.0)));
  }
  return points;
}

// CGAL misplaces sources lying exactly on an edge (tests/core/geodesic/test_exact_reference.cpp),
// so the comparison uses a source 1e-10 (barycentric) inside the face, for both engines.
SurfacePoint intoFace(SurfacePoint p) {
  for (int i = 0; i < 3; ++i) p.barycentric[i] = std::max(p.barycentric[i], 1e-10);
  p.barycentric /= p.barycentric.sum();
  return p;
}

// Error against run time over DistanceSolverOptions::saddleAngleTolerance, with the exact mode
// (tolerance 0) of the same run as the reference: per tolerance, the median thread CPU time per
// field, the windows created, and the worst and mean relative errors at the vertices (farther than
// two mean edges) and at the opposite side's points (side-to-side, as the distance maps use them).
nlohmann::json toleranceTable(const TriMesh& mesh, const std::vector<SurfacePoint>& sources,
                              const std::vector<SurfacePoint>& targets,
                              const std::vector<double>& tolerances) {
  geodesic::DistanceSolverOptions exactOptions = geodesic::DistanceSolverOptions::exact();
  const geodesic::DistanceSolver exact(mesh, exactOptions);
  std::vector<geodesic::DistanceField> reference;
  for (const auto& s : sources) reference.push_back(exact.distances(s, targets));
  nlohmann::json rows = nlohmann::json::array();
  for (const double tolerance : tolerances) {
    geodesic::DistanceSolverOptions options;
    options.saddleAngleTolerance = tolerance;
    const geodesic::DistanceSolver solver(mesh, options);
    std::vector<double> ms;
    double windows = 0.0, worstVertex = 0.0, sumVertex = 0.0, worstSide = 0.0;
    long counted = 0;
    for (size_t i = 0; i < sources.size(); ++i) {
      const double t0 = threadCpuSeconds();
      const auto field = solver.distances(sources[i], targets);
      ms.push_back(1e3 * (threadCpuSeconds() - t0));
      windows += static_cast<double>(field.windowsCreated);
      const auto& ref = reference[i];
      for (size_t v = 0; v < ref.vertexDistances.size(); ++v) {
        if (!(ref.vertexDistances[v] > 2.0 * solver.meanEdgeLength()) ||
            !std::isfinite(ref.vertexDistances[v]))
          continue;
        const double e =
            std::abs(field.vertexDistances[v] - ref.vertexDistances[v]) / ref.vertexDistances[v];
        worstVertex = std::max(worstVertex, e);
        sumVertex += e;
        ++counted;
      }
      for (size_t j = 0; j < targets.size(); ++j) {
        const double e =
            std::abs(field.targetDistances[j] - ref.targetDistances[j]) / ref.targetDistances[j];
        worstSide = std::max(worstSide, e);
      }
    }
    rows.push_back(
        {{"saddle_angle_tolerance_rad", tolerance},
         {"ms_per_source", median(ms)},
         {"windows_per_source", windows / static_cast<double>(sources.size())},
         {"max_relative_error_vertices", worstVertex},
         {"mean_relative_error_vertices", counted ? sumVertex / static_cast<double>(counted) : 0.0},
         {"max_relative_error_side_to_side", worstSide}});
  }
  return rows;
}

// The three engines (DistanceSolverOptions::Engine: stored windows, front only, wavefront) on the
// meshes of issue 19 (each exported by `egg surface NAME --edge-length E`), from the same vertex
// sources, interleaved source by source: median thread CPU time per field, windows, the counted
// working memory at the peak (DistanceField::peakBytes), and the largest relative difference at the
// vertices (farther than two mean edges) of each against the exact mode (tolerance 0, stored
// windows) and of the front and wavefront engines against the stored one.
struct EngineRow {
  std::string sample;
  double edge;
};

nlohmann::json engineTable(const BenchArgs& args, std::ostream& table) {
  using Engine = geodesic::DistanceSolverOptions::Engine;
  std::vector<EngineRow> meshes = {
      {"bump", 0.1699}, {"sphere", 0.2567}, {"sphere", 0.12835}, {"plane", 0.08495}};
  if (args.engineRows == "large") meshes.push_back({"bump", 0.02459});
  table << "\nengines (issue 19): median thread CPU ms per vertex source of the stored-window, "
           "front-only and"
           " wavefront engines; f/s, w/s, w/f = time ratios;\nwin = windows created; MB = counted "
           "working memory"
           " of one field; err = max relative difference at the vertices against the exact "
           "mode\n(tolerance 0,"
           " stored; skipped above 50k vertices); f-s, w-s = against the stored engine; RSS MB = "
           "the process's"
           " peak RSS\nbefore the row's first stored field (mesh, tables, the front and wavefront "
           "fields, earlier"
           " rows)\n";
  table << fmt::format(
      "{:>7} {:>8} {:>9} {:>9} {:>9} {:>5} {:>5} {:>5} {:>9} {:>9} {:>9} {:>8} {:>7} {:>7} {:>8} "
      "{:>8} {:>8} {:>8} "
      "{:>7}\n",
      "sample", "verts", "stored ms", "front ms", "wave ms", "f/s", "w/s", "w/f", "strd win",
      "front win", "wave win", "strd MB", "frntMB", "waveMB", "strd err", "wave err", "f-s", "w-s",
      "RSS MB");
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : meshes) {
    const TriMesh mesh = samples::generateSample(row.sample, {}, row.edge);
    geodesic::DistanceSolverOptions storedOptions, frontOptions, waveOptions, exactOptions;
    storedOptions.engine = Engine::StoredWindows;
    frontOptions.engine = Engine::FrontOnly;
    waveOptions.engine = Engine::Wavefront;
    exactOptions.engine = Engine::StoredWindows;
    exactOptions.saddleAngleTolerance = 0.0;
    exactOptions.imageMergeTolerance = 0.0;
    const geodesic::DistanceSolver stored(mesh, storedOptions), front(mesh, frontOptions),
        wave(mesh, waveOptions);
    const int nv = static_cast<int>(mesh.n_vertices());
    const bool large = nv > 50000;
    std::unique_ptr<geodesic::DistanceSolver> exact;
    if (!large) exact = std::make_unique<geodesic::DistanceSolver>(mesh, exactOptions);
    const int count = large ? 1 : std::max(1, args.engineSources);
    std::vector<double> storedMs, frontMs, waveMs;
    double storedWindows = 0, frontWindows = 0, waveWindows = 0, storedBytes = 0, frontBytes = 0,
           waveBytes = 0;
    double storedErr = 0, waveErr = 0, frontBetween = 0, waveBetween = 0, rssBeforeStored = 0;
    auto worst = [&](const std::vector<double>& a, const std::vector<double>& ref, double& into) {
      for (size_t v = 0; v < ref.size(); ++v) {
        if (ref[v] > 2.0 * stored.meanEdgeLength() && std::isfinite(ref[v])) {
          into = std::max(into, std::abs(a[v] - ref[v]) / ref[v]);
        }
      }
    };
    auto timed = [](const geodesic::DistanceSolver& solver, int v, std::vector<double>& ms) {
      const double t0 = threadCpuSeconds();
      auto field = solver.distancesFromVertex(v);
      ms.push_back(1e3 * (threadCpuSeconds() - t0));
      return field;
    };
    for (int i = 0; i < count; ++i) {
      const int v = static_cast<int>((2LL * i + 1) * nv / (2LL * count));
      // Front and wavefront first: the process's peak RSS before the row's first stored field
      // bounds what a process without stored windows needs (earlier rows count too).
      const auto b = timed(front, v, frontMs);
      const auto c = timed(wave, v, waveMs);
      if (i == 0) rssBeforeStored = peakRssMb();
      const auto a = timed(stored, v, storedMs);
      storedWindows += a.windowsCreated;
      frontWindows += b.windowsCreated;
      waveWindows += c.windowsCreated;
      storedBytes = std::max(storedBytes, a.peakBytes);
      frontBytes = std::max(frontBytes, b.peakBytes);
      waveBytes = std::max(waveBytes, c.peakBytes);
      worst(b.vertexDistances, a.vertexDistances, frontBetween);
      worst(c.vertexDistances, a.vertexDistances, waveBetween);
      if (exact) {
        const auto e = exact->distancesFromVertex(v);
        worst(a.vertexDistances, e.vertexDistances, storedErr);
        worst(c.vertexDistances, e.vertexDistances, waveErr);
      }
    }
    const double sm = median(storedMs), fm = median(frontMs), wm = median(waveMs);
    auto errText = [&](double e) { return exact ? fmt::format("{:.1e}", e) : std::string("-"); };
    table << fmt::format(
        "{:>7} {:>8} {:>9.1f} {:>9.1f} {:>9.1f} {:>5.2f} {:>5.2f} {:>5.2f} {:>9.0f} {:>9.0f} "
        "{:>9.0f} {:>8.1f} {:>7.1f} "
        "{:>7.1f} {:>8} {:>8} {:>8.1e} {:>8.1e} {:>7.0f}\n",
        row.sample, nv, sm, fm, wm, fm / sm, wm / sm, wm / fm, storedWindows / count,
        frontWindows / count, waveWindows / count, storedBytes / 1e6, frontBytes / 1e6,
        waveBytes / 1e6, errText(storedErr), errText(waveErr), frontBetween, waveBetween,
        rssBeforeStored);
    table.flush();
    auto orNull = [&](double e) { return exact ? nlohmann::json(e) : nlohmann::json(nullptr); };
    rows.push_back({{"sample", row.sample},
                    {"edge_length_m", row.edge},
                    {"vertices", nv},
                    {"faces", mesh.n_faces()},
                    {"sources", count},
                    {"stored_ms_per_source", sm},
                    {"front_ms_per_source", fm},
                    {"wavefront_ms_per_source", wm},
                    {"front_over_stored", fm / sm},
                    {"wavefront_over_stored", wm / sm},
                    {"wavefront_over_front", wm / fm},
                    {"stored_windows_per_source", storedWindows / count},
                    {"front_windows_per_source", frontWindows / count},
                    {"wavefront_windows_per_source", waveWindows / count},
                    {"stored_peak_mb", storedBytes / 1e6},
                    {"front_peak_mb", frontBytes / 1e6},
                    {"wavefront_peak_mb", waveBytes / 1e6},
                    {"stored_max_relative_error_vs_exact", orNull(storedErr)},
                    {"wavefront_max_relative_error_vs_exact", orNull(waveErr)},
                    {"front_vs_stored_max_relative_difference", frontBetween},
                    {"wavefront_vs_stored_max_relative_difference", waveBetween},
                    {"process_peak_rss_mb_before_stored", rssBeforeStored},
                    {"process_peak_rss_mb_after_stored", peakRssMb()}});
  }
  return rows;
}

int runBench(const BenchArgs& args) {
  // With --json, stdout carries only the JSON document; the human table goes to stderr.
  std::ostream& table = args.json ? std::cerr : std::cout;
  nlohmann::json rows = nlohmann::json::array();
  // Phase 1: the distance maps at every size, so the peak RSS reported is ours (before CGAL).
  struct Case {
    TriMesh mesh;
    std::vector<SurfacePoint> sources;
    double mapSeconds = 0.0, precompute = 0.0, rss = 0.0;
  };
  std::vector<Case> cases;
  for (int size : args.sizes) {
    Case c;
    c.mesh = samples::generateSampleWithVertices("bump", size);
    geodesic::DistanceSolverOptions options;
    options.threads = args.threads;
    const geodesic::DistanceSolver solver(c.mesh, options);
    c.precompute = solver.precomputeSeconds();
    c.sources = sidePoints(c.mesh, args.sources, false);
    const auto targets = sidePoints(c.mesh, args.sources, true);
    const Stopwatch watch;
    const auto map = solver.distances(c.sources, targets);  // all sources to the opposite side
    c.mapSeconds = watch.seconds();
    c.rss = peakRssMb();
    cases.push_back(std::move(c));
  }
  // Phase 2: ms per source, ours and CGAL's, interleaved source by source so that a change in
  // machine load hits both; and our error against CGAL on the same sources.
  table << "ms/src: median thread CPU time per single-source field (one thread each); speedup = "
           "their ratio;\n"
           "map speedup = CGAL ms/src over the map's wall time per source on `threads` threads.\n";
  table << fmt::format("{:>7} {:>11} {:>11} {:>8} {:>11} {:>9} {:>10} {:>7} {:>9} {:>11}\n",
                       "verts", "ours ms/src", "cgal ms/src", "speedup", "max rel err", "precomp s",
                       fmt::format("map{} s", args.sources), "threads", "map spdup", "ours RSS MB");
  for (size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const geodesic::DistanceSolver solver(c.mesh);
    const int cgalCount = k < args.cgalSources.size() ? args.cgalSources[k] : 0;
    const int count =
        std::max(cgalCount, std::min<int>(args.timedSources, static_cast<int>(c.sources.size())));
    // Per-source cost as thread CPU time (both engines are single-threaded here): other jobs on a
    // shared machine inflate wall time, but barely the CPU time a thread is charged. Medians.
    std::vector<double> oursMsList, cgalMsList;
    double maxError = 0.0;
    for (int i = 0; i < count; ++i) {
      const SurfacePoint s = intoFace(c.sources[(2 * i + 1) * c.sources.size() / (2 * count)]);
      double t0 = threadCpuSeconds();
      const auto ours = solver.distances(s);
      oursMsList.push_back(1e3 * (threadCpuSeconds() - t0));
      if (i >= cgalCount) continue;
      t0 = threadCpuSeconds();
      const auto exact = geodesic::referenceDistances(c.mesh, s);
      cgalMsList.push_back(1e3 * (threadCpuSeconds() - t0));
      for (size_t v = 0; v < exact.size(); ++v) {
        if (exact[v] > 2.0 * solver.meanEdgeLength() && std::isfinite(exact[v])) {
          maxError = std::max(maxError, std::abs(ours.vertexDistances[v] - exact[v]) / exact[v]);
        }
      }
    }
    const double oursMs = median(oursMsList);
    const double cgalMs = cgalCount > 0 ? median(cgalMsList) : NAN;
    const double speedup = cgalMs / oursMs;
    // The target arithmetic: the whole map's wall time per source (on `threads` threads)
    // against CGAL's time per source.
    const double mapSpeedup = cgalMs / (1e3 * c.mapSeconds / args.sources);
    table << fmt::format(
        "{:>7} {:>11.2f} {:>11.1f} {:>7.1f}x {:>11.2e} {:>9.4f} {:>10.3f} {:>7} {:>8.1f}x "
        "{:>11.0f}\n",
        c.mesh.n_vertices(), oursMs, cgalMs, speedup, cgalCount > 0 ? maxError : NAN, c.precompute,
        c.mapSeconds, args.threads, mapSpeedup, c.rss);
    table.flush();
    auto orNull = [&](double x) {
      return cgalCount > 0 ? nlohmann::json(x) : nlohmann::json(nullptr);
    };
    rows.push_back({{"vertices", c.mesh.n_vertices()},
                    {"ours_ms_per_source", oursMs},
                    {"cgal_ms_per_source", orNull(cgalMs)},
                    {"speedup", orNull(speedup)},
                    {"map_speedup", orNull(mapSpeedup)},
                    {"max_relative_error_vs_cgal", orNull(maxError)},
                    {"precompute_seconds", c.precompute},
                    {"map_sources", args.sources},
                    {"map_seconds", c.mapSeconds},
                    {"threads", args.threads},
                    {"peak_rss_mb", c.rss}});
  }
  table << fmt::format("peak RSS with CGAL: {:.0f} MB\n", peakRssMb());
  nlohmann::json toleranceRows = nlohmann::json::array();
  if (!args.saddleTolerances.empty()) {
    table
        << "\nerror against time by saddleAngleTolerance (reference: tolerance 0 in the same run; "
           "vertices farther than 2 mean edges; side = the opposite side's points)\n";
    table << fmt::format("{:>7} {:>10} {:>11} {:>9} {:>12} {:>13} {:>12}\n", "verts", "tolerance",
                         "ms/src", "windows", "max rel err", "mean rel err", "side max err");
    for (const Case& c : cases) {
      const int count =
          std::min<int>(std::max(args.timedSources, 1), static_cast<int>(c.sources.size()));
      std::vector<SurfacePoint> sources;
      for (int i = 0; i < count; ++i)
        sources.push_back(intoFace(c.sources[(2 * i + 1) * c.sources.size() / (2 * count)]));
      const auto targets = sidePoints(c.mesh, args.sources, true);
      for (auto& row : toleranceTable(c.mesh, sources, targets, args.saddleTolerances)) {
        table << fmt::format("{:>7} {:>10.2g} {:>11.2f} {:>9.0f} {:>12.2e} {:>13.2e} {:>12.2e}\n",
                             c.mesh.n_vertices(), row["saddle_angle_tolerance_rad"].get<double>(),
                             row["ms_per_source"].get<double>(),
                             row["windows_per_source"].get<double>(),
                             row["max_relative_error_vertices"].get<double>(),
                             row["mean_relative_error_vertices"].get<double>(),
                             row["max_relative_error_side_to_side"].get<double>());
        row["vertices"] = c.mesh.n_vertices();
        toleranceRows.push_back(row);
      }
    }
  }
  if (!args.csv.empty()) {
    std::ostringstream file;
    file << "vertices,ours_ms_per_source,cgal_ms_per_source,speedup,max_relative_error_vs_cgal,"
            "precompute_seconds,"
            "map_sources,map_seconds,map_speedup,threads,peak_rss_mb\n";
    for (const auto& r : rows) {
      auto num = [](const nlohmann::json& j) {
        return j.is_null() ? std::string("") : fmt::format("{}", j.get<double>());
      };
      file << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", r["vertices"].get<size_t>(),
                          num(r["ours_ms_per_source"]), num(r["cgal_ms_per_source"]),
                          num(r["speedup"]), num(r["max_relative_error_vs_cgal"]),
                          num(r["precompute_seconds"]), r["map_sources"].get<int>(),
                          num(r["map_seconds"]), num(r["map_speedup"]), r["threads"].get<int>(),
                          num(r["peak_rss_mb"]));
    }
    writeFileAtomically(args.csv, file.str());
  }
  const nlohmann::json engineRows =
      args.engineRows == "none" ? nlohmann::json::array() : engineTable(args, table);
  if (args.json) {
    nlohmann::json out = rows;
    if (!args.saddleTolerances.empty() || args.engineRows != "none") {
      out = {{"sizes", rows}};
      if (!args.saddleTolerances.empty()) out["saddle_tolerance"] = toleranceRows;
      if (args.engineRows != "none") out["engines"] = engineRows;
    }
    std::cout << out.dump(2) << "\n";
  }
  return kExitOk;
}

}  // namespace

void registerGeodesicBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd =
      bench.add_subcommand("geodesic",
                           "Geodesic engine vs CGAL's exact Surface_mesh_shortest_path on the bump "
                           "sample: ms per source, "
                           "speed-up, max error, distance-map wall time, precomputation, peak RSS");
  cmd->add_option("--sizes", args->sizes, "approximate vertex counts of the bump patches")
      ->delimiter(',')
      ->check(CLI::Range(100, 1000000));
  cmd->add_option("--sources", args->sources, "sources (and targets) of the timed distance map")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--threads", args->threads, "threads of the distance map")
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_option("--timed-sources", args->timedSources,
                  "single-thread sources timed for ms per source")
      ->check(CLI::Range(0, 10000));
  cmd->add_option("--cgal-sources", args->cgalSources, "CGAL sources per size (0 skips CGAL)")
      ->delimiter(',')
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--saddle-tolerance", args->saddleTolerances,
                  "also tabulate error against time over these saddleAngleTolerance values "
                  "(radians; 0 = exact), "
                  "reference: the exact mode of the same run")
      ->delimiter(',')
      ->check(finiteRange(0.0, 0.0999));
  cmd->add_option("--engine-rows", args->engineRows,
                  "stored-window, front-only and wavefront engines on the bump, sphere cap and "
                  "plane of issue 19: none, "
                  "standard, or large (adds the 418k-triangle bump: minutes, gigabytes for the "
                  "stored engine)")
      ->check(CLI::IsMember({"none", "standard", "large"}));
  cmd->add_option("--engine-sources", args->engineSources,
                  "vertex sources per row of the engine table (large row: 1)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--csv", args->csv, "also write the table as CSV");
  cmd->add_flag("--json", args->json, "also print the table as JSON");
  cmd->callback([args, &action] { action = [args] { return runBench(*args); }; });
}

}  // namespace egg::app
