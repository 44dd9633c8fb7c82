// Backtracing shortest paths through the windows of an exact propagation, and the small surface
// point helpers (vertex points, closest point on the surface).
//
// A window's rays are straight in the unfolding, so the path from a target back to the source is:
// the ray from the target to the window's source image, crossing the window's edge; then the same
// ray continued through the parent window's face (same image, earlier edge), and so on until the
// window born at a (pseudo-)source. At a pseudo-source vertex the path bends and continues with
// whatever gave that vertex its distance. A point whose distance came from bending at the vertex
// X on a window end's boundary ray (Predecessor::BentAtVertex) is traced along the straight
// segment to X's place on the ray first, through the same window chain, then on along the ray.
// Section 4.5.2 avoids tracing for intersections; the members themselves and the tests still need
// the polyline.
#include "core/errors.hpp"
#include "core/geodesic/window_geometry.hpp"
#include "core/geodesic/window_propagation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace egg::geodesic {

namespace detail {
namespace {

SurfacePoint edgePoint(const MeshTables& t, int h, double x) {
  const int f = t.he[h].face;
  const double L = t.he[h].length;
  const double s = std::clamp(x / L, 0.0, 1.0);
  SurfacePoint p;
  p.face = f;
  for (int i = 0; i < 3; ++i) {
    if (t.faceVerts[f][i] == t.he[h].fromVertex) p.barycentric[i] = 1.0 - s;
    if (t.faceVerts[f][i] == t.he[h].toVertex) p.barycentric[i] = s;
  }
  return p;
}

// The point (x, y) of the frame of halfedge h (inside its face) as a surface point.
SurfacePoint framePoint(const MeshTables& t, int h, double x, double y) {
  const auto& e = t.he[h];
  const double wc = std::clamp(y / e.oppositeY, 0.0, 1.0);
  const double wb = std::clamp((x - wc * e.oppositeX) / e.length, 0.0, 1.0 - wc);
  SurfacePoint p;
  p.face = e.face;
  for (int i = 0; i < 3; ++i) {
    const int v = t.faceVerts[e.face][i];
    p.barycentric[i] = v == e.fromVertex ? 1.0 - wb - wc : v == e.toVertex ? wb : wc;
  }
  return p;
}

// From the frame of a child window's halfedge to its parent's (the child's edge is an edge of the
// parent's face): rigid, the inverse of the propagation's FrameChange.
void toParentFrame(const MeshTables& t, int child, int parent, double& x, double& y) {
  const int tw = t.twin(child);
  const double bx = t.he[parent].length, cx = t.he[parent].oppositeX, cy = t.he[parent].oppositeY;
  const double length = t.he[tw].length;
  // The child's frame: origin at its from-vertex (C, or A at the parent's origin), x along its
  // edge.
  const bool fromC = tw == t.he[parent].next;
  const double ox = fromC ? cx : 0.0, oy = fromC ? cy : 0.0;
  const double dx = fromC ? (bx - cx) / length : cx / length,
               dy = fromC ? -cy / length : cy / length;
  const double px = ox + x * dx - y * dy, py = oy + x * dy + y * dx;
  x = px;
  y = py;
}

SurfacePoint vertexPointFromTables(const MeshTables& t, int v) {
  for (int k = t.outgoingStart[v]; k < t.outgoingStart[v + 1]; ++k) {
    const int h = t.outgoing[k];
    if (t.he[h].face < 0) continue;
    SurfacePoint p;
    p.face = t.he[h].face;
    for (int i = 0; i < 3; ++i) p.barycentric[i] = (t.faceVerts[p.face][i] == v) ? 1.0 : 0.0;
    return p;
  }
  throw InvalidInput("geodesic: vertex " + std::to_string(v) + " belongs to no face");
}

class Tracer {
 public:
  Tracer(const MeshTables& t, const Propagation& s) : t_(t), s_(s) {}

  std::vector<SurfacePoint> reversed;  // from the target back towards the source
  std::vector<int> bends;

