// Cutting a geodesic quad out of the surface (Section 2.3.2): insert the corners as vertices, trace
// the four shortest geodesics, insert their polylines into the mesh (split edges where they cross,
// re-triangulate the faces they cut), and keep the faces the quad encloses.
#include "core/egg/patch.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace egg {

void PatchOptions::validate() const {
  if (!(angleMargin >= 0.0 && angleMargin < 1.0))
    throw InvalidInput("patch.angle_margin must lie in [0, 1) rad");
  if (!(boundaryWrapToleranceRad >= 0.0))
    throw InvalidInput("patch.boundary_wrap_tolerance_rad must be >= 0");
  if (!(mergeFraction >= 0.0 && mergeFraction < 0.1))
    throw InvalidInput("patch.merge_fraction must lie in [0, 0.1)");
}

namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey edgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

std::string format(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Replaces every triangle holding edge (x, y) by two triangles through the new vertex n.
void splitEdge(TriangleSoup& soup, int x, int y, int n) {
  const size_t count = soup.triangles.size();
  for (size_t f = 0; f < count; ++f) {
    auto t = soup.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3], c = t[(i + 2) % 3];
      if (edgeKey(a, b) != edgeKey(x, y)) continue;
      soup.triangles[f] = {a, n, c};
      soup.triangles.push_back({n, b, c});
      break;
    }
  }
}

// Makes a corner a mesh vertex (split face or edge, or reuse a vertex it coincides with).
int insertCorner(TriangleSoup& soup, const TriMesh& mesh, const SurfacePoint& point, double merge) {
  const auto ids = faceVertices(mesh, point.face);
  const Eigen::Vector3d& w = point.barycentric;
  int largest = 0, smallest = 0;
  for (int i = 1; i < 3; ++i) {
    if (w[i] > w[largest]) largest = i;
    if (w[i] < w[smallest]) smallest = i;
  }
  if (w[largest] >= 1.0 - merge) return ids[largest];
  const int n = static_cast<int>(soup.vertices.size());
  if (w[smallest] <= merge) {
    const int a = ids[(smallest + 1) % 3], b = ids[(smallest + 2) % 3];
    const double wa = w[(smallest + 1) % 3], wb = w[(smallest + 2) % 3];
    soup.vertices.push_back((wa * soup.vertices[a] + wb * soup.vertices[b]) / (wa + wb));
    splitEdge(soup, a, b, n);
    return n;
  }
  soup.vertices.push_back(w[0] * soup.vertices[ids[0]] + w[1] * soup.vertices[ids[1]] +
                          w[2] * soup.vertices[ids[2]]);
  // Faces of `mesh` are the soup's triangles in order (meshFromSoup), possibly rotated.
  const auto old = soup.triangles[point.face];
  soup.triangles[point.face] = {old[0], old[1], n};
  soup.triangles.push_back({old[1], old[2], n});
  soup.triangles.push_back({old[2], old[0], n});
  return n;
}

// A point of a traced boundary: a mesh vertex or a point on an edge.
struct PathNode {
  int vertex = -1;     // set for a vertex, else the id of the inserted vertex
  int a = -1, b = -1;  // edge (a < b) for an edge point
  double t = 0.0;      // position from a to b
  bool onEdge() const { return a >= 0; }
};

using EdgePoints =
    std::map<EdgeKey, std::vector<std::pair<double, int>>>;  // inserted vertices per edge

// The surface with the four corners inserted as vertices.
struct CornersInserted {
  TriangleSoup soup;  // the surface's soup, the corners added
  TriMesh work;       // the same as a mesh
  std::array<int, 4> cornerIds{};
};

