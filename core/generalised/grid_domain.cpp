// The precomputed patch of a generalised grid (Sections 4.4-4.5): see grid_domain.hpp.
#include "core/generalised/grid_domain.hpp"

#include "core/errors.hpp"
#include "core/generalised/effort.hpp"
#include "core/timing.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

namespace egg::generalised {
namespace {

long long domainPairKey(int a, int b, int n) {
  return static_cast<long long>(std::min(a, b)) * n + std::max(a, b);
}

}  // namespace

Eigen::Vector3d memberTangentAt(const MemberGeometry& member, double arcLengthM) {
  const auto& arc = member.arcLengthM;
  size_t i = std::upper_bound(arc.begin(), arc.end(), arcLengthM) - arc.begin();
  i = std::clamp<size_t>(i, 1, arc.size() - 1);
  return (member.positions[i] - member.positions[i - 1]).normalized();
}

double crossingAngle(const MemberGeometry& g, double sG, const MemberGeometry& h, double sH) {
  return std::acos(std::min(1.0, std::abs(memberTangentAt(g, sG).dot(memberTangentAt(h, sH)))));
}

void GridDomainOptions::validate() const {
  if (!(solver.saddleAngleTolerance >= 0.0))
    throw InvalidInput("GridDomainOptions.solver.saddleAngleTolerance must be >= 0");
}

GridDomain::~GridDomain() = default;

GridDomain::GridDomain(const TriMesh& mesh, const GridDomainOptions& options) : mesh_(mesh) {
  options.validate();
  const Stopwatch clock;
  const auto loops = geodesic::boundaryLoops(mesh_);
  if (loops.size() != 1) {
    throw InvalidInput(
        "generalised grid: the patch must be a topological disk with one boundary "
        "loop, but the mesh has " +
        std::to_string(loops.size()) +
        " (split a surface with holes into disks, "
        "thesis Section 4.9.1)");
  }
  loop_ = loops.front();
  if (loop_.size() < 8) {
    throw InvalidInput("generalised grid: the boundary has " + std::to_string(loop_.size()) +
                       " vertices; at least 8 are needed to place members");
  }
  const int n = sampleCount();
  arcLength_.assign(n, 0.0);
  for (int i = 1; i <= n; ++i) {
    const double step = (position(i % n) - position(i - 1)).norm();
    if (i < n)
      arcLength_[i] = arcLength_[i - 1] + step;
    else
      loopLength_ = arcLength_[n - 1] + step;
  }
  solver_ = std::make_unique<geodesic::DistanceSolver>(mesh_, options.solver);
  meanEdge_ = solver_->meanEdgeLength();
  std::vector<SurfacePoint> sources;
  for (int v : loop_) sources.push_back(geodesic::vertexPoint(mesh_, v));
  auto fields = solver_->distances(sources);
  fields_.resize(n);
  distanceMap_.resize(n, n);
  for (int a = 0; a < n; ++a) {
    fields_[a] = std::move(fields[a].vertexDistances);
    for (int b = 0; b < n; ++b) distanceMap_(a, b) = fields_[a][loop_[b]];
  }
  // The exact distance is symmetric; the two propagations agree to rounding only.
  distanceMap_ = (0.5 * (distanceMap_ + distanceMap_.transpose())).eval();
  bendsInward_ = geodesic::boundaryBendsInward(mesh_, loop_);
  for (int i = 0; i < n; ++i) {
    if (bendsInward_[i]) reflexSamples_.push_back(i);
  }
  geodesic::BoundaryConnectionOptions connectionOptions;
  // Exact distances agree to rounding; the engine's default mode is within ~1e-5 relative.
  tolerance_ = (options.solver.saddleAngleTolerance > 0.0 ? 1e-5 : 1e-9) * loopLength_;
  connectionOptions.tolerance = tolerance_;
  connections_ = geodesic::findBoundaryConnections(distanceMap_, arcLength_, loopLength_,
                                                   bendsInward_, connectionOptions);
  curvature_ = computeCurvature(mesh_);
  double weighted = 0.0, area = 0.0;
  // Over every vertex, the boundary's too: members sample kappa_n there as well.
  for (int v = 0; v < static_cast<int>(mesh_.n_vertices()); ++v) {
    const double k1 = curvature_.kappaMax[v], k2 = curvature_.kappaMin[v];
    weighted += curvature_.mixedArea[v] * 0.5 * (k1 * k1 + k2 * k2);
    area += curvature_.mixedArea[v];
  }
  kappaScale2_ = area > 0.0 ? weighted / area : 0.0;
  // Least-squares plane of the vertices: the frame in which layouts are drawn.
  Eigen::MatrixXd points(3, mesh_.n_vertices());
  for (auto v : mesh_.vertices()) points.col(v.idx()) = toEigen(mesh_.point(v));
  origin_ = points.rowwise().mean();
  const Eigen::MatrixXd centred = points.colwise() - origin_;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred * centred.transpose());
  axes_.col(0) = eigen.eigenvectors().col(2);
  axes_.col(1) = eigen.eigenvectors().col(1);
  // Keep the frame right-handed with the mesh's mean normal, so "left" of a member is the same
  // side whichever way the eigen solver turned its vectors.
  Eigen::Vector3d meanNormal = Eigen::Vector3d::Zero();
  for (const auto& normal : curvature_.normals) meanNormal += normal;
  if (axes_.col(0).cross(axes_.col(1)).dot(meanNormal) < 0.0) axes_.col(1) = -axes_.col(1);
  for (int i = 0; i < n; ++i) projected_.push_back(axes_.transpose() * (position(i) - origin_));
  precomputeSeconds_ = clock.seconds();
}

