#pragma once
// The triangle mesh every stage works on: OpenMesh with double-precision points (the OpenMesh
// default is float, far too coarse for a 0.15 % geodesic length test, Section 2.3.3).
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <Eigen/Dense>
#include <array>
#include <vector>

namespace egg {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

inline Eigen::Vector3d toEigen(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }
inline OpenMesh::Vec3d toOpenMesh(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// A point on the surface: a face and barycentric weights of the face's three vertices, in the
// order OpenMesh's face-vertex circulator visits them (see faceVertices). Patch boundaries and
// members do not run through vertices, so most stages speak in surface points.
struct SurfacePoint {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};

// Plain arrays: what generators and importers produce, and what flat-array algorithms consume.
struct TriangleSoup {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// The three vertex indices of face f, in circulator order.
std::array<int, 3> faceVertices(const TriMesh& mesh, int face);

// Position of a surface point (barycentric combination of its face's vertices).
Eigen::Vector3d position(const TriMesh& mesh, const SurfacePoint& point);

// Builds a mesh from a soup. Throws InvalidInput naming the triangle when a triangle has an
// index out of range, repeats a vertex, or cannot be added without making the mesh non-manifold.
TriMesh meshFromSoup(const TriangleSoup& soup);

// Back to plain arrays (vertex indices are OpenMesh's vertex indices).
TriangleSoup soupFromMesh(const TriMesh& mesh);

// The point of triangle (a, b, c) closest to p, as barycentric weights of a, b, c (Ericson,
// Real-Time Collision Detection, 5.1.5). Snapping points to the surface rests on it.
Eigen::Vector3d closestPointBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(0.0);
  Eigen::Vector3d max = Eigen::Vector3d::Constant(0.0);
  Eigen::Vector3d size() const { return max - min; }
};

BoundingBox boundingBox(const TriMesh& mesh);
double surfaceArea(const TriMesh& mesh);
// Sum of the corner angles of the faces around a vertex (radians): 2 pi at a flat interior vertex,
// pi at a straight boundary vertex; a patch corner's inner angle (criterion iv).
double vertexAngleSum(const TriMesh& mesh, TriMesh::VertexHandle v);
double meanEdgeLength(const TriMesh& mesh);

// How much a polyline on the surface turns where it passes boundary vertex v, from `before` to
// `after` (points on faces round v): the angle between the two through the faces round v, less pi.
// Positive where it bends round a reflex boundary vertex (wrapping the boundary or a hole); about
// zero along a boundary that is itself a geodesic, as the Lilium's vertical base wall, whatever
// the curve does in space; negative on the inner side of a convex boundary vertex.
double geodesicTurningAtBoundary(const TriMesh& mesh, TriMesh::VertexHandle v,
                                 const Eigen::Vector3d& before, const Eigen::Vector3d& after);
// The positive turning of a polyline summed over the listed vertices it passes that lie on the
// boundary (its two ends excluded): how far it wraps round the boundary, in radians.
double boundaryWrapTurning(const TriMesh& mesh, const std::vector<Eigen::Vector3d>& polyline,
                           const std::vector<int>& vertices);

}  // namespace egg