// 1. Corners onto the surface, as vertices. When the four land in faces whose neighbourhoods
//    (the face and the faces across its edges, all an insertion may split) are disjoint, the
//    usual case, they go into the soup together: one mesh rebuild instead of four (~2.5 ms each
//    on a 5k-vertex surface). Otherwise one at a time, each snapped on the mesh so far.
CornersInserted insertCorners(const TriMesh& surface,
                              const std::array<Eigen::Vector3d, 4>& requested, double merge,
                              double maxOffset, Patch& patch) {
  CornersInserted c;
  c.soup = soupFromMesh(surface);
  TriangleSoup& soup = c.soup;
  std::array<SurfacePoint, 4> snapped;
  std::set<int> neighbourhoods;
  bool together = true;
  for (int k = 0; k < 4; ++k) {
    if (!requested[k].allFinite())
      throw InvalidInput("patch corner " + std::to_string(k) + " is not a finite point");
    snapped[k] = geodesic::snapToSurface(surface, requested[k]);
    patch.cornerOffsets[k] = (position(surface, snapped[k]) - requested[k]).norm();
    if (patch.cornerOffsets[k] > maxOffset)
      throw InvalidInput("patch corner " + std::to_string(k) + " " + format(requested[k]) +
                         " lies " + std::to_string(patch.cornerOffsets[k]) +
                         " m off the surface (more than " + std::to_string(maxOffset) + " m)");
    std::set<int> faces{snapped[k].face};
    for (auto fh : surface.ff_range(TriMesh::FaceHandle(snapped[k].face))) faces.insert(fh.idx());
    for (int f : faces) together = neighbourhoods.insert(f).second && together;
  }
  TriMesh& work = c.work;  // the surface with the corners inserted so far
  if (!together) work = surface;
  std::array<int, 4>& cornerIds = c.cornerIds;
  for (int k = 0; k < 4; ++k) {
    if (together) {
      cornerIds[k] = insertCorner(soup, surface, snapped[k], merge);
    } else {
      cornerIds[k] = insertCorner(soup, work, geodesic::snapToSurface(work, requested[k]), merge);
      work = meshFromSoup(soup);
    }
    for (int j = 0; j < k; ++j)
      if (cornerIds[j] == cornerIds[k])
        throw InvalidInput("patch corners " + std::to_string(j) + " and " + std::to_string(k) +
                           " coincide");
  }
  if (together) work = meshFromSoup(soup);
  return c;
}

// One point of boundary k's traced path as a PathNode: a vertex of `work` when it lies (within
// `merge`) on one, else a point on an edge, inserted into the soup once per edge and position.
PathNode pathNodeOf(const TriMesh& work, const SurfacePoint& sp, double merge, int k,
                    TriangleSoup& soup, EdgePoints& edgePoints) {
  const auto ids = faceVertices(work, sp.face);
  const Eigen::Vector3d& w = sp.barycentric;
  int largest = 0, smallest = 0;
  for (int i = 1; i < 3; ++i) {
    if (w[i] > w[largest]) largest = i;
    if (w[i] < w[smallest]) smallest = i;
  }
  PathNode node;
  if (w[largest] >= 1.0 - merge) {
    node.vertex = ids[largest];
  } else if (w[smallest] <= 1e-9) {
    int a = ids[(smallest + 1) % 3], b = ids[(smallest + 2) % 3];
    double wa = w[(smallest + 1) % 3], wb = w[(smallest + 2) % 3];
    if (a > b) std::swap(a, b), std::swap(wa, wb);
    node.a = a, node.b = b, node.t = wb / (wa + wb);
    auto& list = edgePoints[{a, b}];
    for (const auto& [t, id] : list)
      if (std::abs(t - node.t) <= merge) node.vertex = id;
    if (node.vertex < 0) {
      node.vertex = static_cast<int>(soup.vertices.size());
      soup.vertices.push_back((1 - node.t) * soup.vertices[a] + node.t * soup.vertices[b]);
      list.emplace_back(node.t, node.vertex);
    }
  } else {
    throw SolverFailure("patch: boundary " + std::to_string(k) + " has a point inside a face");
  }
  return node;
}

