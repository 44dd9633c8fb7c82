// The only CGAL translation unit of the samples: constrained Delaunay refinement of the parameter
// domain. The size criterion is evaluated on the lifted (3D) triangle, so steep parts of a height
// field get a finer footprint mesh; the remesher then equalises edges in 3D.
#include "samples/generators/domain_triangulation.hpp"

#include "core/errors.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_2/Face_badness.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <map>
#include <queue>
#include <string>

namespace egg::samples::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Which input point a vertex is; vertices the refinement inserts keep the default -1.
struct InputTag {
  int index = -1;
};
using VertexBase0 = CGAL::Triangulation_vertex_base_with_info_2<InputTag, Kernel>;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel, VertexBase0>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Point = Kernel::Point_2;

// Delaunay_mesh_size_criteria_2 with the edge lengths taken in 3D: a face is imperatively bad when
// its longest lifted edge exceeds the bound, and bad when its smallest domain angle is too small.
class LiftedSizeCriteria {
 public:
  using Face_handle = Cdt::Face_handle;
  using Lift = std::function<Vec3(const Vec2&)>;

  struct Quality : public std::pair<double, double> {  // (squared sine, size / bound squared)
    Quality() = default;
    Quality(double sine, double size) : std::pair<double, double>(sine, size) {}
    double sine() const { return first; }
    double size() const { return second; }
    // q1 < q2: q1 is refined first (same order as CGAL's size criteria).
    bool operator<(const Quality& q) const {
      if (size() > 1) return q.size() > 1 ? size() > q.size() : true;
      if (q.size() > 1) return false;
      return sine() < q.sine();
    }
  };

  class Is_bad {
   public:
    Is_bad(double aspectBound, double maxEdge, const Lift* lift)
        : aspectBound_(aspectBound), maxEdge2_(maxEdge * maxEdge), lift_(lift) {}

    CGAL::Mesh_2::Face_badness operator()(const Quality q) const {
      if (q.size() > 1) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      return q.sine() < aspectBound_ ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

    CGAL::Mesh_2::Face_badness operator()(const Face_handle& face, Quality& q) const {
      Vec2 p[3];
      Vec3 lifted[3];
      for (int i = 0; i < 3; ++i) {
        p[i] = {face->vertex(i)->point().x(), face->vertex(i)->point().y()};
        lifted[i] = (*lift_)(p[i]);
      }
      double longest3d = 0.0;
      double domain2[3];
      for (int i = 0; i < 3; ++i) {
        longest3d = std::max(longest3d, (lifted[(i + 1) % 3] - lifted[(i + 2) % 3]).squaredNorm());
        domain2[i] = (p[(i + 1) % 3] - p[(i + 2) % 3]).squaredNorm();
      }
      q.second = longest3d / maxEdge2_;
      if (q.size() > 1) {
        q.first = 1;
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      std::sort(domain2, domain2 + 3);
      const Vec2 e1 = p[1] - p[0], e2 = p[2] - p[0];
      const double area2 = e1.x() * e2.y() - e1.y() * e2.x();
      // Squared sine of the smallest angle = (2 area)^2 / (product of the two longer edges^2).
      q.first = area2 * area2 / (domain2[2] * domain2[1]);
      return q.sine() < aspectBound_ ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

   private:
    double aspectBound_;
    double maxEdge2_;
    const Lift* lift_;
  };

  LiftedSizeCriteria(double aspectBound, double maxEdge, const Lift* lift)
      : aspectBound_(aspectBound), maxEdge_(maxEdge), lift_(lift) {}
  Is_bad is_bad_object() const { return Is_bad(aspectBound_, maxEdge_, lift_); }

 private:
  double aspectBound_;
  double maxEdge_;
  const Lift* lift_;
};

// Marks faces inside the domain by nesting parity: crossing a constrained edge toggles in/out.
void markDomain(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->set_in_domain(false);
  std::map<Cdt::Face_handle, int> level;
  std::queue<Cdt::Face_handle> frontier;
  frontier.push(cdt.infinite_face());
  level[cdt.infinite_face()] = 0;
  // Breadth-first over levels: a face is reached first through the fewest constraints.
  std::queue<Cdt::Face_handle> nextLevel;
  int current = 0;
  while (!frontier.empty()) {
    while (!frontier.empty()) {
      const Cdt::Face_handle f = frontier.front();
      frontier.pop();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (level.count(n)) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          nextLevel.push(n);
        } else {
          level[n] = current;
          frontier.push(n);
        }
      }
    }
    ++current;
    while (!nextLevel.empty()) {
      const Cdt::Face_handle n = nextLevel.front();
      nextLevel.pop();
      if (level.count(n)) continue;
      level[n] = current;
      frontier.push(n);
    }
  }
  for (auto& [face, depth] : level) {
    if (!cdt.is_infinite(face)) face->set_in_domain(depth % 2 == 1);
  }
}

}  // namespace

DomainTriangulation triangulateDomain(const std::vector<std::vector<Vec2>>& polygons,
                                      const std::vector<Vec2>& requiredPoints,
                                      const std::function<Vec3(const Vec2&)>& lift,
                                      double maxEdge3d, double aspectBound,
                                      std::size_t maxVertices) {
  Cdt cdt;
  int index = 0;
  for (const auto& polygon : polygons) {
    std::vector<Cdt::Vertex_handle> handles;
    for (const Vec2& p : polygon) {
      handles.push_back(cdt.insert(Point(p.x(), p.y())));
      handles.back()->info().index = index++;
    }
    for (size_t i = 0; i < handles.size(); ++i) {
      cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
    }
  }
  for (const Vec2& p : requiredPoints) {
    auto handle = cdt.insert(Point(p.x(), p.y()));
    handle->info().index = index++;
  }
  markDomain(cdt);

  LiftedSizeCriteria criteria(aspectBound, maxEdge3d, &lift);
  CGAL::Delaunay_mesher_2<Cdt, LiftedSizeCriteria> mesher(cdt, criteria);
  mesher.init(true);
  // refine_mesh() step by step, so a hopeless domain fails fast instead of exhausting memory.
  for (std::size_t step = 0; !mesher.is_refinement_done(); ++step) {
    mesher.try_one_step_refine_mesh();
    if (step % 1024 == 0 && cdt.number_of_vertices() > maxVertices) {
      throw InvalidInput("Delaunay refinement of the parameter domain exceeded " +
                         std::to_string(maxVertices) +
                         " vertices (the domain is far thinner than the edge length)");
    }
  }

  DomainTriangulation result;
  std::map<Cdt::Vertex_handle, int> outputIndex;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    std::array<int, 3> triangle{};
    for (int i = 0; i < 3; ++i) {
      const Cdt::Vertex_handle v = f->vertex(i);
      auto [it, inserted] = outputIndex.try_emplace(v, int(result.points.size()));
      if (inserted) {
        result.points.emplace_back(v->point().x(), v->point().y());
        result.inputIndex.push_back(v->info().index);
      }
      triangle[i] = it->second;
    }
    result.triangles.push_back(triangle);
  }
  return result;
}

}  // namespace egg::samples::detail
