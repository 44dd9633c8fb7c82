#pragma once
// Exact distance from points to a triangle mesh (the design surface), for the error measures of
// Sections 2.6.2 and 3.5.2. CGAL's AABB tree lives in surface_distance.cpp only.
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace egg::rods {

class SurfaceDistance {
 public:
  explicit SurfaceDistance(const TriMesh& surface);  // throws InvalidInput for a mesh without faces
  ~SurfaceDistance();
  SurfaceDistance(SurfaceDistance&&) noexcept;
  SurfaceDistance& operator=(SurfaceDistance&&) noexcept;

  // Closest point of the surface (exact point-to-triangle) and the distance to it, metres.
  Eigen::Vector3d closestPoint(const Eigen::Vector3d& p) const;
  double distance(const Eigen::Vector3d& p) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

// Root mean square, maximum and normalised RMS (RMSE / scale factor f, Section 3.5.2) of the
// distances of points to the surface.
struct DeviationStats {
  int points = 0;
  double rmseM = 0.0;
  double maxM = 0.0;
  double nrmse = 0.0;
};

DeviationStats measureDeviation(const std::vector<Eigen::Vector3d>& points,
                                const SurfaceDistance& surface, double scaleFactor = 1.0);

}  // namespace egg::rods
