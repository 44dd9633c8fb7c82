#include "core/egg/patch_design.hpp"
#include "core/timing.hpp"

#include "core/errors.hpp"
#include "core/mesh/smoothing.hpp"

#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
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

// The patch vertex nearest to the mean of its vertices: a point on the patch to split at when no
// peak says where (the mean itself lies off a curved patch).
Eigen::Vector3d patchCentre(const Patch& patch) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto vh : patch.mesh.vertices()) mean += toEigen(patch.mesh.point(vh));
  if (patch.mesh.n_vertices() == 0) return mean;
  mean /= static_cast<double>(patch.mesh.n_vertices());
  Eigen::Vector3d nearest = mean;
  double best = std::numeric_limits<double>::infinity();
  for (auto vh : patch.mesh.vertices()) {
    const Eigen::Vector3d p = toEigen(patch.mesh.point(vh));
    if ((p - mean).squaredNorm() < best) best = (p - mean).squaredNorm(), nearest = p;
  }
  return nearest;
}

// Families and p_max of an eta failure: the worst of the checks above eta_max (Section 3.4.1).
DesignFailure etaFailure(const Patch& patch, const std::vector<EtaCheck>& checks, double etaU,
                         double etaV, double etaMax) {
  DesignFailure f;
  f.kind = DesignFailureKind::Eta;
  f.familyU = etaU > etaMax;
  f.familyV = etaV > etaMax;
  if (!f.familyU && !f.familyV)
    f.familyU = f.familyV = true;  // cannot happen for a failed check; be safe
  const EtaCheck* worst = nullptr;
  for (const auto& c : checks)
    if (c.eta > etaMax && (!worst || c.eta > worst->eta)) worst = &c;
  f.peak = worst ? worst->peak : patchCentre(patch);
  return f;
}

double designMeanSide(const PatchDistanceMaps& maps) {
  // The same expression (and rounding) as alpha_bar.cpp's scale of the cladding tolerances.
  return 0.25 * (maps.sides[0] + maps.sides[1] + maps.sides[2] + maps.sides[3]);
}

// Problem 2.3 failed (solveAlphaBar threw InfeasiblePatch). Which family's slopes fail decides the
// split (Algorithm 1): read at the requested angle for choice Given / Unrolled, else at the best
// sample of the convex range (least largest constraint), where the failure is narrowest.
DesignFailure slopeFailure(const PatchDesign& d, const std::string& message) {
  DesignFailure f;
  f.message = message;
  const AlphaBarOptions& options = d.options.alphaBar;
  const auto range = convexAlphaRange(d.maps.sides, 1e-9, options.minPlanarAngle);
  if (!range) {
    f.kind = DesignFailureKind::Convexity;
    f.familyU = f.familyV = true;
    f.peak = patchCentre(d.patch);
    return f;
  }
  f.kind = DesignFailureKind::Slopes;
  std::optional<AlphaBarEvaluation> at;
  if (options.choice == AlphaBarChoice::Given || options.choice == AlphaBarChoice::Unrolled) {
    const double alpha =
        options.choice == AlphaBarChoice::Given ? options.givenAlphaBar : d.maps.alphaSpatial;
    const auto e = evaluateAlphaBar(d.maps, alpha, options);
    if (e.closable) at = e;
  }
  if (!at) {
    double least = std::numeric_limits<double>::infinity();
    const int n = options.scanSamples;
    for (int k = 0; k < n; ++k) {
      const auto e =
          evaluateAlphaBar(d.maps, range->lo + (range->hi - range->lo) * k / (n - 1), options);
      if (!e.closable) continue;
      const double worst = std::max({e.diagonalProduct, e.violationU, e.violationV});
      if (worst < least) least = worst, at = e;
    }
  }
  if (at) {
    f.familyU = at->violationU >= 0.0;
    f.familyV = at->violationV >= 0.0;
  }
  // Only the diagonal inequality (2.2), which couples both maps, or bijectivity fails there.
  if (!f.familyU && !f.familyV) f.familyU = f.familyV = true;
  f.peak = d.peaks.peaks.empty() ? patchCentre(d.patch) : d.peaks.peaks.front().position;
  return f;
}

