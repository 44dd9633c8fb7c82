#pragma once
// Shortest connections that run along a non-convex boundary (Section 4.5.3, 4.5.4).
//
// On a surface with a non-convex boundary the shortest connection between two boundary points
// may hug the boundary: it is then not a geodesic (non-zero geodesic curvature) and cannot be a
// lamella. Criterion (4.3): the surface distance equals the distance along the boundary. On the
// mesh this is Eq. (4.6), D - B < eps, evaluated on a distance map D between boundary samples.
// The non-convex segments are the index ranges [t1, t2] of pairs that fulfil it; connections
// that run partly along such a segment are found with Eq. (4.4)-(4.5): d(p_x,p_y) - d(p_Theta,p_y)
// constant in y.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg::geodesic {

// The boundary loops of a mesh as ordered vertex lists (each loop once, consistent orientation).
std::vector<std::vector<int>> boundaryLoops(const TriMesh& mesh);

struct BoundaryConnectionOptions {
  // Eq. (4.6) tolerance: D - B below this is "along the boundary" (metres). <= 0: automatic,
  // 1e-9 times the loop length (distances are exact, so only rounding is tolerated).
  double tolerance = 0.0;
  // Eq. (4.5) tolerance on the discrete derivative of d_g along y, relative to the sample spacing.
  double derivativeTolerance = 1e-6;

  void validate() const;  // throws InvalidInput naming the field
};

struct BoundaryConnections {
  // alongBoundary(x, y): Eq. (4.6) holds for samples x != y (the connection runs entirely along
  // the boundary).
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> alongBoundary;
  // Non-convex boundary segments as inclusive sample index ranges [first, last] along the loop.
  std::vector<std::pair<int, int>> nonConvexSegments;
  // invalid(x, y): the shortest connection from x to y runs at least partly along a non-convex
  // segment (Eq. 4.4-4.5, grown from the segments), so it is not a geodesic.
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> invalid;
};

// distanceMap(x, y) = surface distance between boundary samples x and y of one closed loop, in loop
// order; arcLength[x] = cumulative boundary length at sample x (arcLength[0] = 0); loopLength =
// total length of the closed loop. Throws InvalidInput on size mismatches.
BoundaryConnections findBoundaryConnections(const Eigen::MatrixXd& distanceMap,
                                            const std::vector<double>& arcLength, double loopLength,
                                            const BoundaryConnectionOptions& options = {});

}  // namespace egg::geodesic