  void fromVertex(int v) {
    // Each step moves to a strictly closer predecessor; the guard only protects against a
    // corrupted state turning into an endless loop.
    for (int guard = 0; guard <= t_.vertexCount; ++guard) {
      reversed.push_back(vertexPointFromTables(t_, v));
      bends.push_back(v);
      const Predecessor pred = s_.vertexPredecessor[v];
      if (pred.kind == Predecessor::Vertex) {
        v = pred.index;
        continue;
      }
      if (pred.kind == Predecessor::ThroughWindow || pred.kind == Predecessor::BentAtVertex) {
        const int h = s_.windows[pred.index].halfedge;
        fromWindow(pred, t_.he[h].oppositeX, t_.he[h].oppositeY);
      }
      return;  // Source (or None for an unreachable vertex)
    }
    throw SolverFailure("geodesic: path backtracing did not reach the source");
  }

  // (qx, qy): the current path point in the frame of the predecessor window's halfedge (inside
  // its face). A bent path runs straight to the bend point (bx, by) first: its crossings with the
  // window chain's edges, until the bend point lies in the current window's face.
  void fromWindow(Predecessor pred, double qx, double qy) {
    int wi = pred.index;
    if (pred.kind == Predecessor::BentAtVertex) {
      const Window& w0 = s_.windows[wi];
      const int x = w0.endVertex[static_cast<int>(pred.side)];
      double bx, by;
      bendPoint(w0, pred.side, s_.vertexDistance[x], bx, by);
      for (;;) {
        const Window& w = s_.windows[wi];
        const int h = w.halfedge;
        const double L = t_.he[h].length;
        if (by >= -1e-12 * L || w.isRoot()) {
          // The bend is in this face, or on its edge (then it is the vertex X).
          if (std::abs(by) <= 1e-12 * L) {
            reversed.push_back(edgePoint(t_, h, bx));
            if (std::min(bx, L - bx) <= 1e-9 * L) bends.push_back(x);
          } else {
            reversed.push_back(framePoint(t_, h, bx, by));
          }
          qx = bx;
          qy = by;
          break;
        }
        if (qy > 1e-12 * L) {
          qx = std::clamp(qx + (bx - qx) * qy / (qy - by), 0.0, L);
          reversed.push_back(edgePoint(t_, h, qx));
        }
        qy = 0.0;
        toParentFrame(t_, h, s_.windows[w.parent].halfedge, qx, qy);
        toParentFrame(t_, h, s_.windows[w.parent].halfedge, bx, by);
        wi = w.parent;
      }
    }
    fromWindow(wi, qx, qy);
  }

  // (qx, qy): the current path point in the frame of window `wi`'s halfedge (inside its face).
  void fromWindow(int wi, double qx, double qy) {
    for (;;) {
      const Window& w = s_.windows[wi];
      const int h = w.halfedge;
      const double L = t_.he[h].length;
      double x = qx;
      if (qy > 1e-12 * L) x = w.sx + (qx - w.sx) * (-w.sy) / (qy - w.sy);
      x = std::clamp(x, std::max(0.0, w.b0), std::min(L, w.b1));
      if (qy > 1e-12 * L) reversed.push_back(edgePoint(t_, h, x));
      if (w.isRoot()) {
        if (w.rootVertex() >= 0) fromVertex(w.rootVertex());
        return;
      }
      const Window& p = s_.windows[w.parent];
      const int hp = p.halfedge;
      const int tw = t_.twin(h);
      const double u = (L - x) / L;  // fraction along tw from its from-vertex
      const double bx = t_.he[hp].length, cx = t_.he[hp].oppositeX, cy = t_.he[hp].oppositeY;
      if (tw == t_.he[hp].next) {  // B -> C
        qx = bx + u * (cx - bx);
        qy = u * cy;
      } else {  // C -> A
        qx = cx - u * cx;
        qy = cy - u * cy;
      }
      wi = w.parent;
    }
  }

