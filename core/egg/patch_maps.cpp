#include "core/egg/patch_maps.hpp"

#include "core/egg/patch_side.hpp"

#include "core/egg/map_proxy.hpp"
#include "core/egg/map_refinement.hpp"
#include "core/errors.hpp"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace egg {

void DistanceMapOptions::validate() const {
  if (resolution < 3 || resolution > 2000)
    throw InvalidInput("grid.map_resolution must lie in [3, 2000]");
  if (!(toleranceRelative >= 0.0) || !std::isfinite(toleranceRelative))
    throw InvalidInput(
        "grid.map_tolerance_relative must be a finite number >= 0 (a fraction of the shorter side; "
        "0 = exact rows)");
  if (initialNodes < 2)
    throw InvalidInput("distance map initialNodes must be >= 2 (both corners of the start side)");
  if (proxyVertices != 0 && (proxyVertices < 8 || proxyVertices > 10000000))
    throw InvalidInput(
        "grid.map_proxy_vertices must be 0 (maps on the patch itself) or an integer in [8, 1e7], "
        "got " +
        std::to_string(proxyVertices));
  if (!(proxyToleranceRelative >= 0.0) || !std::isfinite(proxyToleranceRelative))
    throw InvalidInput(
        "distance map proxyToleranceRelative must be a finite number >= 0 (0 = exact rows on the "
        "proxy)");
  if (!(proxySaddleAngleTolerance >= 0.0) || !std::isfinite(proxySaddleAngleTolerance))
    throw InvalidInput(
        "distance map proxySaddleAngleTolerance must be a finite number >= 0 (radians; 0 = exact "
        "fields on the proxy)");
}

std::pair<int, bool> familySide(Family family, bool end) {
  const PatchSide side = PatchSide::whereMembersEnd(family, end);
  return {side.index(), side.againstCorners()};
}

double familySideLength(const Patch& patch, Family family, bool end) {
  return patch.sideLengths[familySide(family, end).first];
}

SurfacePoint familyBoundaryPoint(const Patch& patch, Family family, bool end, double x) {
  const auto [side, reversed] = familySide(family, end);
  const double length = patch.sideLengths[side];
  x = std::clamp(x, 0.0, 1.0);
  return sidePoint(patch, side, (reversed ? 1.0 - x : x) * length);
}

namespace {

// Both maps of `patch` measured with `solver` (which must be built on patch.mesh); the adaptive
// rows refine to `toleranceRelative` times the family's shorter side. Sides, diagonals and alpha
// are those of `patch`.
PatchDistanceMaps mapsOn(const Patch& patch, const geodesic::DistanceSolver& solver, int n,
                         double toleranceRelative, int initialNodes) {
  PatchDistanceMaps maps;
  maps.sides = patch.sideLengths;
  maps.alphaSpatial = patch.innerAngles[0];
  int propagations[2] = {0, 0};
  const auto familyMap = [&](Family family) {
    std::vector<SurfacePoint> targets;
    for (int j = 0; j < n; ++j)
      targets.push_back(familyBoundaryPoint(patch, family, true, static_cast<double>(j) / (n - 1)));
    // One batch per call: the initial nodes, then the middles of every interval still under test.
    const auto exactRows = [&](const std::vector<int>& indices) {
      std::vector<SurfacePoint> sources;
      for (int i : indices)
        sources.push_back(
            familyBoundaryPoint(patch, family, false, static_cast<double>(i) / (n - 1)));
      auto fields = solver.distances(sources, targets);
      std::vector<std::vector<double>> rows;
      for (auto& field : fields) {
        for (double d : field.targetDistances)
          if (!std::isfinite(d))
            throw SolverFailure("distance map: a boundary point is unreachable inside the patch");
        rows.push_back(std::move(field.targetDistances));
      }
      return rows;
    };
    std::vector<std::vector<double>> rows;
    const double tolerance = toleranceRelative * std::min(familySideLength(patch, family, false),
                                                          familySideLength(patch, family, true));
    const auto stats = refineMapRows(n, n, tolerance, initialNodes, exactRows, rows);
    propagations[family == Family::U ? 0 : 1] = stats.exactRows;
    DistanceMap map(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) map.at(i, j) = rows[i][j];
    (family == Family::U ? maps.u : maps.v) = std::move(map);
  };
  // Both batches share the thread pool, so the tail of one family overlaps the other.
  tbb::parallel_invoke([&] { familyMap(Family::U); }, [&] { familyMap(Family::V); });
  maps.propagations = propagations[0] + propagations[1];
  maps.diagonalE = maps.u.at(0, n - 1);  // c0 to c2
  maps.diagonalF = maps.u.at(n - 1, 0);  // c3 to c1
  return maps;
}

}  // namespace

bool mapsUseProxy(const Patch& patch, const DistanceMapOptions& options) {
  return options.proxyVertices != 0 &&
         static_cast<int>(patch.mesh.n_vertices()) > options.proxyVertices;
}

geodesic::DistanceSolverOptions proxySolverOptions(const geodesic::DistanceSolver& solver,
                                                   const DistanceMapOptions& options) {
  geodesic::DistanceSolverOptions proxyOptions = solver.options();
  proxyOptions.saddleAngleTolerance = options.proxySaddleAngleTolerance;
  return proxyOptions;
}

PatchDistanceMaps computeDistanceMaps(const Patch& patch, const geodesic::DistanceSolver& solver,
                                      const DistanceMapOptions& options) {
  options.validate();
  if (!mapsUseProxy(patch, options)) {
    // A patch no larger than its proxy would be is its own proxy: the proxy's row tolerance, as
    // its mesh noise is the proxy's (at 1e-4 the 0.6k-vertex bench patch refined 145 of 200 rows
    // and took longer than the 3.4k one). proxyVertices = 0 asks for the rows on the patch at
    // toleranceRelative whatever its size.
    const double tolerance =
        options.proxyVertices > 0 ? options.proxyToleranceRelative : options.toleranceRelative;
    return mapsOn(patch, solver, options.resolution, tolerance, options.initialNodes);
  }
  // Maps on the proxy (map_proxy.hpp): its own solver, its own row tolerance; the sides, alpha
  // and the corners' parameters are the fine patch's (copied into the proxy patch).
  const MapProxy proxy = makeMapProxy(patch, options.proxyVertices);
  const geodesic::DistanceSolver proxySolver(proxy.patch.mesh, proxySolverOptions(solver, options));
  return computeDistanceMaps(proxy, proxySolver, options);
}

PatchDistanceMaps computeDistanceMaps(const MapProxy& proxy,
                                      const geodesic::DistanceSolver& proxySolver,
                                      const DistanceMapOptions& options) {
  options.validate();
  // The diagonals (Problem 2.3's (e - e_bar)(f - f_bar) and the injectivity check) are the
  // proxy's too: measured on the patch by directed propagations they cost ~25 ms of CPU at 3.4k
  // vertices (a corner-to-corner ellipse is half the patch) and moved neither alpha_bar nor eta.
  return mapsOn(proxy.patch, proxySolver, options.resolution, options.proxyToleranceRelative,
                options.initialNodes);
}

}  // namespace egg
