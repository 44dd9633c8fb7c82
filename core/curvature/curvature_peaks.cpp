#include "core/curvature/curvature_peaks.hpp"

#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace egg {
namespace {

// Vertices within Euclidean distance `radius` of v, reached through vertices that are themselves
// within the radius (a graph walk, so the far side of a thin fold is not included).
void ball(const TriMesh& mesh, int v, double radius, std::vector<int>& stamp,
          std::vector<int>& out) {
  out.clear();
  out.push_back(v);
  stamp[v] = v;
  const Eigen::Vector3d centre = toEigen(mesh.point(TriMesh::VertexHandle(v)));
  const double r2 = radius * radius;
  for (size_t i = 0; i < out.size(); ++i)
    for (auto w : mesh.vv_range(TriMesh::VertexHandle(out[i]))) {
      if (stamp[w.idx()] == v) continue;
      stamp[w.idx()] = v;
      if ((toEigen(mesh.point(w)) - centre).squaredNorm() <= r2) out.push_back(w.idx());
    }
}

}  // namespace

void PeakOptions::validate() const {
  auto fail = [](const std::string& field, double value, const std::string& rule) {
    std::ostringstream s;
    s << "PeakOptions." << field << " " << rule << ", got " << value;
    throw InvalidInput(s.str());
  };
  if (!std::isfinite(minGaussian)) fail("min_gaussian", minGaussian, "must be finite");
  if (!(smoothingRadiusM >= 0.0 && std::isfinite(smoothingRadiusM)))
    fail("smoothing_radius_m", smoothingRadiusM, "must be >= 0 (0 = automatic)");
  if (!(separationM >= 0.0 && std::isfinite(separationM)))
    fail("separation_m", separationM, "must be >= 0 (0 = automatic)");
}

Eigen::VectorXd averageOverBall(const TriMesh& mesh, const Eigen::VectorXd& field,
                                const Eigen::VectorXd& vertexArea, double radiusM) {
  const int n = static_cast<int>(mesh.n_vertices());
  if (field.size() != n || vertexArea.size() != n)
    throw InvalidInput("averageOverBall: field and area must have one value per vertex (" +
                       std::to_string(n) + ")");
  Eigen::VectorXd averaged(n);
  std::vector<int> stamp(n, -1), members;
  for (int v = 0; v < n; ++v) {
    ball(mesh, v, radiusM, stamp, members);
    // Smooth compact kernel (1 - d^2/r^2)^2: a plain box average jumps whenever a vertex enters or
    // leaves the ball, which on a regular grid moves the maximum off the apex.
    const Eigen::Vector3d centre = toEigen(mesh.point(TriMesh::VertexHandle(v)));
    double weighted = 0.0, area = 0.0;
    for (int w : members) {
      const double q = (toEigen(mesh.point(TriMesh::VertexHandle(w))) - centre).squaredNorm() /
                       (radiusM * radiusM);
      const double weight = vertexArea(w) * (1.0 - q) * (1.0 - q);
      weighted += weight * field(w), area += weight;
    }
    averaged(v) = area > 0.0 ? weighted / area : field(v);
  }
  return averaged;
}

std::vector<CurvaturePeak> findGaussianPeaks(const TriMesh& mesh, const Eigen::VectorXd& gaussian,
                                             const Eigen::VectorXd& vertexArea,
                                             const PeakOptions& options) {
  options.validate();
  const int n = static_cast<int>(mesh.n_vertices());
  if (gaussian.size() != n)
    throw InvalidInput("findGaussianPeaks: gaussian has " + std::to_string(gaussian.size()) +
                       " values for " + std::to_string(n) + " vertices");
  if (n == 0) return {};
  const double radius =
      options.smoothingRadiusM > 0.0 ? options.smoothingRadiusM : 2.0 * meanEdgeLength(mesh);
  const double separation = options.separationM > 0.0 ? options.separationM : radius;
  const Eigen::VectorXd averaged = averageOverBall(mesh, gaussian, vertexArea, radius);

  std::vector<CurvaturePeak> peaks;
  std::vector<int> stamp(n, -1), stampNearby(n, -1), members;
  for (int v = 0; v < n; ++v) {
    if (!(averaged(v) > options.minGaussian)) continue;
    const auto vh = TriMesh::VertexHandle(v);
    const bool boundary = mesh.is_boundary(vh);
    if (boundary && !options.includeBoundary) continue;
    ball(mesh, v, separation, stamp, members);
    // Strict maximum, ties broken by the lower index, so a plateau yields exactly one peak.
    const bool isMax = std::all_of(members.begin(), members.end(), [&](int w) {
      return w == v || averaged(w) < averaged(v) || (averaged(w) == averaged(v) && w > v);
    });
    if (!isMax) continue;
    CurvaturePeak peak;
    peak.vertex = v;
    peak.position = toEigen(mesh.point(vh));
    peak.gaussianAveraged = averaged(v);
    peak.gaussianVertex = gaussian(v);
    ball(mesh, v, radius, stampNearby, members);
    peak.gaussianMaxNearby = gaussian(v);
    for (int w : members) peak.gaussianMaxNearby = std::max(peak.gaussianMaxNearby, gaussian(w));
    peak.injectivityBoundM = injectivityRadiusBound(peak.gaussianMaxNearby);
    peak.onBoundary = boundary;
    peaks.push_back(peak);
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const auto& a, const auto& b) { return a.gaussianAveraged > b.gaussianAveraged; });
  return peaks;
}

}  // namespace egg
