// The patch layout: corners, curves traced once, T-junctions, segments (see layout.hpp).
#include "patching/layout.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

namespace egg::patching {

void LayoutOptions::validate() const { patch.validate(); }

namespace {

std::string format(const Eigen::Vector3d& p) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", p.x(), p.y(), p.z());
}

double maxCornerOffset(const TriMesh& surface, const LayoutOptions& options) {
  return options.patch.maxCornerOffsetM > 0.0
             ? options.patch.maxCornerOffsetM
             : std::max(2.0 * meanEdgeLength(surface), 0.01 * boundingBox(surface).size().norm());
}

// The surface vertices a point's barycentric weights rest on (weights above `eps`).
std::vector<int> support(const TriMesh& mesh, const SurfacePoint& p, double eps = 1e-12) {
  const auto ids = faceVertices(mesh, p.face);
  std::vector<int> out;
  for (int i = 0; i < 3; ++i)
    if (p.barycentric[i] > eps) out.push_back(ids[i]);
  return out;
}

// `p` in the barycentric weights of `face`, or false when it does not lie on that face.
bool inFace(const TriMesh& mesh, const SurfacePoint& p, int face, Eigen::Vector3d& weights) {
  if (p.face == face) return weights = p.barycentric, true;
  const auto from = faceVertices(mesh, p.face), to = faceVertices(mesh, face);
  weights.setZero();
  for (int i = 0; i < 3; ++i) {
    if (p.barycentric[i] <= 1e-12) continue;
    const auto it = std::find(to.begin(), to.end(), from[i]);
    if (it == to.end()) return false;
    weights[it - to.begin()] += p.barycentric[i];
  }
  weights /= weights.sum();
  return true;
}

// A face holding both points (they are consecutive points of a traced geodesic).
int commonFace(const TriMesh& mesh, const SurfacePoint& p, const SurfacePoint& q) {
  Eigen::Vector3d w;
  if (inFace(mesh, q, p.face, w)) return p.face;
  if (inFace(mesh, p, q.face, w)) return q.face;
  for (int v : support(mesh, p))
    for (auto fh : mesh.vf_range(TriMesh::VertexHandle(v))) {
      Eigen::Vector3d a, b;
      if (inFace(mesh, p, fh.idx(), a) && inFace(mesh, q, fh.idx(), b)) return fh.idx();
    }
  return -1;
}

std::vector<double> cumulative(const std::vector<Eigen::Vector3d>& positions) {
  std::vector<double> s{0.0};
  for (size_t i = 1; i < positions.size(); ++i)
    s.push_back(s.back() + (positions[i] - positions[i - 1]).norm());
  return s;
}

// Inserts a point into a curve at arc length s; returns the point and its index in points.
std::pair<SurfacePoint, size_t> insertIntoCurve(const TriMesh& surface, LayoutCurve& curve,
                                                double s) {
  const auto arc = cumulative(curve.positions);
  s = std::clamp(s, 0.0, arc.back());
  size_t hi = std::upper_bound(arc.begin(), arc.end(), s) - arc.begin();
  hi = std::clamp<size_t>(hi, 1, arc.size() - 1);
  const size_t lo = hi - 1;
  const double span = arc[hi] - arc[lo];
  const double t = span > 0 ? (s - arc[lo]) / span : 0.0;
  const SurfacePoint &p = curve.points[lo], &q = curve.points[hi];
  const int face = commonFace(surface, p, q);
  if (face < 0) throw SolverFailure("layout: two consecutive points of a side share no face");
  Eigen::Vector3d wp, wq;
  inFace(surface, p, face, wp);
  inFace(surface, q, face, wq);
  SurfacePoint point{face, (1.0 - t) * wp + t * wq};
  if (t <= 0.0) return {p, lo};
  if (t >= 1.0) return {q, hi};
  curve.points.insert(curve.points.begin() + hi, point);
  curve.positions.insert(curve.positions.begin() + hi, position(surface, point));
  return {point, hi};
}

void traceCurve(const TriMesh& surface, const geodesic::DistanceSolver& solver,
                const PatchLayout& layout, LayoutCurve& curve) {
  const auto path = solver.path(layout.cornerPoints[curve.from], layout.cornerPoints[curve.to]);
  if (!std::isfinite(path.length) || path.points.size() < 2)
    throw InvalidInput(fmt::format("layout: corners {} and {} are not connected on the surface",
                                   curve.from, curve.to));
  curve.points = path.points;
  curve.positions = path.positions;
  curve.bendVertices = path.bendVertices;
  curve.length = path.length;
  (void)surface;
}

}  // namespace

