#pragma once
// Injectivity circles of a design surface (Section 3.4.1, Expression 3.1; Algorithm 2 "find p_max
// and compute r = pi / sqrt(K_max); draw a circle (p_max, r) on the surface"). Around a peak of
// Gaussian curvature K_max, two shortest geodesics from one point cannot meet again (no conjugate
// points) within r = pi / sqrt(K_max) (Eq. 2.1): a patch whose members fit inside such a circle has
// unique shortest geodesics, so Workflow 2 starts its patches from these circles, and plan.svg
// shows them.
#include "core/curvature/curvature.hpp"
#include "core/curvature/curvature_peaks.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg::geodesic {
class DistanceSolver;
}

namespace egg::patching {

struct SurfacePeakOptions {
  CurvatureOptions curvature;  // the K estimate (core/curvature)
  PeakOptions peaks;  // ball averaging of K; its min_gaussian is raised to `min_gaussian` below
  // Report only peaks with K_max above this [1/m^2]; 0 = automatic: peaks whose injectivity radius
  // pi / sqrt(K_max) is smaller than the surface's bounding-box diagonal (the others cannot
  // matter).
  double minGaussian = 0.0;
  void validate() const;  // throws InvalidInput naming the field
};

// One high-K peak of the whole surface.
struct SurfacePeak {
  int vertex = -1;  // p_max, a surface vertex
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double gaussianAveraged = 0.0;  // ball-averaged K, the strength the peaks are ordered by [1/m^2]
  double gaussianMax =
      0.0;  // largest K within the averaging ball: the conservative K_max of Eq. 3.1 [1/m^2]
  double radiusM = 0.0;  // injectivity radius pi / sqrt(gaussianMax) [m]
  bool onBoundary = false;
};

// Peaks of the ball-averaged K (findGaussianPeaks) above the threshold, with non-maximum
// suppression: a weaker peak closer (Euclidean, a lower bound of the geodesic distance) than the
// injectivity radius of a stronger kept peak lies inside its circle and is dropped. Strongest
// (by gaussianAveraged, ties by vertex index) first; deterministic for any thread count.
std::vector<SurfacePeak> findSurfacePeaks(const TriMesh& surface,
                                          const SurfacePeakOptions& options = {});

// A piece of the circle: a polyline of surface points on mesh edges, each at geodesic distance r
// from p_max. Closed loops run counter-clockwise seen from the normal side (the disc on the left).
struct CirclePolyline {
  std::vector<SurfacePoint> points;
  std::vector<Eigen::Vector3d> positions;
  bool closed = false;   // a loop (the last point connects to the first, not repeated)
  double lengthM = 0.0;  // including the closing segment of a loop
};

struct InjectivityCircle {
  int peakVertex = -1;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radiusM = 0.0;                   // r = pi / sqrt(K_max) (geodesic)
  std::vector<CirclePolyline> polylines;  // loops first, then open pieces; each by its first edge
  bool complete = false;           // the circle lies on the surface: some polyline, all closed
  bool coversSurface = false;      // every vertex is closer than r: no circle at all
  double lengthM = 0.0;            // summed polyline length
  double maxDistanceErrorM = 0.0;  // largest |d(p_max, point) - r| of the points (root finding)
  int propagations = 0;            // distance fields computed
  double seconds = 0.0;
};

// The geodesic circle of radius peak.radiusM around peak.vertex: the isoline d = r of the exact
// distance field from p_max, by marching triangles on the vertex distances (a face whose vertices
// lie on both sides holds one segment), each crossing point then moved along its edge until its own
// exact distance is r (a few batched propagations with the crossings as targets, regula falsi).
// Pieces are chained through shared edges: loops where the circle stays on the surface, open pieces
// ending on the surface boundary where it leaves it.
InjectivityCircle injectivityCircle(const TriMesh& surface, const geodesic::DistanceSolver& solver,
                                    const SurfacePeak& peak);

// All circles, in parallel over peaks (TBB); the same result for any thread count.
std::vector<InjectivityCircle> injectivityCircles(const TriMesh& surface,
                                                  const geodesic::DistanceSolver& solver,
                                                  const std::vector<SurfacePeak>& peaks);

}  // namespace egg::patching
