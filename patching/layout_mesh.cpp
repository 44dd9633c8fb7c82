// Inserting a layout's sides into the surface (see layout_mesh.hpp). The only CGAL user of
// patching/: each crossed surface face is re-triangulated in its own plane by a constrained
// Delaunay triangulation whose constraints are the face's edges (split where sides cross them)
// and the side steps inside it; shared points on a surface edge get one id, so the pieces of
// neighbouring faces fit together.
#include "patching/layout_mesh.hpp"

#include "core/errors.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <deque>
#include <map>
#include <set>
#include <unordered_map>

namespace egg::patching {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct VertexInfo {
  int id = -1;  // global vertex id; -1 for a vertex CGAL made where two constraints cross
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Triangulation = CGAL::Constrained_triangulation_plus_2<Cdt>;
using Point2 = Kernel::Point_2;

using EdgeKey = std::pair<int, int>;
EdgeKey edgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Where a surface point is, once snapped: at a vertex, on an edge, or inside a face.
struct Location {
  enum Kind { Vertex, Edge, Face } kind = Vertex;
  int vertex = -1;                                    // Vertex
  EdgeKey edge{-1, -1};                               // Edge (a < b)
  double t = 0.0;                                     // Edge: from a to b
  int face = -1;                                      // Face
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // Face
};

class Builder {
 public:
  Builder(const TriMesh& surface, double merge) : surface_(surface), merge_(merge) {
    for (auto vh : surface.vertices()) positions_.push_back(toEigen(surface.point(vh)));
  }

  Location locate(const SurfacePoint& point) const {
    const auto ids = faceVertices(surface_, point.face);
    const Eigen::Vector3d& w = point.barycentric;
    int largest = 0, smallest = 0;
    for (int i = 1; i < 3; ++i) {
      if (w[i] > w[largest]) largest = i;
      if (w[i] < w[smallest]) smallest = i;
    }
    Location loc;
    if (w[largest] >= 1.0 - merge_) {
      loc.kind = Location::Vertex, loc.vertex = ids[largest];
    } else if (w[smallest] <= merge_) {
      int a = ids[(smallest + 1) % 3], b = ids[(smallest + 2) % 3];
      double wa = w[(smallest + 1) % 3], wb = w[(smallest + 2) % 3];
      if (a > b) std::swap(a, b), std::swap(wa, wb);
      loc.kind = Location::Edge, loc.edge = {a, b}, loc.t = wb / (wa + wb);
    } else {
      loc.kind = Location::Face, loc.face = point.face, loc.weights = w / w.sum();
    }
    return loc;
  }

  // The global id of a location, made on first use (merging near-coincident points).
  int idOf(const Location& loc) {
    if (loc.kind == Location::Vertex) return loc.vertex;
    if (loc.kind == Location::Edge) {
      auto& list = edgePoints_[loc.edge];
      for (const auto& [t, id] : list)
        if (std::abs(t - loc.t) <= merge_) return id;
      const int id = newVertex((1.0 - loc.t) * positions_[loc.edge.first] +
                               loc.t * positions_[loc.edge.second]);
      list.emplace_back(loc.t, id);
      for (int f : facesOf(loc)) touched_.insert(f);
      return id;
    }
    auto& list = facePoints_[loc.face];
    for (const auto& [w, id] : list)
      if ((w - loc.weights).cwiseAbs().maxCoeff() <= merge_) return id;
    const auto ids = faceVertices(surface_, loc.face);
    const int id =
        newVertex(loc.weights[0] * positions_[ids[0]] + loc.weights[1] * positions_[ids[1]] +
                  loc.weights[2] * positions_[ids[2]]);
    list.emplace_back(loc.weights, id);
    touched_.insert(loc.face);
    return id;
  }