SurfacePoint curvePoint(const PatchLayout& layout, int curveId, double s) {
  LayoutCurve copy = layout.curves[curveId];
  return insertIntoCurve(*layout.surface, copy, s).first;
}

double nearestArcLength(const PatchLayout& layout, int curveId, const Eigen::Vector3d& p) {
  const auto& pos = layout.curves[curveId].positions;
  const auto arc = cumulative(pos);
  double best = std::numeric_limits<double>::infinity(), bestS = 0.0;
  for (size_t i = 1; i < pos.size(); ++i) {
    const Eigen::Vector3d d = pos[i] - pos[i - 1];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - pos[i - 1]).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (pos[i - 1] + t * d - p).norm();
    if (dist < best) best = dist, bestS = arc[i - 1] + t * (arc[i] - arc[i - 1]);
  }
  return bestS;
}

int addCorner(PatchLayout& layout, const SurfacePoint& point) {
  layout.cornerPoints.push_back(point);
  layout.corners.push_back(position(*layout.surface, point));
  layout.cornerOffsets.push_back(0.0);
  return static_cast<int>(layout.corners.size()) - 1;
}

int addCornerOnCurve(PatchLayout& layout, int curveId, double s) {
  LayoutCurve& curve = layout.curves[curveId];
  const auto [point, index] = insertIntoCurve(*layout.surface, curve, s);
  (void)index;
  const int corner = addCorner(layout, point);
  // Keep the curve's corners in order along it.
  std::vector<std::pair<double, int>> along;
  for (int c : curve.corners)
    along.emplace_back(nearestArcLength(layout, curveId, layout.corners[c]), c);
  along.emplace_back(s, corner);
  std::stable_sort(along.begin(), along.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  curve.corners.clear();
  for (const auto& [arc, c] : along) curve.corners.push_back(c);
  return corner;
}

int addCurve(PatchLayout& layout, const geodesic::DistanceSolver& solver, int from, int to,
             const LayoutOptions&) {
  LayoutCurve curve;
  curve.from = from, curve.to = to, curve.corners = {from, to};
  traceCurve(*layout.surface, solver, layout, curve);
  ++layout.propagations;
  layout.curves.push_back(std::move(curve));
  return static_cast<int>(layout.curves.size()) - 1;
}

PatchLayout makeLayout(const TriMesh& surface, const geodesic::DistanceSolver& solver,
                       const std::vector<Eigen::Vector3d>& requested,
                       const std::vector<std::array<int, 4>>& patches,
                       const LayoutOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  if (surface.n_faces() == 0) throw InvalidInput("layout: the surface has no faces");
  PatchLayout layout;
  layout.surface = &surface;
  const double maxOffset = maxCornerOffset(surface, options);
  for (size_t k = 0; k < requested.size(); ++k) {
    if (!requested[k].allFinite())
      throw InvalidInput(fmt::format("corner {} is not a finite point", k));
    const SurfacePoint p = geodesic::snapToSurface(surface, requested[k]);
    addCorner(layout, p);
    layout.cornerOffsets[k] = (layout.corners[k] - requested[k]).norm();
    if (layout.cornerOffsets[k] > maxOffset)
      throw InvalidInput(
          fmt::format("corner {} {} lies {:.4g} m off the surface (more than {:.4g} m)", k,
                      format(requested[k]), layout.cornerOffsets[k], maxOffset));
  }
  std::set<std::pair<int, int>> sides;
  for (size_t p = 0; p < patches.size(); ++p) {
    const auto& q = patches[p];
    for (int k = 0; k < 4; ++k) {
      if (q[k] < 0 || q[k] >= static_cast<int>(requested.size()))
        throw InvalidInput(fmt::format("patch {}: corner index {} is not a corner (there are {})",
                                       p, q[k], requested.size()));
      for (int j = 0; j < k; ++j)
        if (q[j] == q[k])
          throw InvalidInput(fmt::format("patch {}: corner {} appears twice", p, q[k]));
    }
    for (int k = 0; k < 4; ++k)
      sides.insert({std::min(q[k], q[(k + 1) % 4]), std::max(q[k], q[(k + 1) % 4])});
  }
  for (size_t k = 0; k < requested.size(); ++k)
    for (size_t j = 0; j < k; ++j)
      if ((layout.corners[k] - layout.corners[j]).norm() <= 1e-9 * (1.0 + layout.corners[k].norm()))
        throw InvalidInput(fmt::format("corners {} and {} coincide on the surface", j, k));
  // A patch side shorter than half an edge of the mesh cannot be traced as a side: the corners
  // fall on one vertex or one edge (four corners 1e-7 m apart ended as a solver failure without a
  // report, issue 40).
  const double shortest = 0.5 * meanEdgeLength(surface);
  for (size_t p = 0; p < patches.size(); ++p)
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < k; ++j) {
        const double apart = (layout.corners[patches[p][k]] - layout.corners[patches[p][j]]).norm();
        if (apart < shortest)
          throw InvalidInput(fmt::format(
              "patch {}: corners {} and {} are {:.3g} m apart, less than half the mesh's mean edge "
              "length ({:.3g} m): the mesh cannot carry such a patch (a finer "
              "surface.edge_length_m, or corners farther apart)",
              p, patches[p][j], patches[p][k], apart, 2 * shortest));
      }
  layout.patches = patches;

  // Curves: the longest side pairs first; a side whose corners already lie on one curve is a
  // piece of it. A curve takes in every corner t with sides x - t and t - y between two of its
  // consecutive corners x, y: t is a T-junction on it.
  std::vector<std::pair<int, int>> pairs(sides.begin(), sides.end());
  std::stable_sort(pairs.begin(), pairs.end(), [&](const auto& a, const auto& b) {
    return (layout.corners[a.first] - layout.corners[a.second]).norm() >
           (layout.corners[b.first] - layout.corners[b.second]).norm();
  });
  const auto onOneCurve = [&](int a, int b) {
    for (const auto& c : layout.curves) {
      const bool hasA = std::count(c.corners.begin(), c.corners.end(), a) > 0;
      const bool hasB = std::count(c.corners.begin(), c.corners.end(), b) > 0;
      if (hasA && hasB) return true;
    }
    return false;
  };
  const auto isSide = [&](int a, int b) {
    return sides.count({std::min(a, b), std::max(a, b)}) > 0;
  };
  for (const auto& [a, b] : pairs) {
    if (onOneCurve(a, b)) continue;
    LayoutCurve curve;
    curve.from = a, curve.to = b, curve.corners = {a, b};
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t i = 0; i + 1 < curve.corners.size() && !grew; ++i)
        for (int t = 0; t < static_cast<int>(requested.size()) && !grew; ++t) {
          if (std::count(curve.corners.begin(), curve.corners.end(), t)) continue;
          if (isSide(curve.corners[i], t) && isSide(t, curve.corners[i + 1])) {
            curve.corners.insert(curve.corners.begin() + i + 1, t);
            grew = true;
          }
        }
    }
    layout.curves.push_back(std::move(curve));
  }

  // Trace in rounds: a curve whose end corners are final (not a T-junction on a curve still to be
  // traced); its own T-junction corners are then moved onto it and become final.
  std::vector<char> final(requested.size(), 1), traced(layout.curves.size(), 0);
  for (const auto& c : layout.curves)
    for (size_t i = 1; i + 1 < c.corners.size(); ++i) final[c.corners[i]] = 0;
  for (size_t done = 0; done < layout.curves.size();) {
    std::vector<int> ready;
    for (size_t c = 0; c < layout.curves.size(); ++c)
      if (!traced[c] && final[layout.curves[c].from] && final[layout.curves[c].to])
        ready.push_back(static_cast<int>(c));
    if (ready.empty())
      throw InvalidInput("layout: T-junction corners that lie on each other's sides form a cycle");
    tbb::parallel_for(size_t(0), ready.size(), [&](size_t i) {
      traceCurve(surface, solver, layout, layout.curves[ready[i]]);
    });
    layout.propagations += static_cast<int>(ready.size());
    for (int c : ready) {
      traced[c] = 1;
      ++done;
      LayoutCurve& curve = layout.curves[c];
      for (size_t i = 1; i + 1 < curve.corners.size(); ++i) {
        const int t = curve.corners[i];
        const double s = nearestArcLength(layout, c, layout.corners[t]);
        const auto [point, index] = insertIntoCurve(surface, curve, s);
        (void)index;
        const Eigen::Vector3d moved = position(surface, point);
        const double offset = (moved - requested[t]).norm();
        if (offset > maxOffset)
          throw InvalidInput(
              fmt::format("corner {} {} is a T-junction on the side from corner {} to corner {} "
                          "but lies {:.4g} m "
                          "off that geodesic (more than {:.4g} m)",
                          t, format(requested[t]), curve.from, curve.to, offset, maxOffset));
        layout.cornerPoints[t] = point;
        layout.corners[t] = moved;
        layout.cornerOffsets[t] = offset;
        final[t] = 1;
      }
    }
  }
  finishLayout(layout, options);
  layout.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return layout;
}

