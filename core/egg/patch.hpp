#pragma once
// A surface patch (Sections 2.3.2, 3.3.2): four corners on the design surface joined by the four
// shortest geodesics, cut out of the surface as its own mesh whose boundary is exactly that
// geodesic quadrilateral (the boundary polylines are inserted into the mesh, so distances are
// measured inside the patch). Rejected with a clear reason (InfeasiblePatch / InvalidInput) when a
// corner is off the surface, a boundary leaves the surface or wraps around a hole or a concave
// stretch of the surface boundary, boundaries cross, or an inner angle reaches pi (criterion iv).
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace egg {

struct PatchOptions {
  // A corner may lie at most this far from the surface (metres); <= 0: automatic,
  // max(2 mean edge lengths, 1 % of the bounding-box diagonal).
  double maxCornerOffsetM = 0.0;
  // Inner angles must stay below pi - this (radians), criterion (iv).
  double angleMargin = 1e-3;
  // A side may run along the surface boundary where that is a geodesic: summed over the boundary
  // vertices it passes, it may turn round them (bend towards the boundary, as round a hole) by at
  // most this (radians). The Lilium's vertical base is a geodesic, yet its discrete angle sums
  // scatter by +-0.01 rad, and a side hugging 12 m of it turns up to 0.043 in all; a side
  // wrapping round a corner or a hole turns by far more.
  double boundaryWrapToleranceRad = 0.06;
  // Inserted points closer than this fraction of their edge to an edge end are merged with it.
  double mergeFraction = 1e-6;
  void validate() const;  // throws InvalidInput naming the field
};

struct Patch {
  TriMesh mesh;                            // the patch alone; its boundary is the geodesic quad
  std::array<Eigen::Vector3d, 4> corners;  // corner positions (on the surface)
  std::array<int, 4> cornerVertices{};     // corner vertex ids in `mesh`
  std::array<std::vector<int>, 4> sides;  // boundary vertex chain of side k, corner k -> corner k+1
  std::array<std::vector<double>, 4>
      sideArcLength;                    // cumulative length along side k at its chain vertices
  std::array<double, 4> sideLengths{};  // geodesic side lengths (metres)
  std::array<double, 4> innerAngles{};  // inner angle at each corner, measured in `mesh` (radians)
  std::array<double, 4>
      cornerOffsets{};   // how far each requested corner was moved onto the surface
  double area = 0.0;     // m^2
  int propagations = 0;  // geodesic propagations on the surface (one per side)
  double seconds = 0.0;
};

// Builds the patch. Corners are taken in order around the quad.
Patch makePatch(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& corners,
                const PatchOptions& options = {});

// Recomputes inner angles and area after the patch mesh moved (smoothing keeps the boundary).
void refreshPatchGeometry(Patch& patch);

// The point at arc length `s` along side k (clamped), as a surface point of the patch mesh lying
// on the boundary edge there, and its position.
SurfacePoint sidePoint(const Patch& patch, int side, double arcLength);

}  // namespace egg
