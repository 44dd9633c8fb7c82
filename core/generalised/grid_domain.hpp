#pragma once
// What a generalised grid needs to know of its patch before any layout is tried (thesis Sections
// 4.4-4.5, t_pre of Table 4.1): the boundary loop sampled at the mesh's boundary vertices (the
// discrete dual space of Section 4.5.4, one index per vertex), the distance field of every sample,
// the distance map D between samples, the invalid regions of a non-convex boundary (Eq. 4.3-4.6)
// and the surface's principal curvatures (Section 4.6). A member is a pair of samples; everything
// that depends on one member only (its traced geodesic, its normal curvature profile, E_c of
// Eq. 4.10) is computed once per pair and kept, because the optimisation of Section 4.6.4 visits
// the same pairs again and again.
#include "core/curvature/curvature.hpp"
#include "core/geodesic/boundary_connections.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace egg::generalised {

struct GridDomainOptions {
  // Exact polyhedral distances by default: the invalid-region test compares sums of distances
  // with a tolerance of 1e-9 x the loop length (boundary_connections.hpp).
  geodesic::DistanceSolverOptions solver = geodesic::DistanceSolverOptions::exact();
  void validate() const;  // throws InvalidInput naming the field
};

// One member's geometry on the surface, from its first sample to its second.
struct MemberGeometry {
  double lengthM = 0.0;                    // d(p_x, p_y) from the distance map
  std::vector<Eigen::Vector3d> positions;  // traced shortest geodesic
  std::vector<SurfacePoint> points;
  std::vector<double> arcLengthM;  // along `positions`, 0 .. traced length
  std::vector<double> kappaN;      // normal curvature at each point along the member (1/m)
  double effort = 0.0;             // E_c of Eq. 4.10 (1/m^2)
};

// The unit direction of the traced member's segment at arc length s (clamped to the member).
Eigen::Vector3d memberTangentAt(const MemberGeometry& member, double arcLengthM);

// The acute angle (radians, [0, pi/2]) between members g and h where g is at arc length sG and h
// at sH: the crossing angle of their lamellas.
double crossingAngle(const MemberGeometry& g, double sG, const MemberGeometry& h, double sH);

class GridDomain {
 public:
  // Throws InvalidInput unless the mesh is a topological disk (exactly one boundary loop of at
  // least 8 vertices).
  explicit GridDomain(const TriMesh& mesh, const GridDomainOptions& options = {});
  ~GridDomain();

  const TriMesh& mesh() const { return mesh_; }
  int sampleCount() const { return static_cast<int>(loop_.size()); }
  int vertex(int sample) const { return loop_.at(sample); }
  Eigen::Vector3d position(int sample) const;
  double distance(int a, int b) const { return distanceMap_(a, b); }
  const std::vector<double>& field(int sample) const { return fields_.at(sample); }
  double arcLength(int sample) const { return arcLength_.at(sample); }
  double loopLengthM() const { return loopLength_; }
  const geodesic::BoundaryConnections& connections() const { return connections_; }
  const std::vector<char>& bendsInward() const { return bendsInward_; }
  const CurvatureField& curvature() const { return curvature_; }
  const geodesic::DistanceSolver& solver() const { return *solver_; }
  double meanEdgeLengthM() const { return meanEdge_; }
  double precomputeSeconds() const { return precomputeSeconds_; }
  // Squared curvature scale of the surface: the area-weighted mean of (kappa_1^2 + kappa_2^2) / 2
  // over all vertices (1/m^2); makes E_effort dimensionless in E_grid.
  double kappaScale2() const { return kappaScale2_; }

  // The plane of least squares through the mesh (its normal the direction of least spread):
  // layouts are drawn as straight lines in it (generalised_grid.hpp).
  Eigen::Vector3d planeOrigin() const { return origin_; }
  Eigen::Matrix<double, 3, 2> planeAxes() const { return axes_; }
  const std::vector<Eigen::Vector2d>& projectedBoundary() const { return projected_; }

  // The member from sample a to sample b (a != b), traced and measured on first use; thread-safe.
  // The reference stays valid for the domain's lifetime.
  const MemberGeometry& member(int a, int b) const;
  // Traces the not yet known members among `pairs` in parallel (TBB).
  void prepareMembers(const std::vector<std::pair<int, int>>& pairs) const;
  int tracedMemberCount() const;  // distinct members traced so far
  // The reflex samples of non-convex segments the shortest connection a-b passes through, ordered
  // from a to b (empty for a valid member).
  std::vector<int> contacts(int a, int b) const;

 private:
  MemberGeometry traceMember(int a, int b) const;

  TriMesh mesh_;
  std::unique_ptr<geodesic::DistanceSolver> solver_;
  std::vector<int> loop_;
  std::vector<double> arcLength_;
  double loopLength_ = 0.0;
  std::vector<std::vector<double>> fields_;
  Eigen::MatrixXd distanceMap_;
  std::vector<char> bendsInward_;
  std::vector<int> reflexSamples_;
  geodesic::BoundaryConnections connections_;
  CurvatureField curvature_;
  double meanEdge_ = 0.0;
  double precomputeSeconds_ = 0.0;
  double kappaScale2_ = 0.0;
  double tolerance_ = 0.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 2> axes_ = Eigen::Matrix<double, 3, 2>::Zero();
  std::vector<Eigen::Vector2d> projected_;
  mutable std::mutex cacheMutex_;
  mutable std::unordered_map<long long, std::unique_ptr<MemberGeometry>> cache_;
};

}  // namespace egg::generalised