Eigen::Vector3d GridDomain::position(int sample) const {
  return toEigen(mesh_.point(TriMesh::VertexHandle(loop_.at(sample))));
}

std::vector<int> GridDomain::contacts(int a, int b) const {
  std::vector<int> result;
  if (!connections_.invalid(a, b)) return result;
  for (int t : reflexSamples_) {
    if (t == a || t == b) continue;
    if (distanceMap_(a, t) + distanceMap_(t, b) - distanceMap_(a, b) < tolerance_)
      result.push_back(t);
  }
  std::sort(result.begin(), result.end(),
            [&](int x, int y) { return distanceMap_(a, x) < distanceMap_(a, y); });
  return result;
}

MemberGeometry GridDomain::traceMember(int a, int b) const {
  if (a == b || a < 0 || b < 0 || a >= sampleCount() || b >= sampleCount()) {
    throw InvalidInput("generalised grid: a member needs two different boundary samples (got " +
                       std::to_string(a) + ", " + std::to_string(b) + ")");
  }
  MemberGeometry m;
  m.lengthM = distanceMap_(a, b);
  const auto path =
      solver_->path(geodesic::vertexPoint(mesh_, loop_[a]), geodesic::vertexPoint(mesh_, loop_[b]));
  // Consecutive points closer than rounding (a path through a vertex) would give no tangent.
  for (size_t i = 0; i < path.positions.size(); ++i) {
    if (!m.positions.empty() && (path.positions[i] - m.positions.back()).norm() < 1e-12) continue;
    m.positions.push_back(path.positions[i]);
    m.points.push_back(path.points[i]);
  }
  if (m.positions.size() < 2) {
    throw InvalidInput("generalised grid: samples " + std::to_string(a) + " and " +
                       std::to_string(b) + " are not connected on the surface");
  }
  m.arcLengthM.assign(m.positions.size(), 0.0);
  for (size_t i = 1; i < m.positions.size(); ++i)
    m.arcLengthM[i] = m.arcLengthM[i - 1] + (m.positions[i] - m.positions[i - 1]).norm();
  const auto tangents = memberTangents(m.positions);
  for (size_t i = 0; i < m.positions.size(); ++i)
    m.kappaN.push_back(normalCurvatureAt(mesh_, curvature_, m.points[i], tangents[i]));
  m.effort = memberEffort(m.positions, m.kappaN);
  return m;
}

const MemberGeometry& GridDomain::member(int a, int b) const {
  if (a == b || a < 0 || b < 0 || a >= sampleCount() || b >= sampleCount()) {
    throw InvalidInput("generalised grid: a member needs two different boundary samples of 0.." +
                       std::to_string(sampleCount() - 1) + " (got " + std::to_string(a) + ", " +
                       std::to_string(b) + ")");
  }
  const long long key = domainPairKey(a, b, sampleCount());
  {
    std::lock_guard<std::mutex> lock(cacheMutex_);
    const auto it = cache_.find(key);
    if (it != cache_.end() && a < b) return *it->second;
  }
  // The cache holds each member from its lower sample; the other direction is stored separately
  // (reversed), so that references stay valid.
  const long long directed = a < b ? key : -key - 1;
  {
    std::lock_guard<std::mutex> lock(cacheMutex_);
    const auto it = cache_.find(directed);
    if (it != cache_.end()) return *it->second;
  }
  auto geometry = std::make_unique<MemberGeometry>();
  if (a < b) {
    *geometry = traceMember(a, b);
  } else {
    *geometry = member(b, a);
    std::reverse(geometry->positions.begin(), geometry->positions.end());
    std::reverse(geometry->points.begin(), geometry->points.end());
    std::reverse(geometry->kappaN.begin(), geometry->kappaN.end());
    const double total = geometry->arcLengthM.back();
    std::reverse(geometry->arcLengthM.begin(), geometry->arcLengthM.end());
    for (double& s : geometry->arcLengthM) s = total - s;
  }
  std::lock_guard<std::mutex> lock(cacheMutex_);
  auto& slot = cache_[directed];
  if (!slot) slot = std::move(geometry);
  return *slot;
}

int GridDomain::tracedMemberCount() const {
  std::lock_guard<std::mutex> lock(cacheMutex_);
  int count = 0;
  for (const auto& [key, geometry] : cache_) count += key >= 0 ? 1 : 0;
  return count;
}

void GridDomain::prepareMembers(const std::vector<std::pair<int, int>>& pairs) const {
  std::vector<std::pair<int, int>> missing;
  {
    std::lock_guard<std::mutex> lock(cacheMutex_);
    for (auto [a, b] : pairs) {
      if (!cache_.count(domainPairKey(a, b, sampleCount())))
        missing.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(missing.begin(), missing.end());
  missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
  tbb::parallel_for(size_t(0), missing.size(),
                    [&](size_t i) { member(missing[i].first, missing[i].second); });
}

}  // namespace egg::generalised