// Section 2.3.3: cotangent-Laplacian smoothing of the patch (boundary held, it is the traced
// quad) repeated until eta <= eta_max. Only when the check fails and smoothing is asked for
// (in multi-patch mode splitting replaces it, Section 3.1); the maps are then redone on the
// smoothed patch. `solver` becomes the smoothed patch's; returns the failure when smoothing
// leaves a corner's inner angle at pi or above.
std::optional<DesignFailure> smoothUntilUnique(
    PatchDesign& d, std::shared_ptr<const geodesic::DistanceSolver>& solver,
    const EggOptions& options) {
  std::vector<Eigen::Vector3d> original;
  for (auto vh : d.patch.mesh.vertices()) original.push_back(toEigen(d.patch.mesh.point(vh)));
  SmoothingOptions smoothing;
  smoothing.fixBoundary = true;
  int rounds = 0;
  UniquenessReport report = d.uniqueness;
  // The same boundary samples as the check on the maps, so eta before and after smoothing
  // compare like with like.
  UniquenessOptions after = options.uniqueness;
  after.sideSamples = options.maps.resolution;
  while (!report.passed && rounds < options.uniqueness.maxSmoothingRounds) {
    d.patch.mesh = smoothMeshStep(d.patch.mesh, smoothing).mesh;
    ++rounds;
    solver = std::make_shared<geodesic::DistanceSolver>(d.patch.mesh);
    report = checkUniqueness(d.patch, *solver, after);
    d.propagations += report.propagations;
  }
  report.smoothingRounds = rounds;
  for (auto vh : d.patch.mesh.vertices())
    report.smoothingDisplacementM =
        std::max(report.smoothingDisplacementM,
                 (toEigen(d.patch.mesh.point(vh)) - original[vh.idx()]).norm());
  report.seconds += d.uniqueness.seconds;
  report.checksBeforeSmoothing = d.uniqueness.checks;
  report.etaBeforeSmoothing = std::max(d.uniqueness.etaU, d.uniqueness.etaV);
  const UniquenessReport before = d.uniqueness;
  d.uniqueness = report;
  refreshPatchGeometry(d.patch);
  d.solver = solver;
  // Smoothing moves the interior next to the corners, so criterion (iv) is checked again. The
  // split this asks for is the one the eta failure before smoothing asked for.
  for (int k = 0; k < 4; ++k) {
    if (d.patch.innerAngles[k] >= M_PI - options.patch.angleMargin) {
      DesignFailure f =
          etaFailure(d.patch, before.checks, before.etaU, before.etaV, options.uniqueness.etaMax);
      f.kind = DesignFailureKind::Convexity;
      f.message = "after smoothing, the inner angle at corner " + std::to_string(k) + " is " +
                  std::to_string(d.patch.innerAngles[k]) + " rad, not below pi (criterion iv)";
      return f;
    }
  }
  return std::nullopt;
}

PatchDesign failed(PatchDesign d, DesignFailure failure,
                   std::chrono::steady_clock::time_point started) {
  d.feasible = false;
  d.failure = std::move(failure);
  d.seconds.total = secondsSince(started);
  return d;
}

}  // namespace

