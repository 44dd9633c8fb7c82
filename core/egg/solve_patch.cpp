#include "core/egg/solve_patch.hpp"

#include "core/errors.hpp"
#include "core/mesh/smoothing.hpp"

#include <tbb/task_group.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <cmath>
#include <string>
#include <sstream>

namespace egg {

void EggOptions::validate() const {
  patch.validate();
  uniqueness.validate();
  maps.validate();
  alphaBar.validate();
  members.validate();
  grid.validate();
}

namespace {
double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

EggResult solveEgg(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& corners, const EggOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  EggResult result;

  auto t = std::chrono::steady_clock::now();
  result.patch = makePatch(surface, corners, options.patch);
  result.seconds.patch = since(t);

  // One solver for the whole solve: its tables serve the eta check, the maps and the tracing.
  t = std::chrono::steady_clock::now();
  auto solver = std::make_unique<geodesic::DistanceSolver>(result.patch.mesh);
  result.seconds.uniqueness = since(t);

  // The maps and the eta check in one go (Sections 2.4.2, 2.3.3, 3.4.1): the maps hold the
  // diagonals; the check adds one field per K peak and one from each p1 (per peak and family),
  // exact, since the maps' rows between source fields are interpolated; none when the
  // injectivity bound holds for sure. Curvature, peaks and these fields run alongside the
  // maps' batches on the same thread pool.
  // With a proxy (map_proxy.hpp) both read their fields there; eta's distances are then measured
  // on the patch by directed propagations (uniquenessFieldsViaProxy).
  t = std::chrono::steady_clock::now();
  PatchPeaks peaks;
  UniquenessFields etaFields;
  etaFields.samples = options.maps.resolution;
  std::optional<MapProxy> proxy;
  std::unique_ptr<geodesic::DistanceSolver> proxySolver;
  // One task group: the peak search (curvature of the fine patch) overlaps the decimation, the
  // maps start as soon as the proxy exists, and the eta fields, which need both, are spawned by
  // whichever of the two finishes last, so they run alongside the maps. (Waiting for the peak
  // search alone let the waiting thread pick up the maps task first: eta ran after the maps.)
  tbb::task_group tasks;
  std::atomic<int> etaInputsPending{2};  // the peaks and the proxy
  const auto etaInputReady = [&] {
    if (--etaInputsPending > 0) return;
    tasks.run([&] {
      if (peaks.peaks.empty() || boundCertainlyHolds(result.patch, peaks)) return;
      const int n = options.maps.resolution;
      etaFields = proxy ? uniquenessFieldsViaProxy(result.patch, *solver, *proxy, *proxySolver, peaks, n)
                        : uniquenessFields(result.patch, peaks, *solver, n);
    });
  };
  // Should anything below throw, the group is waited for (its tasks use the locals above) before
  // the exception leaves; on the normal path tasks.wait() rethrows a task's exception.
  struct WaitFor {
    tbb::task_group& group;
    ~WaitFor() {
      try {
        group.wait();
      } catch (...) {
      }
    }
  } waitFor{tasks};
  tasks.run([&] {
    peaks = findPatchPeaks(result.patch, options.uniqueness);
    etaInputReady();
  });
  if (mapsUseProxy(result.patch, options.maps)) {
    proxy = makeMapProxy(result.patch, options.maps.proxyVertices);
    proxySolver = std::make_unique<geodesic::DistanceSolver>(proxy->patch.mesh, proxySolverOptions(*solver, options.maps));
  }
  tasks.run([&] {
    result.maps = proxy ? computeDistanceMaps(*proxy, *proxySolver, options.maps)
                        : computeDistanceMaps(result.patch, *solver, options.maps);
  });
  etaInputReady();
  tasks.wait();
  if (proxy && !peaks.peaks.empty() && measureDiagonalsNearTheBound(result.maps, result.patch, *solver, peaks))
    result.propagations += 2;
  result.propagations += result.maps.propagations + etaFields.propagations();
  result.seconds.distanceMaps = since(t);

  t = std::chrono::steady_clock::now();
  result.uniqueness = checkUniqueness(result.patch, peaks, etaFields, result.maps, options.uniqueness);
  result.uniqueness.propagations = etaFields.propagations();
  if (!result.uniqueness.passed && options.uniqueness.smooth) {
    // Section 2.3.3: cotangent-Laplacian smoothing of the patch (boundary held, it is the traced
    // quad) repeated until eta <= eta_max. Only when the check fails; the maps are then redone
    // on the smoothed patch.
    std::vector<Eigen::Vector3d> original;
    for (auto vh : result.patch.mesh.vertices()) original.push_back(toEigen(result.patch.mesh.point(vh)));
    SmoothingOptions smoothing;
    smoothing.fix_boundary = true;
    int rounds = 0;
    UniquenessReport report = result.uniqueness;
    // The same boundary samples as the check on the maps, so eta before and after smoothing
    // compare like with like.
    UniquenessOptions after = options.uniqueness;
    after.sideSamples = options.maps.resolution;
    while (!report.passed && rounds < options.uniqueness.maxSmoothingRounds) {
      result.patch.mesh = smoothMeshStep(result.patch.mesh, smoothing).mesh;
      ++rounds;
      solver = std::make_unique<geodesic::DistanceSolver>(result.patch.mesh);
      report = checkUniqueness(result.patch, *solver, after);
      result.propagations += report.propagations;
    }
    report.smoothingRounds = rounds;
    for (auto vh : result.patch.mesh.vertices())
      report.smoothingDisplacementM =
          std::max(report.smoothingDisplacementM, (toEigen(result.patch.mesh.point(vh)) - original[vh.idx()]).norm());
    report.seconds += result.uniqueness.seconds;
    report.checksBeforeSmoothing = result.uniqueness.checks;
    report.etaBeforeSmoothing = std::max(result.uniqueness.etaU, result.uniqueness.etaV);
    result.uniqueness = report;
    refreshPatchGeometry(result.patch);
    // Smoothing moves the interior next to the corners, so criterion (iv) is checked again.
    for (int k = 0; k < 4; ++k) {
      if (result.patch.innerAngles[k] >= M_PI - options.patch.angleMargin) {
        throw InfeasiblePatch("after smoothing, the inner angle at corner " + std::to_string(k) + " is " +
                              std::to_string(result.patch.innerAngles[k]) + " rad, not below pi (criterion iv)");
      }
    }
  }
  if (!result.uniqueness.passed) {
    std::ostringstream message;
    message << "shortest geodesics are not unique on this patch: eta_u = " << result.uniqueness.etaU
            << ", eta_v = " << result.uniqueness.etaV << " > eta_max = " << options.uniqueness.etaMax
            << " (K_max = " << result.uniqueness.gaussianMax << " 1/m^2, injectivity bound "
            << result.uniqueness.injectivityBoundM << " m < longest geodesic " << result.uniqueness.longestGeodesicM
            << " m; smoothing rounds " << result.uniqueness.smoothingRounds << ")";
    throw InfeasiblePatch(message.str());
  }
  result.seconds.uniqueness += since(t);
  if (result.uniqueness.smoothingRounds > 0) {
    t = std::chrono::steady_clock::now();
    result.maps = computeDistanceMaps(result.patch, *solver, options.maps);
    result.propagations += result.maps.propagations;
    result.seconds.distanceMaps += since(t);
  }

  t = std::chrono::steady_clock::now();
  result.alphaBar = solveAlphaBar(result.maps, options.alphaBar);
  result.seconds.sqp = since(t);

  t = std::chrono::steady_clock::now();
  result.membersU = placeMembers(result.alphaBar.claddingU, result.alphaBar.quad, familySideLength(result.patch, Family::U, false),
                                 familySideLength(result.patch, Family::U, true), options.members);
  result.membersV = placeMembers(result.alphaBar.claddingV, result.alphaBar.quad, familySideLength(result.patch, Family::V, false),
                                 familySideLength(result.patch, Family::V, true), options.members);
  result.seconds.members = since(t);

  t = std::chrono::steady_clock::now();
  result.grid = buildGrid(result.patch, *solver, result.alphaBar.quad, result.membersU, result.membersV, options.grid);
  result.seconds.tracing = since(t);
  result.propagations += result.patch.propagations + result.grid.propagations;
  result.seconds.total = since(started);
  return result;
}

}  // namespace egg