// The four boundaries as PathNodes, and the vertices they add on edges of `work`.
struct TracedBoundaries {
  std::array<std::vector<PathNode>, 4> paths;
  EdgePoints edgePoints;  // inserted vertices per edge
};

// 2. The four shortest geodesics.
TracedBoundaries traceBoundaries(const TriMesh& work, const std::array<int, 4>& cornerIds,
                                 const PatchOptions& options, TriangleSoup& soup) {
  const double merge = options.mergeFraction;
  const geodesic::DistanceSolver solver(work);
  TracedBoundaries out;
  auto& paths = out.paths;
  auto& edgePoints = out.edgePoints;
  // The four traces are independent propagations: run them concurrently, then insert them in order.
  std::array<geodesic::GeodesicPath, 4> traced;
  tbb::parallel_for(0, 4, [&](int k) {
    traced[k] = solver.path(geodesic::vertexPoint(work, cornerIds[k]),
                            geodesic::vertexPoint(work, cornerIds[(k + 1) % 4]));
  });
  for (int k = 0; k < 4; ++k) {
    const auto& path = traced[k];
    if (!std::isfinite(path.length) || path.points.size() < 2)
      throw InfeasiblePatch("boundary " + std::to_string(k) + ": corners " + std::to_string(k) +
                            " and " + std::to_string((k + 1) % 4) +
                            " are not connected on the surface");
    if (const double wrap = boundaryWrapTurning(work, path.positions, path.bendVertices);
        wrap > options.boundaryWrapToleranceRad) {
      int at = path.bendVertices.front();
      for (int v : path.bendVertices)
        if (work.is_boundary(TriMesh::VertexHandle(v))) at = v;
      throw InfeasiblePatch("boundary " + std::to_string(k) +
                            " wraps around the surface boundary or a hole (turning " +
                            std::to_string(wrap) + " rad round it, near " +
                            format(toEigen(work.point(TriMesh::VertexHandle(at)))) +
                            "): it is not a geodesic there");
    }
    for (const SurfacePoint& sp : path.points) {
      const PathNode node = pathNodeOf(work, sp, merge, k, soup, edgePoints);
      if (paths[k].empty() || paths[k].back().vertex != node.vertex) paths[k].push_back(node);
    }
  }
  for (auto& [key, list] : edgePoints) std::sort(list.begin(), list.end());
  return out;
}

// 3. Boundaries may share only their common corners.
void checkBoundariesApart(const std::array<std::vector<PathNode>, 4>& paths,
                          const std::array<int, 4>& cornerIds, const TriangleSoup& soup) {
  std::map<int, int> owner;
  for (int k = 0; k < 4; ++k)
    for (const auto& node : paths[k]) {
      const bool corner = node.vertex == cornerIds[k] || node.vertex == cornerIds[(k + 1) % 4];
      if (corner) continue;
      auto [it, inserted] = owner.emplace(node.vertex, k);
      if (!inserted && it->second != k)
        throw InfeasiblePatch("boundaries " + std::to_string(it->second) + " and " +
                              std::to_string(k) + " cross at " +
                              format(soup.vertices[node.vertex]));
    }
  for (int k = 0; k < 4; ++k)
    for (const auto& node : paths[k])
      for (int c = 0; c < 4; ++c)
        if (node.vertex == cornerIds[c] && c != k && c != (k + 1) % 4)
          throw InfeasiblePatch("boundary " + std::to_string(k) + " runs through corner " +
                                std::to_string(c) + " (collinear or crossing corners)");
}

// The faces of `work` holding a path node (the faces round its vertex, or the two on its edge).
std::set<int> facesOf(const TriMesh& work, const PathNode& n) {
  std::set<int> faces;
  if (n.onEdge()) {
    for (auto fh : work.vf_range(TriMesh::VertexHandle(n.a)))
      for (auto v : work.fv_range(fh))
        if (v.idx() == n.b) faces.insert(fh.idx());
  } else {
    for (auto fh : work.vf_range(TriMesh::VertexHandle(n.vertex))) faces.insert(fh.idx());
  }
  return faces;
}