void finishLayout(PatchLayout& layout, const LayoutOptions& options) {
  const TriMesh& surface = *layout.surface;
  std::vector<std::vector<SurfacePoint>> polylines;
  for (const auto& c : layout.curves) polylines.push_back(c.points);
  layout.mesh =
      buildLayoutMesh(surface, layout.cornerPoints, polylines, options.patch.mergeFraction);
  layout.cornerVertex = layout.mesh.pointVertices;
  const auto& mesh = layout.mesh.mesh;
  const auto vertexPosition = [&](int v) { return toEigen(mesh.point(TriMesh::VertexHandle(v))); };

  // Problems of curves: wrapping around the surface boundary or a hole, crossing each other,
  // running through a corner that is not one of theirs.
  layout.curveProblems.assign(layout.curves.size(), "");
  layout.crossings.clear();
  const auto problem = [&](size_t c, const std::string& what) {
    if (layout.curveProblems[c].empty()) layout.curveProblems[c] = what;
  };
  for (size_t c = 0; c < layout.curves.size(); ++c) {
    // Running along a boundary that is a geodesic (the Great Court's rectangle at its eave height,
    // the Lilium's vertical base) is no wrap; bending round the boundary or a hole is.
    const auto& curve = layout.curves[c];
    const double wrap = boundaryWrapTurning(surface, curve.positions, curve.bendVertices);
    if (wrap <= options.patch.boundaryWrapToleranceRad) continue;
    int at = curve.bendVertices.front();
    for (int v : curve.bendVertices)
      if (surface.is_boundary(TriMesh::VertexHandle(v))) at = v;
    problem(c, fmt::format("the side from corner {} to corner {} wraps around the surface boundary "
                           "or a hole near {} (it turns {:.3g} rad "
                           "round it): it is not a geodesic there",
                           curve.from, curve.to,
                           format(toEigen(surface.point(TriMesh::VertexHandle(at)))), wrap));
  }
  std::map<int, int> cornerOfVertex;  // corners some patch uses (an unused corner may lie anywhere)
  for (const auto& q : layout.patches)
    for (int k : q) cornerOfVertex[layout.cornerVertex[k]] = k;
  std::map<int, int> curveOfVertex;
  for (size_t c = 0; c < layout.curves.size(); ++c) {
    const auto& corners = layout.curves[c].corners;
    for (int v : layout.mesh.chains[c]) {
      if (auto it = cornerOfVertex.find(v); it != cornerOfVertex.end()) {
        if (!std::count(corners.begin(), corners.end(), it->second))
          problem(c, fmt::format("the side from corner {} to corner {} runs through corner {}",
                                 layout.curves[c].from, layout.curves[c].to, it->second));
        continue;
      }
      auto [it, inserted] = curveOfVertex.emplace(v, static_cast<int>(c));
      if (!inserted && it->second != static_cast<int>(c)) {
        const auto& other = layout.curves[it->second];
        const std::string what =
            fmt::format("the sides {}-{} and {}-{} cross at {}", other.from, other.to,
                        layout.curves[c].from, layout.curves[c].to, format(vertexPosition(v)));
        problem(c, what);
        problem(it->second, what);
        const int first = it->second;  // a plain int: a lambda may not capture a binding (clang 14)
        const auto seen = std::find_if(
            layout.crossings.begin(), layout.crossings.end(), [&](const PatchLayout::Crossing& x) {
              return x.curveA == first && x.curveB == static_cast<int>(c);
            });
        if (seen == layout.crossings.end())
          layout.crossings.push_back({first, static_cast<int>(c), vertexPosition(v)});
      }
    }
  }

  // Segments: each curve's chain cut at its corners.
  layout.segments.clear();
  std::vector<std::vector<int>> segmentsOfCurve(layout.curves.size());
  for (size_t c = 0; c < layout.curves.size(); ++c) {
    const auto& chain = layout.mesh.chains[c];
    const auto& corners = layout.curves[c].corners;
    size_t at = 0;
    std::vector<size_t> cuts;
    for (int corner : corners) {
      const int v = layout.cornerVertex[corner];
      while (at < chain.size() && chain[at] != v) ++at;
      if (at == chain.size())
        throw SolverFailure(
            fmt::format("layout: corner {} is not on the side from corner {} to corner {}", corner,
                        layout.curves[c].from, layout.curves[c].to));
      cuts.push_back(at);
    }
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
      LayoutSegment seg;
      seg.curve = static_cast<int>(c), seg.from = corners[i], seg.to = corners[i + 1];
      seg.chain.assign(chain.begin() + cuts[i], chain.begin() + cuts[i + 1] + 1);
      seg.arcLength.push_back(0.0);
      for (size_t j = 1; j < seg.chain.size(); ++j)
        seg.arcLength.push_back(
            seg.arcLength.back() +
            (vertexPosition(seg.chain[j]) - vertexPosition(seg.chain[j - 1])).norm());
      seg.length = seg.arcLength.back();
      segmentsOfCurve[c].push_back(static_cast<int>(layout.segments.size()));
      layout.segments.push_back(std::move(seg));
    }
  }

  // Patch sides as segments.
  layout.patchSides.assign(layout.patches.size(), {});
  for (size_t p = 0; p < layout.patches.size(); ++p)
    for (int k = 0; k < 4; ++k) {
      const int a = layout.patches[p][k], b = layout.patches[p][(k + 1) % 4];
      bool found = false;
      for (size_t c = 0; c < layout.curves.size() && !found; ++c) {
        const auto& corners = layout.curves[c].corners;
        const auto ia = std::find(corners.begin(), corners.end(), a),
                   ib = std::find(corners.begin(), corners.end(), b);
        if (ia == corners.end() || ib == corners.end()) continue;
        found = true;
        const long i = ia - corners.begin(), j = ib - corners.begin();
        if (i < j)
          for (long s = i; s < j; ++s)
            layout.patchSides[p][k].emplace_back(segmentsOfCurve[c][s], false);
        else
          for (long s = i - 1; s >= j; --s)
            layout.patchSides[p][k].emplace_back(segmentsOfCurve[c][s], true);
      }
      if (!found)
        throw InvalidInput(
            fmt::format("patch {}: no side of the layout joins corners {} and {}", p, a, b));
    }
}

