#pragma once
// Uniqueness of shortest geodesics on a patch (Sections 2.3.3, 3.4.1). Near a peak of Gaussian
// curvature, shortest geodesics between opposite boundaries may avoid the peak and leave a gap no
// member can cover. Quick check: members shorter than the injectivity bound pi / sqrt(K_max)
// (Eq. 2.1) are unique. Otherwise, per family and peak p_max: p1 = the boundary point closest to
// p_max, q1 = the point of the opposite boundary minimising d(p1,p_max) + d(p_max,q) - d(p1,q), and
//   eta = (d(p1, p_max) + d(p_max, q1)) / d(p1, q1)
// measures the gap; the patch passes when eta <= eta_max (1.0015 in the thesis).
#include "core/curvature/curvature_peaks.hpp"
#include "core/egg/distance_map.hpp"
#include "core/egg/map_proxy.hpp"
#include "core/egg/patch.hpp"
#include "core/egg/planar_quad.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg {

struct UniquenessOptions {
  double etaMax = 1.0015;  // largest acceptable eta (thesis value)
  int maxPeaks = 4;        // strongest interior K peaks checked
  // Peaks closer to the boundary than this fraction of the longest side (at least two mean edge
  // lengths) count as on the boundary, which is harmless (Section 2.3.3): eta there measures the
  // corner's shape, not a gap (a peak 1 % of the side from a corner gives eta ~ 1 + 0.3 % whatever
  // its height), and the curvature fit is least reliable at corner vertices.
  double boundaryMarginRelative = 0.03;
  int sideSamples = 64;  // boundary samples searched for p1 and q1 (solveEgg: the maps' resolution)
  bool smooth = true;    // smooth the patch (cotan Laplacian) until eta <= eta_max
  int maxSmoothingRounds = 30;  // smoothing rounds before giving up
  void validate() const;        // throws InvalidInput naming the field
};

struct EtaCheck {
  Family family = Family::U;
  int peakVertex = -1;
  Eigen::Vector3d peak = Eigen::Vector3d::Zero(), p1 = Eigen::Vector3d::Zero(),
                  q1 = Eigen::Vector3d::Zero();
  double gaussian = 0.0;  // K near the peak [1/m^2]
  double eta = 1.0;
};

struct UniquenessReport {
  double gaussianMax = 0.0;        // largest K near an interior peak [1/m^2] (0 if none)
  double injectivityBoundM = 0.0;  // pi / sqrt(K_max), +inf without positive peaks
  double longestGeodesicM =
      0.0;                  // longest of the sides and diagonals: a proxy for the longest member
  bool boundHolds = false;  // longest < bound: geodesics are unique, eta not needed
  std::vector<EtaCheck> checks;                 // one per family and peak (empty when skipped)
  double etaU = 1.0, etaV = 1.0;                // worst eta per family
  bool passed = false;                          // bound holds or eta <= eta_max for both families
  std::vector<EtaCheck> checksBeforeSmoothing;  // the failing checks that triggered smoothing
  double etaBeforeSmoothing = 1.0;              // worst eta before smoothing
  int smoothingRounds = 0;              // rounds applied by solveEgg (0 = not needed / not done)
  double smoothingDisplacementM = 0.0;  // largest vertex displacement caused by smoothing
  int propagations =
      0;  // distance fields computed by the check itself (not those reused from the maps)
  double seconds = 0.0;
};

// The bound and, where it fails, the eta check on `patch` (no smoothing here). Two batch calls:
// the diagonals and the peak fields together, then the fields from every p1.
UniquenessReport checkUniqueness(const Patch& patch, const geodesic::DistanceSolver& solver,
                                 const UniquenessOptions& options = {});