// The boundaries' steps: the edges the flood fill must not cross, the chords across faces of
// `work`, and each boundary's chain of vertices.
struct BoundarySteps {
  std::set<EdgeKey> constrained;
  std::map<int, std::vector<EdgeKey>> chords;  // face of `work` -> chords across it
  std::array<std::vector<int>, 4> chains;
};

// 4. Re-triangulate every face the boundaries cut. Steps of a path either run along an edge of
//    `work` or cut straight across one face (a geodesic is straight inside a face).
BoundarySteps boundaryStepsOf(const TriMesh& work,
                              const std::array<std::vector<PathNode>, 4>& paths) {
  BoundarySteps out;
  auto& constrained = out.constrained;
  auto& chords = out.chords;
  auto& chains = out.chains;
  for (int k = 0; k < 4; ++k) {
    chains[k].push_back(paths[k].front().vertex);
    for (size_t s = 1; s < paths[k].size(); ++s) {
      const PathNode &p = paths[k][s - 1], &q = paths[k][s];
      const auto fp = facesOf(work, p), fq = facesOf(work, q);
      std::vector<int> common;
      std::set_intersection(fp.begin(), fp.end(), fq.begin(), fq.end(), std::back_inserter(common));
      if (common.empty())
        throw SolverFailure("patch: a step of boundary " + std::to_string(k) + " leaves its face");
      chains[k].push_back(q.vertex);
      constrained.insert(edgeKey(p.vertex, q.vertex));
      if (common.size() == 1) {
        // Unless both ends are on one edge of that face, the step is a chord of the face.
        const auto ids = faceVertices(work, common[0]);
        bool alongEdge = false;
        for (int i = 0; i < 3 && !alongEdge; ++i) {
          const EdgeKey e = edgeKey(ids[i], ids[(i + 1) % 3]);
          const auto onThisEdge = [&](const PathNode& n) {
            return n.onEdge() ? EdgeKey(n.a, n.b) == e
                              : (n.vertex == e.first || n.vertex == e.second);
          };
          alongEdge = onThisEdge(p) && onThisEdge(q);
        }
        if (!alongEdge) chords[common[0]].push_back(edgeKey(p.vertex, q.vertex));
      }
    }
  }
  return out;
}

// A face of `work` as a polygon: its three vertices with the points inserted on its edges.
std::vector<int> facePolygon(const std::array<int, 3>& ids, const EdgePoints& edgePoints) {
  std::vector<int> polygon;
  for (int i = 0; i < 3; ++i) {
    const int a = ids[i], b = ids[(i + 1) % 3];
    polygon.push_back(a);
    const auto it = edgePoints.find(edgeKey(a, b));
    if (it == edgePoints.end()) continue;
    std::vector<int> along;
    for (const auto& [t, id] : it->second) along.push_back(id);
    if (a > b) std::reverse(along.begin(), along.end());
    polygon.insert(polygon.end(), along.begin(), along.end());
  }
  return polygon;
}

// Cuts a face's polygon along the chords across it into pieces.
std::vector<std::vector<int>> cutByChords(const std::vector<int>& polygon,
                                          const std::vector<EdgeKey>* faceChords,
                                          const TriangleSoup& soup) {
  std::vector<std::vector<int>> pieces{polygon};
  if (faceChords)
    for (const auto& [x, y] : *faceChords) {
      bool split = false;
      for (size_t p = 0; p < pieces.size() && !split; ++p) {
        auto& piece = pieces[p];
        const auto ix = std::find(piece.begin(), piece.end(), x),
                   iy = std::find(piece.begin(), piece.end(), y);
        if (ix == piece.end() || iy == piece.end()) continue;
        size_t i = ix - piece.begin(), j = iy - piece.begin();
        if (i > j) std::swap(i, j);
        std::vector<int> first(piece.begin() + i, piece.begin() + j + 1);
        std::vector<int> second(piece.begin() + j, piece.end());
        second.insert(second.end(), piece.begin(), piece.begin() + i + 1);
        piece = first;
        pieces.push_back(second);
        split = true;
      }
      if (!split)
        throw InfeasiblePatch("two boundaries cross inside a face near " +
                              format(soup.vertices[x]));
    }
  return pieces;
}