  std::vector<int> facesOf(const Location& loc) const {
    std::vector<int> faces;
    if (loc.kind == Location::Face) return {loc.face};
    const int v = loc.kind == Location::Vertex ? loc.vertex : loc.edge.first;
    for (auto fh : surface_.vf_range(TriMesh::VertexHandle(v))) {
      if (loc.kind == Location::Vertex) {
        faces.push_back(fh.idx());
        continue;
      }
      for (auto w : surface_.fv_range(fh))
        if (w.idx() == loc.edge.second) faces.push_back(fh.idx());
    }
    std::sort(faces.begin(), faces.end());
    return faces;
  }

  // A step of a polyline between two located points: the face it runs in.
  void addStep(int polyline, const Location& p, const Location& q) {
    const int ip = idOf(p), iq = idOf(q);
    if (ip == iq) return;
    const auto fp = facesOf(p), fq = facesOf(q);
    std::vector<int> common;
    std::set_intersection(fp.begin(), fp.end(), fq.begin(), fq.end(), std::back_inserter(common));
    if (common.empty())
      throw SolverFailure("layout mesh: a step of side " + std::to_string(polyline) +
                          " leaves its surface face");
    steps_.push_back({polyline, common.front(), ip, iq});
    touched_.insert(common.front());
  }

  LayoutMesh build(size_t polylineCount) {
    for (auto& [key, list] : edgePoints_) std::sort(list.begin(), list.end());
    std::map<int, std::vector<size_t>> stepsOfFace;
    for (size_t s = 0; s < steps_.size(); ++s) stepsOfFace[steps_[s].face].push_back(s);
    std::vector<std::vector<int>> stepChains(steps_.size());

    TriangleSoup soup;
    std::vector<int> parent;
    for (auto fh : surface_.faces()) {
      const int f = fh.idx();
      const auto ids = faceVertices(surface_, f);
      if (!touched_.count(f)) {
        soup.triangles.push_back(ids);
        parent.push_back(f);
        continue;
      }
      triangulateFace(f, ids, stepsOfFace[f], stepChains, soup.triangles, parent);
    }
    soup.vertices = positions_;

    LayoutMesh out;
    out.mesh = meshFromSoup(soup);
    out.parentFace = std::move(parent);
    out.surfaceVertex.assign(positions_.size(), -1);
    for (size_t v = 0; v < surface_.n_vertices(); ++v) out.surfaceVertex[v] = static_cast<int>(v);
    out.chains.resize(polylineCount);
    for (size_t s = 0; s < steps_.size(); ++s) {
      auto& chain = out.chains[steps_[s].polyline];
      for (int v : stepChains[s])
        if (chain.empty() || chain.back() != v) chain.push_back(v);
    }
    return out;
  }

 private:
  struct Step {
    int polyline, face, from, to;
  };

  int newVertex(const Eigen::Vector3d& p) {
    positions_.push_back(p);
    return static_cast<int>(positions_.size()) - 1;
  }

