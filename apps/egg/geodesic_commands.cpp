// `egg geodesic SURFACE --source x,y,z --out F.csv`.
#include "apps/egg/commands.hpp"
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

Eigen::Vector3d parsePoint(const std::string& text) {
  std::stringstream in(text);
  std::string item;
  std::vector<double> values;
  while (std::getline(in, item, ',')) {
    try {
      size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InvalidInput("--source: '" + text + "' is not x,y,z (metres)");
    }
  }
  if (values.size() != 3) throw InvalidInput("--source: '" + text + "' is not x,y,z (metres)");
  return {values[0], values[1], values[2]};
}

struct GeodesicArgs {
  std::string surface;
  std::string source;
  std::string out;
  std::string engine;  // empty: the solver's default
  bool exact = false;
  double mergeTolerance = geodesic::DistanceSolverOptions{}.imageMergeTolerance;
  bool json = false;
};

int runGeodesic(const GeodesicArgs& args) {
  const TriMesh mesh = loadSurfaceArgument(args.surface);
  const Eigen::Vector3d requested = parsePoint(args.source);
  geodesic::DistanceSolverOptions options;
  if (args.exact)
    options = geodesic::DistanceSolverOptions::exact();
  else if (!(args.mergeTolerance >= 0.0 && args.mergeTolerance < 1e-3))
    throw InvalidInput(fmt::format(
        "--merge-tolerance {}: must be in [0, 0.001) (a fraction of the edge length; 0: off)",
        args.mergeTolerance));
  else
    options.imageMergeTolerance = args.mergeTolerance;
  if (args.engine == "stored")
    options.engine = geodesic::DistanceSolverOptions::Engine::StoredWindows;
  if (args.engine == "front") options.engine = geodesic::DistanceSolverOptions::Engine::FrontOnly;
  if (args.engine == "wavefront")
    options.engine = geodesic::DistanceSolverOptions::Engine::Wavefront;
  const geodesic::DistanceSolver solver(mesh, options);
  const SurfacePoint source = geodesic::snapToSurface(mesh, requested);
  const Eigen::Vector3d snapped = position(mesh, source);
  const auto field = solver.distances(source);
  {
    std::ostringstream file;
    file << "x,y,z,distance\n";
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      const double d = field.vertexDistances[vh.idx()];
      file << fmt::format("{:.17g},{:.17g},{:.17g},{}\n", p[0], p[1], p[2],
                          std::isfinite(d) ? fmt::format("{:.17g}", d) : std::string("inf"));
    }
    writeFileAtomically(args.out, file.str());
  }
  double maxDistance = 0.0;
  int unreachable = 0;
  for (double d : field.vertexDistances) {
    if (std::isfinite(d))
      maxDistance = std::max(maxDistance, d);
    else
      ++unreachable;
  }
  nlohmann::json summary = {{"vertices", mesh.n_vertices()},
                            {"source_requested_m", {requested.x(), requested.y(), requested.z()}},
                            {"source_snapped_m", {snapped.x(), snapped.y(), snapped.z()}},
                            {"snap_distance_m", (snapped - requested).norm()},
                            {"max_distance_m", maxDistance},
                            {"unreachable_vertices", unreachable},
                            {"windows", field.windowsCreated},
                            {"peak_windows", field.peakWindows},
                            {"peak_working_memory_mb", field.peakBytes / 1e6},
                            {"precompute_seconds", solver.precomputeSeconds()},
                            {"seconds", field.seconds},
                            {"out", args.out}};
  if (args.json) {
    std::cout << summary.dump(2) << "\n";
  } else {
    std::cout << fmt::format(
        "source    ({:.6g}, {:.6g}, {:.6g}) snapped to the surface ({:.3g} m away)\n", snapped.x(),
        snapped.y(), snapped.z(), (snapped - requested).norm());
    std::cout << fmt::format("distances {} vertices, max {:.6g} m, {} unreachable\n",
                             mesh.n_vertices(), maxDistance, unreachable);
    std::cout << fmt::format("time      {:.3f} s (+ {:.3f} s precomputation)\nwritten   {}\n",
                             field.seconds, solver.precomputeSeconds(), args.out);
  }
  return kExitOk;
}

}  // namespace

void registerGeodesicCommand(CLI::App& parent, Action& action) {
  auto args = std::make_shared<GeodesicArgs>();
  auto* cmd = parent.add_subcommand(
      "geodesic",
      "Geodesic distances (the polyhedral distance, within 1e-5) from a point on SURFACE to every "
      "vertex, written as x,y,z,distance CSV");
  cmd->add_option("SURFACE", args->surface, "sample name, mesh file, or scene file (its surface)")
      ->required();
  cmd->add_option("--source", args->source, "source point x,y,z in metres (snapped to the surface)")
      ->required();
  cmd->add_option("--out", args->out, "output CSV (x,y,z,distance per vertex; inf if unreachable)")
      ->required();
  cmd->add_option("--engine", args->engine,
                  "stored (every window kept), front (only the queued windows, far less memory) or "
                  "wavefront "
                  "(the same, queued per edge, VTP-style); default: the solver's")
      ->check(CLI::IsMember({"stored", "front", "wavefront"}));
  cmd->add_flag(
      "--exact", args->exact,
      "the exact polyhedral distance: every saddle a pseudo-source, no near images merged");
  cmd->add_option(
         "--merge-tolerance", args->mergeTolerance,
         "near images merged within this fraction of the edge length, in [0, 0.001) (0: off)")
      ->capture_default_str()
      ->excludes("--exact");
  cmd->add_flag("--json", args->json, "print the summary as JSON");
  cmd->callback([args, &action] { action = [args] { return runGeodesic(*args); }; });
}

}  // namespace egg::app