// Each piece is convex (a triangle cut by straight chords); clip ears of positive area.
void clipEars(const std::vector<std::vector<int>>& pieces, const TriangleSoup& soup,
              const Eigen::Vector3d& normal, TriangleSoup& cut) {
  for (auto piece : pieces) {
    while (piece.size() > 3) {
      size_t best = piece.size();
      double bestArea = 0.0;
      for (size_t i = 0; i < piece.size(); ++i) {
        const auto& a = soup.vertices[piece[(i + piece.size() - 1) % piece.size()]];
        const auto& b = soup.vertices[piece[i]];
        const auto& c = soup.vertices[piece[(i + 1) % piece.size()]];
        const double area =
            (b - a).cross(c - a).dot(normal) / ((b - a).norm() * (c - a).norm() + 1e-300);
        if (area > bestArea) bestArea = area, best = i;
      }
      if (best == piece.size()) break;  // only collinear points left: nothing to triangulate
      const size_t n = piece.size();
      cut.triangles.push_back({piece[(best + n - 1) % n], piece[best], piece[(best + 1) % n]});
      piece.erase(piece.begin() + best);
    }
    if (piece.size() == 3) {
      const auto& a = soup.vertices[piece[0]];
      if ((soup.vertices[piece[1]] - a).cross(soup.vertices[piece[2]] - a).dot(normal) > 0.0)
        cut.triangles.push_back({piece[0], piece[1], piece[2]});
    }
  }
}

// Every face of `work`, cut along the boundaries and triangulated.
TriangleSoup cutFaces(const TriMesh& work, const TriangleSoup& soup, const EdgePoints& edgePoints,
                      const std::map<int, std::vector<EdgeKey>>& chords) {
  TriangleSoup cut;
  cut.vertices = soup.vertices;
  for (auto fh : work.faces()) {
    const auto ids = faceVertices(work, fh.idx());
    const std::vector<int> polygon = facePolygon(ids, edgePoints);
    const auto it = chords.find(fh.idx());
    const auto pieces = cutByChords(polygon, it != chords.end() ? &it->second : nullptr, soup);
    const Eigen::Vector3d normal = (soup.vertices[ids[1]] - soup.vertices[ids[0]])
                                       .cross(soup.vertices[ids[2]] - soup.vertices[ids[0]]);
    clipEars(pieces, soup, normal, cut);
  }
  return cut;
}

// The split surface's faces in regions the boundaries separate.
struct Regions {
  std::vector<int> component;  // per face of the split surface
  std::vector<double> area;
  std::vector<char> touchesSurfaceBoundary;
};