  void triangulateFace(int f, const std::array<int, 3>& ids, const std::vector<size_t>& steps,
                       std::vector<std::vector<int>>& stepChains,
                       std::vector<std::array<int, 3>>& triangles, std::vector<int>& parent) {
    // The face in its own plane: a at the origin, b on the x axis, c above it (counter-clockwise,
    // the orientation of the face).
    const Eigen::Vector3d pa = positions_[ids[0]], pb = positions_[ids[1]], pc = positions_[ids[2]];
    const Eigen::Vector3d ex = (pb - pa).normalized();
    const Eigen::Vector3d normal = (pb - pa).cross(pc - pa).normalized();
    const Eigen::Vector3d ey = normal.cross(ex);
    const auto planar = [&](const Eigen::Vector3d& p) {
      return Point2((p - pa).dot(ex), (p - pa).dot(ey));
    };

    Triangulation cdt;
    std::unordered_map<int, Triangulation::Vertex_handle> handles;
    const auto insert = [&](int id) {
      auto it = handles.find(id);
      if (it != handles.end()) return it->second;
      auto vh = cdt.insert(planar(positions_[id]));
      if (vh->info().id >= 0 && vh->info().id != id)
        throw SolverFailure("layout mesh: two inserted points coincide in surface face " +
                            std::to_string(f));
      vh->info().id = id;
      handles.emplace(id, vh);
      return vh;
    };
    for (int k = 0; k < 3; ++k) {
      const int a = ids[k], b = ids[(k + 1) % 3];
      std::vector<int> along{a};
      if (auto it = edgePoints_.find(edgeKey(a, b)); it != edgePoints_.end()) {
        std::vector<int> inner;
        for (const auto& [t, id] : it->second) inner.push_back(id);
        if (a > b) std::reverse(inner.begin(), inner.end());
        along.insert(along.end(), inner.begin(), inner.end());
      }
      along.push_back(b);
      for (size_t i = 0; i + 1 < along.size(); ++i)
        cdt.insert_constraint(insert(along[i]), insert(along[i + 1]));
    }
    if (auto it = facePoints_.find(f); it != facePoints_.end())
      for (const auto& [w, id] : it->second) insert(id);
    std::vector<std::pair<Triangulation::Constraint_id, int>> stepConstraints;
    for (size_t s : steps) {
      const auto vp = insert(steps_[s].from), vq = insert(steps_[s].to);
      stepConstraints.emplace_back(cdt.insert_constraint(vp, vq), steps_[s].from);
    }

    // Vertices CGAL made at crossings of constraints get ids and positions (back to 3D in the
    // face).
    const Eigen::Vector3d origin = pa;
    for (auto vh : cdt.finite_vertex_handles()) {
      if (vh->info().id >= 0) continue;
      const Eigen::Vector3d p = origin + vh->point().x() * ex + vh->point().y() * ey;
      vh->info().id = newVertex(p);
    }

    // Faces inside the surface face: those not reachable from outside without crossing a constraint
    // (the face's own edges are constraints).
    std::set<Triangulation::Face_handle> outside;
    std::deque<Triangulation::Face_handle> queue{cdt.infinite_face()};
    outside.insert(cdt.infinite_face());
    while (!queue.empty()) {
      const auto fh = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        if (fh->is_constrained(i)) continue;
        const auto next = fh->neighbor(i);
        if (outside.insert(next).second) queue.push_back(next);
      }
    }
    for (auto fh : cdt.finite_face_handles()) {
      if (outside.count(fh)) continue;
      triangles.push_back(
          {fh->vertex(0)->info().id, fh->vertex(1)->info().id, fh->vertex(2)->info().id});
      parent.push_back(f);
    }

    for (size_t k = 0; k < steps.size(); ++k) {
      const auto [cid, from] = stepConstraints[k];
      std::vector<int> chain;
      for (auto it = cdt.vertices_in_constraint_begin(cid);
           it != cdt.vertices_in_constraint_end(cid); ++it)
        chain.push_back((*it)->info().id);
      if (!chain.empty() && chain.front() != from) std::reverse(chain.begin(), chain.end());
      stepChains[steps[k]] = std::move(chain);
    }
  }

  const TriMesh& surface_;
  double merge_;
  std::vector<Eigen::Vector3d> positions_;
  std::map<EdgeKey, std::vector<std::pair<double, int>>> edgePoints_;
  std::map<int, std::vector<std::pair<Eigen::Vector3d, int>>> facePoints_;
  std::set<int> touched_;
  std::vector<Step> steps_;
};

}  // namespace

LayoutMesh buildLayoutMesh(const TriMesh& surface, const std::vector<SurfacePoint>& points,
                           const std::vector<std::vector<SurfacePoint>>& polylines,
                           double mergeFraction) {
  if (surface.n_faces() == 0) throw InvalidInput("layout: the surface has no faces");
  Builder builder(surface, mergeFraction);
  std::vector<int> pointIds;
  for (const auto& p : points) pointIds.push_back(builder.idOf(builder.locate(p)));
  for (size_t k = 0; k < polylines.size(); ++k) {
    const auto& line = polylines[k];
    for (size_t i = 1; i < line.size(); ++i)
      builder.addStep(static_cast<int>(k), builder.locate(line[i - 1]), builder.locate(line[i]));
  }
  LayoutMesh out = builder.build(polylines.size());
  out.pointVertices = std::move(pointIds);
  return out;
}

}  // namespace egg::patching
