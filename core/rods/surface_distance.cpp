#include "core/rods/surface_distance.hpp"

#include "core/errors.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>

namespace egg::rods {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct SurfaceDistance::Tree {
  Triangles triangles;
  egg::rods::Tree tree;
};

SurfaceDistance::SurfaceDistance(const TriMesh& surface) : tree_(std::make_unique<Tree>()) {
  for (auto f : surface.faces()) {
    Point corners[3];
    int k = 0;
    for (auto v : surface.fv_range(f)) {
      if (k < 3) {
        const auto& p = surface.point(v);
        corners[k] = Point(p[0], p[1], p[2]);
      }
      ++k;
    }
    if (k == 3 && !Kernel::Triangle_3(corners[0], corners[1], corners[2]).is_degenerate()) {
      tree_->triangles.emplace_back(corners[0], corners[1], corners[2]);
    }
  }
  if (tree_->triangles.empty())
    throw InvalidInput("SurfaceDistance: the surface has no (non-degenerate) triangles");
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;
SurfaceDistance::SurfaceDistance(SurfaceDistance&&) noexcept = default;
SurfaceDistance& SurfaceDistance::operator=(SurfaceDistance&&) noexcept = default;

Eigen::Vector3d SurfaceDistance::closestPoint(const Eigen::Vector3d& p) const {
  const Point c = tree_->tree.closest_point(Point(p.x(), p.y(), p.z()));
  return {c.x(), c.y(), c.z()};
}

double SurfaceDistance::distance(const Eigen::Vector3d& p) const {
  return (closestPoint(p) - p).norm();
}

DeviationStats measureDeviation(const std::vector<Eigen::Vector3d>& points,
                                const SurfaceDistance& surface, double scaleFactor) {
  if (!(scaleFactor > 0.0)) throw InvalidInput("measureDeviation: scaleFactor must be > 0");
  DeviationStats stats;
  double sum = 0.0;
  for (const auto& p : points) {
    const double d = surface.distance(p);
    sum += d * d;
    stats.maxM = std::max(stats.maxM, d);
  }
  stats.points = static_cast<int>(points.size());
  stats.rmseM = points.empty() ? 0.0 : std::sqrt(sum / points.size());
  stats.nrmse = stats.rmseM / scaleFactor;
  return stats;
}

}  // namespace egg::rods