// 5. Flood fill the faces without crossing a boundary; keep the region the quad encloses.
Regions floodFill(const TriMesh& split, const TriangleSoup& cut,
                  const std::set<EdgeKey>& constrained) {
  Regions out;
  std::vector<int>& component = out.component;
  std::vector<double>& componentArea = out.area;
  std::vector<char>& componentTouchesSurfaceBoundary = out.touchesSurfaceBoundary;
  component.assign(split.n_faces(), -1);
  for (auto seed : split.faces()) {
    if (component[seed.idx()] >= 0) continue;
    const int id = static_cast<int>(componentArea.size());
    componentArea.push_back(0.0);
    componentTouchesSurfaceBoundary.push_back(0);
    std::vector<int> stack{seed.idx()};
    component[seed.idx()] = id;
    while (!stack.empty()) {
      const auto fh = TriMesh::FaceHandle(stack.back());
      stack.pop_back();
      const auto ids = faceVertices(split, fh.idx());
      componentArea[id] += 0.5 * (cut.vertices[ids[1]] - cut.vertices[ids[0]])
                                     .cross(cut.vertices[ids[2]] - cut.vertices[ids[0]])
                                     .norm();
      for (auto heh : split.fh_range(fh)) {
        const int a = split.from_vertex_handle(heh).idx(), b = split.to_vertex_handle(heh).idx();
        if (constrained.count(edgeKey(a, b))) continue;
        const auto opposite = split.opposite_face_handle(heh);
        if (!opposite.is_valid()) {
          componentTouchesSurfaceBoundary[id] = 1;
          continue;
        }
        if (component[opposite.idx()] < 0)
          component[opposite.idx()] = id, stack.push_back(opposite.idx());
      }
    }
  }
  return out;
}

// The region the quad encloses, of the two beside side 0's first step.
int enclosedRegion(const TriMesh& split, const Regions& regions, const std::vector<int>& side0) {
  const auto& component = regions.component;
  // The regions left and right of the first step of side 0.
  int left = -1, right = -1;
  for (auto heh : split.voh_range(TriMesh::VertexHandle(side0[0]))) {
    if (split.to_vertex_handle(heh).idx() != side0[1]) continue;
    if (!split.is_boundary(heh)) left = component[split.face_handle(heh).idx()];
    const auto opp = split.opposite_halfedge_handle(heh);
    if (!split.is_boundary(opp)) right = component[split.face_handle(opp).idx()];
  }
  if (left == right)
    throw InfeasiblePatch(
        "the four boundaries do not enclose a region: they cross or leave the surface");
  const auto encloses = [&](int c) { return c >= 0 && !regions.touchesSurfaceBoundary[c]; };
  int inside = -1;
  if (encloses(left) && encloses(right))
    inside = regions.area[left] <= regions.area[right] ? left : right;
  else if (encloses(left))
    inside = left;
  else if (encloses(right))
    inside = right;
  else
    throw InfeasiblePatch(
        "the region inside the four boundaries contains part of the surface boundary or a hole");
  return inside;
}

// 6. The patch mesh, with the boundary chains renumbered.
void fillPatch(const TriMesh& split, const TriangleSoup& cut, const Regions& regions, int inside,
               const std::array<int, 4>& cornerIds, const std::array<std::vector<int>, 4>& chains,
               Patch& patch) {
  TriangleSoup out;
  std::vector<int> renumber(cut.vertices.size(), -1);
  for (auto fh : split.faces()) {
    if (regions.component[fh.idx()] != inside) continue;
    std::array<int, 3> t{};
    const auto ids = faceVertices(split, fh.idx());
    for (int i = 0; i < 3; ++i) {
      if (renumber[ids[i]] < 0)
        renumber[ids[i]] = static_cast<int>(out.vertices.size()),
        out.vertices.push_back(cut.vertices[ids[i]]);
      t[i] = renumber[ids[i]];
    }
    out.triangles.push_back(t);
  }
  patch.mesh = meshFromSoup(out);
  patch.area = regions.area[inside];
  for (int k = 0; k < 4; ++k) {
    patch.cornerVertices[k] = renumber[cornerIds[k]];
    patch.corners[k] = cut.vertices[cornerIds[k]];
    double s = 0.0;
    for (size_t i = 0; i < chains[k].size(); ++i) {
      const int v = renumber[chains[k][i]];
      if (v < 0)
        throw SolverFailure("patch: boundary " + std::to_string(k) +
                            " lost a vertex while cutting");
      if (i > 0) s += (cut.vertices[chains[k][i]] - cut.vertices[chains[k][i - 1]]).norm();
      patch.sides[k].push_back(v);
      patch.sideArcLength[k].push_back(s);
    }
    patch.sideLengths[k] = s;
  }
}

