#pragma once
// Procedural grids with known geometry, for tests, `egg bench sim` and `egg stress`: an exact
// geodesic grid on a cylindrical vault. Geodesics of a cylinder are straight lines of its
// development, so two families of lines at +-45 degrees in the unrolled rectangle are a notch-free
// elastic geodesic grid (docs/architecture.md "Notch-free grids"): deployed, it must reproduce the
// cylinder.
#include "core/mesh/mesh.hpp"
#include "core/rods/rod_network.hpp"

namespace egg::rods {

struct CylinderGridParameters {
  double radiusM = 5.0;        // cylinder radius; axis along y
  double halfAngleRad = 0.8;   // the vault spans -halfAngle..halfAngle around the axis
  double lengthM = 8.0;        // extent along the axis
  double spacingM = 1.0;       // perpendicular distance between members of a family
  double notchFraction = 0.2;  // notch length on each side of inner bolts, in spacings (0: none)
  CrossSection section{0.05, 0.005};
  Material material{10.0e9, 0.6e9, 500.0};
  double meshEdgeM = 0.25;  // edge length of the surface triangulation
  void validate() const;    // throws InvalidInput naming the field
};

struct SampleGrid {
  RodNetwork network;
  TriMesh surface;
};

// Members are the line segments clipped to the development, mapped onto the cylinder (guess and
// normals), family 1 in layer 0 and family 2 in layer 1; every member end on the boundary is a
// support (anchor with the surface normal), every crossing a bolt.
SampleGrid cylinderGrid(const CylinderGridParameters& parameters);

}  // namespace egg::rods
