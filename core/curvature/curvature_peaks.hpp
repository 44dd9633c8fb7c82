#pragma once
// Peaks of Gaussian curvature: where the eta check of Section 2.3.3 / 3.4.1 starts ("evaluating
// [Eq. 2.1] at local peaks of Gaussian curvature K_max serves as a quick check"). The discrete K
// of a real mesh is noisy from vertex to vertex, so peaks are searched on an area-weighted average
// of K over a ball of a few edge lengths (smooth kernel): every bump gives one peak, mesh noise
// gives none.
#include "core/mesh/mesh.hpp"

#include <Eigen/Dense>
#include <vector>

namespace egg {

struct PeakOptions {
  // Only peaks whose averaged K exceeds this are reported [1/m^2].
  double minGaussian = 0.0;
  // Radius of the averaging ball [m]; 0 = twice the mean edge length.
  double smoothingRadiusM = 0.0;
  // A peak is the largest averaged K within this radius [m]; 0 = the smoothing radius.
  double separationM = 0.0;
  // Report peaks on the boundary too (a peak on the boundary is harmless for one patch, Section
  // 2.3.3, but matters when the surface is split).
  bool includeBoundary = true;

  void validate() const;  // throws InvalidInput naming the field
};

struct CurvaturePeak {
  int vertex = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double gaussianAveraged = 0.0;   // kernel-averaged K at the peak, the search criterion [1/m^2]
                                   // (biased low by O((radius / bump width)^2))
  double gaussianVertex = 0.0;     // K of the peak vertex itself [1/m^2]
  double gaussianMaxNearby = 0.0;  // largest K within the smoothing ball [1/m^2]: a conservative
                                   // (high) estimate, safe for the uniqueness check
  double injectivityBoundM = 0.0;  // pi / sqrt(gaussian_max_nearby), Eq. 2.1
  bool onBoundary = false;
};

// Average of a per-vertex field over the vertices within Euclidean distance `radiusM` reachable
// through such vertices (so the two sides of a thin fold do not mix), weighted by vertex area times
// the smooth kernel (1 - d^2 / r^2)^2.
Eigen::VectorXd averageOverBall(const TriMesh& mesh, const Eigen::VectorXd& field,
                                const Eigen::VectorXd& vertexArea, double radiusM);

// Local maxima of the ball-averaged `gaussian` field, strongest (by average) first.
std::vector<CurvaturePeak> findGaussianPeaks(const TriMesh& mesh, const Eigen::VectorXd& gaussian,
                                             const Eigen::VectorXd& vertexArea,
                                             const PeakOptions& options = {});

}  // namespace egg