// 7. Criterion (iv): every inner angle below pi.
void checkInnerAngles(Patch& patch, const PatchOptions& options) {
  for (int k = 0; k < 4; ++k) {
    patch.innerAngles[k] =
        vertexAngleSum(patch.mesh, TriMesh::VertexHandle(patch.cornerVertices[k]));
    if (patch.innerAngles[k] >= M_PI - options.angleMargin)
      throw InfeasiblePatch("inner angle at corner " + std::to_string(k) + " is " +
                            std::to_string(patch.innerAngles[k]) +
                            " rad, not below pi: the patch is not convex (criterion iv)");
  }
}

}  // namespace

Patch makePatch(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& requested,
                const PatchOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (surface.n_faces() == 0) throw InvalidInput("patch: the surface has no faces");
  Patch patch;
  const double merge = options.mergeFraction;
  const double maxOffset =
      options.maxCornerOffsetM > 0.0
          ? options.maxCornerOffsetM
          : std::max(2.0 * meanEdgeLength(surface), 0.01 * boundingBox(surface).size().norm());

  CornersInserted corners = insertCorners(surface, requested, merge, maxOffset, patch);  // 1.
  const TriMesh& work = corners.work;
  TriangleSoup& soup = corners.soup;
  const TracedBoundaries boundaries =
      traceBoundaries(work, corners.cornerIds, options, soup);          // 2.
  checkBoundariesApart(boundaries.paths, corners.cornerIds, soup);      // 3.
  const BoundarySteps steps = boundaryStepsOf(work, boundaries.paths);  // 4.
  const TriangleSoup cut = cutFaces(work, soup, boundaries.edgePoints, steps.chords);
  // Drop vertices no triangle uses (none expected) by rebuilding through meshFromSoup later.
  const TriMesh split = meshFromSoup(cut);
  const Regions regions = floodFill(split, cut, steps.constrained);  // 5.
  const int inside = enclosedRegion(split, regions, steps.chains[0]);
  fillPatch(split, cut, regions, inside, corners.cornerIds, steps.chains, patch);  // 6.
  checkInnerAngles(patch, options);                                                // 7.
  patch.propagations = 4;
  patch.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return patch;
}

void refreshPatchGeometry(Patch& patch) {
  for (int k = 0; k < 4; ++k)
    patch.innerAngles[k] =
        vertexAngleSum(patch.mesh, TriMesh::VertexHandle(patch.cornerVertices[k]));
  patch.area = surfaceArea(patch.mesh);
}

SurfacePoint sidePoint(const Patch& patch, int side, double arcLength) {
  const auto& s = patch.sideArcLength[side];
  const auto& chain = patch.sides[side];
  arcLength = std::clamp(arcLength, 0.0, s.back());
  size_t hi = std::upper_bound(s.begin(), s.end(), arcLength) - s.begin();
  hi = std::clamp<size_t>(hi, 1, s.size() - 1);
  const size_t lo = hi - 1;
  const double span = s[hi] - s[lo];
  const double t = span > 0 ? (arcLength - s[lo]) / span : 0.0;
  const int a = chain[lo], b = chain[hi];
  for (auto heh : patch.mesh.voh_range(TriMesh::VertexHandle(a))) {
    if (patch.mesh.to_vertex_handle(heh).idx() != b) continue;
    auto h = patch.mesh.is_boundary(heh) ? patch.mesh.opposite_halfedge_handle(heh) : heh;
    SurfacePoint point;
    point.face = patch.mesh.face_handle(h).idx();
    const auto ids = faceVertices(patch.mesh, point.face);
    for (int i = 0; i < 3; ++i)
      point.barycentric[i] = ids[i] == a ? 1.0 - t : ids[i] == b ? t : 0.0;
    return point;
  }
  throw SolverFailure("patch: side " + std::to_string(side) +
                      " has no edge between consecutive vertices");
}

}  // namespace egg
