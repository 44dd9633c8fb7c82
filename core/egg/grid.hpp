#pragma once
// The grid of one patch (Sections 2.4.5, 2.4.6): members traced as shortest geodesics on the patch
// and as straight segments in the planar quad, their connections, notch lengths l = s - s_bar with
// sliding directions, and anchors. The result is plain data the rod simulation and the writers
// consume (grid_io.hpp).
#include "core/egg/members.hpp"
#include "core/egg/patch.hpp"
#include "core/egg/planar_quad.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace egg {

struct GridOptions {
  // Criterion (i): the end parameter x2 of an inner member is refined until the geodesic and the
  // planar segment differ in length by at most this fraction of the member length.
  double lengthTolerance = 1e-10;  // 10x tighter than the 1e-9 the tests demand
  int maxStripTraces = 4;   // traces of a member solved in their unfolded strip before the fallback
  int bracketSamples = 25;  // fallback: samples of x2 around the cladding function's guess
  int maxSecantSteps = 12;  // fallback: refinement steps after bracketing
  // Anchors (2.4.6): boundary curvature maxima at least this fraction of the side's largest.
  double anchorCurvatureFraction = 0.5;
  void validate() const;  // throws InvalidInput naming the field
};

struct GridMember {
  Family family = Family::U;
  int index = 0;                         // position in its family, 0 .. count-1
  bool boundary = false;                 // a patch side: carries no notches
  double x1 = 0.0, x2 = 0.0;             // boundary parameters
  std::vector<Eigen::Vector3d> spatial;  // polyline on the surface, start side to end side
  std::vector<Eigen::Vector3d>
      normals;  // unit surface normal at each polyline point (mesh orientation)
  Eigen::Vector2d planarStart = Eigen::Vector2d::Zero(), planarEnd = Eigen::Vector2d::Zero();
  double spatialLength = 0.0;  // metres
  double planarLength = 0.0;   // metres
  bool bracketed = false;  // matched by the fallback (bracketing with full fields), not in a strip
};

struct GridConnection {
  int memberU = 0, memberV = 0;  // indices into EggGrid::u and EggGrid::v
  Eigen::Vector3d spatial = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit surface normal at the connection
  Eigen::Vector2d planar = Eigen::Vector2d::Zero();
  double sU = 0.0, sBarU = 0.0;  // arc length along the u member: surface, plane
  double sV = 0.0, sBarV = 0.0;  // same along the v member
  double notchU = 0.0,
         notchV = 0.0;      // l = s - s_bar (metres); sign = sliding direction along the member
  bool onBoundary = false;  // one of the two members is a patch side
};

struct GridAnchor {
  int connection = 0;  // index into EggGrid::connections
  std::string reason;  // "corner" or "boundary curvature extremum"
};

struct EggGrid {
  PlanarQuad quad;
  std::vector<GridMember> u, v;
  std::vector<GridConnection> connections;  // row-major: connection (i, j) at i * v.size() + j
  std::vector<GridAnchor> anchors;
  double maxNotch = 0.0;           // largest |notch| (metres)
  double maxLengthMismatch = 0.0;  // largest |spatial - planar| / length over members (criterion i)
  int propagations = 0;            // distance fields spent on refining members
  double seconds = 0.0;
  const GridConnection& at(int i, int j) const {
    return connections[static_cast<size_t>(i) * v.size() + j];
  }
};

// Traces both families and builds connections, notches and anchors. Throws SolverFailure when an
// inner member cannot be matched in length or two inner members do not cross.
EggGrid buildGrid(const Patch& patch, const geodesic::DistanceSolver& solver,
                  const PlanarQuad& quad, const FamilyMembers& u, const FamilyMembers& v,
                  const GridOptions& options = {});

// Notches to cut: member-connection pairs whose |l| exceeds `minimumM` (each connection can hold
// one notch in each of its two members). Feeds report.json patches[].notches.
int countNotches(const EggGrid& grid, double minimumM = 1e-4);

// Intersection of two planar segments as parameters (t along the first, s along the second);
// false if they are parallel or miss each other (beyond `slack` in parameter units).
bool intersectSegments(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                       const Eigen::Vector2d& b0, const Eigen::Vector2d& b1, double& t, double& s,
                       double slack = 1e-9);

}  // namespace egg