std::vector<PatchOverlap> crossingPatches(const PatchLayout& layout) {
  std::vector<std::set<int>> curvesOf(layout.patches.size());
  for (size_t p = 0; p < layout.patchSides.size(); ++p)
    for (const PatchSideSegments& side : layout.patchSides[p])
      for (const auto& piece : side) curvesOf[p].insert(layout.segments[piece.first].curve);
  std::vector<PatchOverlap> out;
  std::set<std::pair<int, int>> pairs;
  for (const auto& x : layout.crossings)
    for (size_t a = 0; a < curvesOf.size(); ++a)
      for (size_t b = a + 1; b < curvesOf.size(); ++b) {
        const bool across = (curvesOf[a].count(x.curveA) && curvesOf[b].count(x.curveB)) ||
                            (curvesOf[a].count(x.curveB) && curvesOf[b].count(x.curveA));
        // Sides of one patch crossing each other: that patch is twisted, not overlapping.
        const bool ownA = curvesOf[a].count(x.curveA) && curvesOf[a].count(x.curveB);
        const bool ownB = curvesOf[b].count(x.curveA) && curvesOf[b].count(x.curveB);
        if (!across || ownA || ownB || !pairs.insert({int(a), int(b)}).second) continue;
        const auto& ca = layout.curves[x.curveA];
        const auto& cb = layout.curves[x.curveB];
        out.push_back({static_cast<int>(a), static_cast<int>(b),
                       fmt::format("their sides {}-{} and {}-{} cross at {}", ca.from, ca.to,
                                   cb.from, cb.to, format(x.at))});
      }
  return out;
}

std::vector<PatchOverlap> overlapFaces(const PatchLayout& layout,
                                       const std::vector<std::vector<int>>& patchFaces) {
  const TriMesh& mesh = layout.mesh.mesh;
  std::vector<int> owner(mesh.n_faces(), -1);
  std::map<std::pair<int, int>, double> shared;  // (a, b) -> area
  for (size_t p = 0; p < patchFaces.size(); ++p)
    for (int f : patchFaces[p]) {
      if (f < 0 || f >= static_cast<int>(owner.size())) continue;
      if (owner[f] >= 0 && owner[f] != static_cast<int>(p))
        shared[{owner[f], static_cast<int>(p)}] += mesh.calc_face_area(TriMesh::FaceHandle(f));
      else
        owner[f] = static_cast<int>(p);
    }
  std::vector<PatchOverlap> out;
  for (const auto& [pair, area] : shared)
    out.push_back({pair.first, pair.second, fmt::format("they share {:.3g} m² of surface", area)});
  return out;
}

}  // namespace egg::patching