// The same check when the distance maps of the patch are known (solveEgg): the maps hold the
// diagonals (their corner rows are exact fields on the patch, or the proxy's within ~1e-3 m), so
// the check itself needs no field. The distances d(p1, q) are NOT read from the maps: their rows
// between exact source fields are interpolated (map_refinement.hpp), off by up to the map
// tolerance, while eta's margin is 1.5e-3 relative. As in Section 3.4.1 each check gets its
// distances from p1 measured on the patch: by uniquenessFields (an exact field from p1; eta then
// equals the standalone check's on the same boundary samples, the check after smoothing) or by
// uniquenessFieldsViaProxy (directed propagations at the samples the proxy picked). With a proxy
// the maps' diagonals are the proxy's (~1e-3 m off): measureDiagonalsNearTheBound replaces them
// by the patch's where that could decide the bound.
struct PatchPeaks {
  std::vector<CurvaturePeak>
      peaks;                 // interior peaks of positive K, strongest first, at most maxPeaks
  double gaussianMax = 0.0;  // largest K near them [1/m^2] (0 if none)
  double seconds = 0.0;      // curvature and peak search
};
PatchPeaks findPatchPeaks(const Patch& patch, const UniquenessOptions& options = {});
// True when even an upper bound of the longest geodesic (the sides, and each diagonal bounded by
// two sides) lies below pi / sqrt(K_max): the check passes without any distance field.
bool boundCertainlyHolds(const Patch& patch, const PatchPeaks& peaks);
// Targets of the peak and p1 fields: the start and end sides of u, then of v, n samples each at x =
// k/(n-1).
std::vector<SurfacePoint> uniquenessPeakTargets(const Patch& patch, int n);
// The fields the eta check reads, to uniquenessPeakTargets(patch, n): one batch from the peaks,
// then one from every p1 (the boundary sample nearest to the peak, per peak and family u, v).
struct UniquenessFields {
  int samples = 0;                                 // n
  std::vector<geodesic::DistanceField> fromPeaks;  // per peak
  std::vector<geodesic::DistanceField> fromP1;     // per peak: u, then v
  // uniquenessFieldsViaProxy: the checks themselves, measured on the patch (the fields above are
  // then the proxy's), and the directed propagations that measured them.
  std::vector<EtaCheck> measured;
  int directed = 0;
  int propagations() const { return static_cast<int>(fromPeaks.size() + fromP1.size()) + directed; }
};
UniquenessFields uniquenessFields(const Patch& patch, const PatchPeaks& peaks,
                                  const geodesic::DistanceSolver& solver, int n);
// The same check with its fields on a coarse proxy of the patch (map_proxy.hpp; `proxySolver` on
// proxy.patch.mesh): the proxy's peak and p1 fields pick p1 and q1 among the n boundary samples,
// and each check's distances d(p1, p_max), d(p_max, q), d(p1, q) are then measured on the patch
// (`solver`) by three propagations directed at them (goal_bound.hpp), for q1 and its two
// neighbouring samples; the sample with the smallest excess d(p1,p_max) + d(p_max,q) - d(p1,q) is
// q1, as in Section 2.3.3. So eta is the patch's own; the proxy's error (~1e-3 m on the 6 m bench
// patch) can only shift which samples are measured, and the excess is stationary at its minimum.
// Why: two p1 fields and a peak field on the proxy plus six short directed propagations per peak
// cost less than three fields on the patch (docs/measurements.md).
UniquenessFields uniquenessFieldsViaProxy(const Patch& patch,
                                          const geodesic::DistanceSolver& solver,
                                          const MapProxy& proxy,
                                          const geodesic::DistanceSolver& proxySolver,
                                          const PatchPeaks& peaks, int n);
// `fields` from uniquenessFields(patch, peaks, solver, maps.u.n1) or uniquenessFieldsViaProxy
// (same n); may be empty when boundCertainlyHolds, and ignored when the diagonals of the maps
// satisfy the bound.
// Maps read on a proxy carry the proxy's diagonals. Where the longer one lies within `band`
// (relative) of the injectivity bound pi / sqrt(K_max), so that the proxy's error could tip the
// bound, both are measured on the patch (two directed propagations) and written into `maps`;
// returns whether it did. solveEgg calls it before checkUniqueness, so the check decides as it
// would with maps on the patch (and as the standalone check after smoothing does).
bool measureDiagonalsNearTheBound(PatchDistanceMaps& maps, const Patch& patch,
                                  const geodesic::DistanceSolver& solver, const PatchPeaks& peaks,
                                  double band = 0.01);
UniquenessReport checkUniqueness(const Patch& patch, const PatchPeaks& peaks,
                                 const UniquenessFields& fields, const PatchDistanceMaps& maps,
                                 const UniquenessOptions& options = {});

}  // namespace egg
