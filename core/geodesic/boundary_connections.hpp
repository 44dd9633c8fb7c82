#pragma once
// Shortest connections that run along a non-convex boundary (Section 4.5.3, 4.5.4).
//
// On a surface with a non-convex boundary the shortest connection between two boundary points
// may hug the boundary: it is then not a geodesic (non-zero geodesic curvature) and cannot be a
// lamella. Criterion (4.3): the surface distance equals the distance along the boundary. On the
// mesh this is Eq. (4.6), |D - B| < eps, evaluated on a distance map D between boundary samples.
// The non-convex segments are the index ranges [t1, t2] of pairs that fulfil it; connections
// that run partly along such a segment (Eq. 4.4-4.5) are those passing through one of the
// segment's inward-bending boundary vertices t: d(x,t) + d(t,y) = d(x,y) (see the .cpp for why
// this replaces the derivative test on exact distances).
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg::geodesic {

// The boundary loops of a mesh as ordered vertex lists (each loop once, consistent orientation).
std::vector<std::vector<int>> boundaryLoops(const TriMesh& mesh);

struct BoundaryConnectionOptions {
  // Eq. (4.6) tolerance: D - B below this is "along the boundary", and d(x,t) + d(t,y) - d(x,y)
  // below it is "through t" (metres). <= 0: automatic, 1e-9 times the loop length, right for
  // distances of the engine's exact mode; raise it to 1e-5 x loop length for its default, which
  // skips near-flat saddles (DistanceSolverOptions::saddleAngleTolerance, errors up to ~1e-5).
  double tolerance = 0.0;

  void validate() const;  // throws InvalidInput naming the field
};

struct BoundaryConnections {
  // alongBoundary(x, y): Eq. (4.6) holds for samples x != y (the connection runs entirely along
  // the boundary).
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> alongBoundary;
  // Non-convex boundary segments as inclusive sample index ranges [first, last] along the loop.
  std::vector<std::pair<int, int>> nonConvexSegments;
  // invalid(x, y): the shortest connection from x to y runs at least partly along a non-convex
  // segment or touches it (Eq. 4.4-4.5), so it is not a geodesic. Symmetric.
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> invalid;
};

// distanceMap(x, y) = surface distance between boundary samples x and y of one closed loop, in loop
// order; arcLength[x] = cumulative boundary length at sample x (arcLength[0] = 0); loopLength =
// total length of the closed loop. bendsInward[x] != 0 where the boundary turns towards the
// surface at sample x (a reflex turn, see boundaryBendsInward): a connection along the boundary
// counts only if it bends inwards somewhere, since along a straight stretch it is a geodesic (a
// patch side is one). Throws InvalidInput on size mismatches.
BoundaryConnections findBoundaryConnections(const Eigen::MatrixXd& distanceMap,
                                            const std::vector<double>& arcLength, double loopLength,
                                            const std::vector<char>& bendsInward,
                                            const BoundaryConnectionOptions& options = {});

// The thesis' criterion without geometry: every sample may bend (Eq. 4.6 as printed).
BoundaryConnections findBoundaryConnections(const Eigen::MatrixXd& distanceMap,
                                            const std::vector<double>& arcLength, double loopLength,
                                            const BoundaryConnectionOptions& options = {});

// For boundary vertices (e.g. a loop of boundaryLoops): 1 where the surface angle at the vertex
// exceeds pi + tolerance (radians), i.e. the boundary turns towards the surface there.
std::vector<char> boundaryBendsInward(const TriMesh& mesh, const std::vector<int>& loopVertices,
                                      double tolerance = 1e-9);

}  // namespace egg::geodesic