 private:
  const MeshTables& t_;
  const Propagation& s_;
};

}  // namespace

GeodesicPath tracePath(const MeshTables& t, const Propagation& s, int targetIndex,
                       const SurfacePoint& source, const SurfacePoint& target) {
  GeodesicPath path;
  if (!(s.targetDistance[targetIndex] < kInfinity)) {
    path.length = kInfinity;
    return path;
  }
  Tracer tracer(t, s);
  tracer.reversed.push_back(target);
  const Predecessor pred = s.targetPredecessor[targetIndex];
  if (pred.kind == Predecessor::Vertex) {
    tracer.fromVertex(pred.index);
  } else if (pred.kind == Predecessor::ThroughWindow || pred.kind == Predecessor::BentAtVertex) {
    const Window& w = s.windows[pred.index];
    const int f = t.he[w.halfedge].face;
    const int h = w.halfedge;
    const Eigen::Vector3d& wt = s.targetWeights[targetIndex];
    double qx = 0, qy = 0;
    for (int i = 0; i < 3; ++i) {
      const int v = t.faceVerts[f][i];
      if (v == t.he[h].toVertex) qx += wt[i] * t.he[h].length;
      if (v == t.he[h].oppositeVertex) {
        qx += wt[i] * t.he[h].oppositeX;
        qy += wt[i] * t.he[h].oppositeY;
      }
    }
    tracer.fromWindow(pred, qx, qy);
  }
  tracer.reversed.push_back(source);
  // Source first; drop repeated points (a vertex source is also the end of the vertex chain).
  std::reverse(tracer.reversed.begin(), tracer.reversed.end());
  const double tiny = 1e-12 * std::max(1.0, t.meanEdgeLength);
  for (const auto& p : tracer.reversed) {
    const Eigen::Vector3d x = t.pointIn(p.face, p.barycentric);
    if (!path.positions.empty() && (x - path.positions.back()).norm() <= tiny) {
      if (&p == &tracer.reversed.back()) path.points.back() = p;  // keep the exact target
      continue;
    }
    if (!path.positions.empty()) path.length += (x - path.positions.back()).norm();
    path.points.push_back(p);
    path.positions.push_back(x);
  }
  for (auto it = tracer.bends.rbegin(); it != tracer.bends.rend(); ++it) {
    if (*it != s.sourceVertex) path.bendVertices.push_back(*it);
  }
  return path;
}

}  // namespace detail

SurfacePoint vertexPoint(const TriMesh& mesh, int vertex) {
  if (vertex < 0 || vertex >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInput("geodesic: vertex " + std::to_string(vertex) + " is out of range");
  }
  for (auto fh : mesh.vf_range(TriMesh::VertexHandle(vertex))) {
    SurfacePoint p;
    p.face = fh.idx();
    const auto ids = faceVertices(mesh, p.face);
    for (int i = 0; i < 3; ++i) p.barycentric[i] = (ids[i] == vertex) ? 1.0 : 0.0;
    return p;
  }
  throw InvalidInput("geodesic: vertex " + std::to_string(vertex) + " belongs to no face");
}

SurfacePoint snapToSurface(const TriMesh& mesh, const Eigen::Vector3d& point) {
  if (mesh.n_faces() == 0)
    throw InvalidInput("geodesic: cannot snap a point to a mesh without faces");
  if (!point.allFinite())
    throw InvalidInput("geodesic: cannot snap a non-finite point to the surface");
  SurfacePoint best;
  double bestDistance = detail::kInfinity;
  for (auto fh : mesh.faces()) {
    const auto ids = faceVertices(mesh, fh.idx());
    const Eigen::Vector3d a = toEigen(mesh.point(TriMesh::VertexHandle(ids[0])));
    const Eigen::Vector3d b = toEigen(mesh.point(TriMesh::VertexHandle(ids[1])));
    const Eigen::Vector3d c = toEigen(mesh.point(TriMesh::VertexHandle(ids[2])));
    const Eigen::Vector3d w = closestPointBarycentric(point, a, b, c);
    const double d = (w[0] * a + w[1] * b + w[2] * c - point).squaredNorm();
    if (d < bestDistance) {
      bestDistance = d;
      best.face = fh.idx();
      best.barycentric = w;
    }
  }
  return best;
}

}  // namespace egg::geodesic
