#pragma once
// Supports (Section 3.5.3): a support is a point and a plane, the connection's position and the
// tangent plane of the surface there. Each becomes a block standing on the ground plane whose top
// is the inclined contact face through the point, with a bolt hole along the normal: a closed solid
// for 3D printing, or the formwork of a cast support (Figure 3.19).
#include "fabrication/options.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace egg::fabrication {

struct Support {
  std::string id;            // "S<nnn>"
  std::string connectionId;  // the connection it holds
  int patchId = 0;
  int connection = 0;  // index into the grid's connections; -1: a generalised member end
  std::string
      reason;  // "anchor: corner", "anchor: boundary curvature extremum", "boundary connection"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // metres
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit, pointing up
  double inclinationDeg = 0.0;  // angle of the contact plane to the horizontal
  double directionDeg = 0.0;    // azimuth (from +x towards +y) the contact plane falls towards
  double heightM = 0.0;         // the point above the ground plane
  // A contact plane steeper than 80 degrees (a near-vertical wall, as at the Lilium's base) cannot
  // sit on a block: it needs a bracket fixed to the wall, which is listed but not drawn.
  bool block = true;
  double blockMm = 0.0;        // footprint side of its block (fabricate(); 0 for a bracket)
  double belowGroundMm = 0.0;  // how far the block reaches below the ground (supportSolid's drop)
};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
};

// Supports at the anchors of every patch that lie on one of its free sides (and, with
// supports_at_boundary_connections, at every connection on a free side), sorted by patch and
// connection, one per point (within 1 mm) where patches meet, with the ground plane of the options
// (or 0.1 m below the lowest). A support whose plane is steeper than 80° is a bracket (block =
// false). innerAnchors: how many anchors were left out because they lie on shared sides only.
std::vector<Support> planSupports(const std::vector<FabricationPatch>& patches,
                                  const FabricationOptions& options,
                                  double* groundHeightM = nullptr, int* innerAnchors = nullptr);

// The block of one support in millimetres, in a frame with the point above the origin and z = 0 at
// the bottom face: a square footprint of `blockMm`, the top face on the contact plane, a blind bolt
// hole of `holeDiameterMm` along the normal, `holeDepthMm` deep. Raises the bottom below the ground
// where the contact plane would cut it (reported by bottomDropMm). A closed 2-manifold.
TriangleMesh supportSolid(const Support& support, double blockMm, double holeDiameterMm,
                          double holeDepthMm, double* bottomDropMm = nullptr);

// Binary STL of a mesh (facet normals from the winding).
std::string toBinaryStl(const TriangleMesh& mesh, const std::string& header);

// The supports table: id, connection, reason, x_m, y_m, z_m, nx, ny, nz, inclination_deg,
// direction_deg, height_m, kind (block | bracket), block_mm (footprint side; empty for a bracket),
// below_ground_mm (how far the block reaches below the ground; empty for a bracket).
std::string supportsCsv(const std::vector<Support>& supports);

}  // namespace egg::fabrication