PatchDesign designPatch(Patch patch, const EggOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  PatchDesign d;
  d.options = options;
  d.patch = std::move(patch);

  // One solver for the whole design (and the grid): its tables serve the eta check, the maps and
  // the tracing.
  auto t = std::chrono::steady_clock::now();
  std::shared_ptr<const geodesic::DistanceSolver> solver =
      std::make_shared<geodesic::DistanceSolver>(d.patch.mesh);
  d.seconds.uniqueness = secondsSince(t);

  // The maps and the eta check in one go (Sections 2.4.2, 2.3.3, 3.4.1): the maps hold the
  // diagonals; the check adds one field per K peak and one from each p1 (per peak and family),
  // exact, since the maps' rows between source fields are interpolated; none when the
  // injectivity bound holds for sure. Curvature, peaks and these fields run alongside the
  // maps' batches on the same thread pool.
  // With a proxy (map_proxy.hpp) both read their fields there; eta's distances are then measured
  // on the patch by directed propagations (uniquenessFieldsViaProxy).
  t = std::chrono::steady_clock::now();
  UniquenessFields etaFields;
  etaFields.samples = options.maps.resolution;
  std::optional<MapProxy> proxy;
  std::unique_ptr<geodesic::DistanceSolver> proxySolver;
  {
    // One task group: the peak search (curvature of the fine patch) overlaps the decimation, the
    // maps start as soon as the proxy exists, and the eta fields, which need both, are spawned by
    // whichever of the two finishes last, so they run alongside the maps. (Waiting for the peak
    // search alone let the waiting thread pick up the maps task first: eta ran after the maps.)
    tbb::task_group tasks;
    std::atomic<int> etaInputsPending{2};  // the peaks and the proxy
    const auto etaInputReady = [&] {
      if (--etaInputsPending > 0) return;
      tasks.run([&] {
        if (d.peaks.peaks.empty() || boundCertainlyHolds(d.patch, d.peaks)) return;
        const int n = options.maps.resolution;
        etaFields =
            proxy ? uniquenessFieldsViaProxy(d.patch, *solver, *proxy, *proxySolver, d.peaks, n)
                  : uniquenessFields(d.patch, d.peaks, *solver, n);
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
      d.peaks = findPatchPeaks(d.patch, options.uniqueness);
      etaInputReady();
    });
    if (mapsUseProxy(d.patch, options.maps)) {
      proxy = makeMapProxy(d.patch, options.maps.proxyVertices);
      proxySolver = std::make_unique<geodesic::DistanceSolver>(
          proxy->patch.mesh, proxySolverOptions(*solver, options.maps));
    }
    tasks.run([&] {
      d.maps = proxy ? computeDistanceMaps(*proxy, *proxySolver, options.maps)
                     : computeDistanceMaps(d.patch, *solver, options.maps);
    });
    etaInputReady();
    tasks.wait();
  }
  if (proxy && !d.peaks.peaks.empty() &&
      measureDiagonalsNearTheBound(d.maps, d.patch, *solver, d.peaks))
    d.propagations += 2;
  d.propagations += d.maps.propagations + etaFields.propagations();
  d.seconds.distanceMaps = secondsSince(t);

  t = std::chrono::steady_clock::now();
  d.uniqueness = checkUniqueness(d.patch, d.peaks, etaFields, d.maps, options.uniqueness);
  d.uniqueness.propagations = etaFields.propagations();
  if (!d.uniqueness.passed && options.uniqueness.smooth) {
    if (std::optional<DesignFailure> f = smoothUntilUnique(d, solver, options)) {
      d.seconds.uniqueness += secondsSince(t);
      return failed(std::move(d), std::move(*f), started);
    }
  }
  d.solver = solver;
  if (!d.uniqueness.passed) {
    const UniquenessReport& u = d.uniqueness;
    DesignFailure f = etaFailure(d.patch, u.checks, u.etaU, u.etaV, options.uniqueness.etaMax);
    std::ostringstream message;
    message << "shortest geodesics are not unique on this patch: eta_u = " << u.etaU
            << ", eta_v = " << u.etaV << " > eta_max = " << options.uniqueness.etaMax
            << " (K_max = " << u.gaussianMax << " 1/m^2, injectivity bound " << u.injectivityBoundM
            << " m < longest geodesic " << u.longestGeodesicM << " m; smoothing rounds "
            << u.smoothingRounds << ")";
    f.message = message.str();
    d.seconds.uniqueness += secondsSince(t);
    return failed(std::move(d), std::move(f), started);
  }
  d.seconds.uniqueness += secondsSince(t);
  if (d.uniqueness.smoothingRounds > 0) {
    t = std::chrono::steady_clock::now();
    d.maps = computeDistanceMaps(d.patch, *solver, options.maps);
    d.propagations += d.maps.propagations;
    d.seconds.distanceMaps += secondsSince(t);
  }

  t = std::chrono::steady_clock::now();
  try {
    d.alphaBar = solveAlphaBar(d.maps, options.alphaBar);
  } catch (const InfeasiblePatch& e) {
    DesignFailure f = slopeFailure(d, e.what());
    d.seconds.sqp = secondsSince(t);  // with the classification of the failure
    return failed(std::move(d), std::move(f), started);
  }
  d.seconds.sqp = secondsSince(t);
  d.feasible = true;
  d.seconds.total = secondsSince(started);
  return d;
}

void requireFeasible(const PatchDesign& design) {
  if (!design.feasible) throw InfeasiblePatch(design.failure.message);
}

namespace {

const CladdingFunction& designCladding(const PatchDesign& design, Family family) {
  if (!design.feasible)
    throw InvalidInput("the patch design is infeasible (" + design.failure.message + ")");
  return family == Family::U ? design.alphaBar.claddingU : design.alphaBar.claddingV;
}

}  // namespace

double claddingValue(const PatchDesign& design, Family family, double x1) {
  return designCladding(design, family).evaluate(x1);
}

double claddingInverse(const PatchDesign& design, Family family, double x2) {
  return designCladding(design, family).inverse(x2);
}

double claddingSlope(const CladdingFunction& cladding, double x1) {
  const auto& p = cladding.points;
  if (p.size() < 2)
    throw InvalidInput("claddingSlope: the cladding function has fewer than two points");
  x1 = std::clamp(x1, 0.0, 1.0);
  // The segment CladdingFunction::evaluate interpolates on (cladding.cpp interpolateAlong): the
  // last point with x1 at or below the key starts it, so the slope is right-continuous.
  size_t lo = 0, top = p.size() - 1;
  while (top - lo > 1) {
    const size_t mid = (lo + top) / 2;
    (p[mid].x() <= x1 ? lo : top) = mid;
  }
  const Eigen::Vector2d step = p[top] - p[lo];
  if (!(step.x() > 0.0))
    throw InvalidInput("claddingSlope: the cladding function is not bijective (criterion iii)");
  return step.y() / step.x();
}

double claddingSlope(const PatchDesign& design, Family family, double x1) {
  return claddingSlope(designCladding(design, family), x1);
}

CladdingFunction claddingAt(const PatchDesign& design, Family family, double alphaBar) {
  designCladding(design, family);  // feasibility
  const AlphaBarOptions& options = design.options.alphaBar;
  const auto quad = planarQuad(design.maps.sides, alphaBar, options.minPlanarAngle);
  if (!quad)
    throw InvalidInput("claddingAt: alpha_bar = " + std::to_string(alphaBar) +
                       " rad gives no convex planar quad with this patch's sides (criterion iv)");
  return claddingFunction(design.maps.map(family), *quad, family, designMeanSide(design.maps),
                          options.cladding);
}

FamilyMembers placeDesignMembers(const PatchDesign& design, Family family,
                                 const MemberOptions& options) {
  return placeMembers(designCladding(design, family), design.alphaBar.quad,
                      familySideLength(design.patch, family, false),
                      familySideLength(design.patch, family, true), options);
}

FamilyMembers membersAt(const PatchDesign& design, Family family, const std::vector<double>& x1) {
  const CladdingFunction& cladding = designCladding(design, family);
  if (x1.size() < 2 || x1.front() != 0.0 || x1.back() != 1.0)
    throw InvalidInput(
        "membersAt: x1 must start at 0 and end at 1 (the boundary members), with at least two "
        "members");
  for (size_t k = 1; k < x1.size(); ++k)
    if (!(x1[k] > x1[k - 1]))
      throw InvalidInput("membersAt: x1 must increase strictly (x1[" + std::to_string(k) + "] = " +
                         std::to_string(x1[k]) + " after " + std::to_string(x1[k - 1]) + ")");
  FamilyMembers members;
  members.family = family;
  for (size_t k = 0; k < x1.size(); ++k) {
    const bool boundary = k == 0 || k + 1 == x1.size();
    members.x1.push_back(x1[k]);
    // The boundary members are the patch sides: exactly (0,0) and (1,1), as placeMembers sets them.
    members.x2.push_back(k == 0 ? 0.0 : boundary ? 1.0 : cladding.evaluate(x1[k]));
    members.lengths.push_back(cladding.lengthAt(x1[k]));
    members.origin.push_back(boundary ? MemberOrigin::Boundary : MemberOrigin::Given);
  }
  return members;
}

EggGrid traceDesignGrid(const PatchDesign& design, const FamilyMembers& u, const FamilyMembers& v,
                        const GridOptions& options) {
  designCladding(design, Family::U);  // feasibility
  if (u.family != Family::U || v.family != Family::V)
    throw InvalidInput(
        "traceDesignGrid: the first members must be of family u, the second of family v");
  return buildGrid(design.patch, *design.solver, design.alphaBar.quad, u, v, options);
}

}  // namespace egg
