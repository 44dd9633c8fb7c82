#pragma once
// Intersection of two shortest geodesics from their four endpoint distance fields (Section 4.5.2).
//
// For a point p on the surface, d(A,p) + d(p,B) >= d(A,B) with equality exactly on the shortest
// geodesic AB (Eq. 4.1), and likewise for CD (Eq. 4.2). The sum of the four fields therefore
// attains d(A,B) + d(C,D) only where both geodesics pass: at their intersection. We take the
// vertex minimising the summed field and refine it to second order (the thesis' paraboloid fit
// over the vertex ring in local (u,v) coordinates). Near a geodesic the excess
// d(A,p) + d(p,B) - d(A,B) grows quadratically with the offset, so the fit is well posed.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg::geodesic {

struct GeodesicIntersectionOptions {
  // The intersection is accepted when the summed field's excess over d(A,B) + d(C,D) at the
  // refined point is at most this (metres). <= 0: automatic, 0.5 * (mean edge length)^2 /
  // min(d(A,B), d(C,D)) * 4, the largest excess a vertex within one edge of both geodesics has.
  double maxExcess = 0.0;
  // Rings of neighbours of the first paraboloid fit (1 = the vertex ring of the thesis). If that
  // fit is not convex or its minimum leaves the rings, it is widened by one ring, at most twice.
  int fitRings = 1;

  void validate() const;  // throws InvalidInput naming the field
};

struct GeodesicIntersection {
  bool found = false;  // false: the geodesics do not cross (excess above maxExcess)
  SurfacePoint point;  // refined intersection
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int nearestVertex = -1;      // vertex minimising the summed field
  double vertexExcess = 0.0;   // summed field minus d(A,B) + d(C,D) at that vertex (metres)
  double refinedExcess = 0.0;  // same, predicted by the fitted paraboloid at `point`
};

// dA..dD: vertex distance fields from the endpoints A, B (first geodesic) and C, D (second), e.g.
// DistanceField::vertexDistances. lengthAB = d(A,B), lengthCD = d(C,D) (e.g. target distances).
// Throws InvalidInput when the field sizes do not match the mesh.
GeodesicIntersection intersectGeodesics(const TriMesh& mesh, const std::vector<double>& dA,
                                        const std::vector<double>& dB,
                                        const std::vector<double>& dC,
                                        const std::vector<double>& dD, double lengthAB,
                                        double lengthCD,
                                        const GeodesicIntersectionOptions& options = {});

// Exact intersection of two traced polylines (e.g. DistanceSolver::path results): the first
// crossing of the two polylines, as a 3D point and the arc lengths along each. Used to validate
// the field-based intersection and by callers that already traced the members.
struct PolylineCrossing {
  bool found = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double arcLengthFirst = 0.0;
  double arcLengthSecond = 0.0;
};
PolylineCrossing intersectPolylines(const std::vector<Eigen::Vector3d>& first,
                                    const std::vector<Eigen::Vector3d>& second, double tolerance);

}  // namespace egg::geodesic
