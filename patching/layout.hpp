#pragma once
// A patch layout (Sections 3.3, 3.4): corners on the design surface, the sides between them, each
// the shortest geodesic between two corners traced ONCE on the surface, and the patches (four
// corners each, in order). Two patches that share a side use the one polyline; a corner lying on
// another patch's side (a T-junction) splits that side into segments, which are pieces of the same
// traced curve. The layout mesh (layout_mesh.hpp) holds every side as an edge chain, and each
// patch is cut from it in O(patch).
#include "core/egg/patch.hpp"
#include "patching/layout_mesh.hpp"

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace egg::geodesic {
class DistanceSolver;
}

namespace egg::patching {

struct LayoutOptions {
  PatchOptions
      patch;  // corner snapping, criterion (iv) margin, straight-boundary tolerance, merging
  void validate() const;
};

// One traced shortest geodesic between two corners of the layout; it may carry further corners
// (T-junctions) along it, which cut it into segments.
struct LayoutCurve {
  int from = -1, to = -1;            // corner ids at its ends
  std::vector<SurfacePoint> points;  // on the surface, from -> to (T corners included)
  std::vector<Eigen::Vector3d> positions;
  std::vector<int> corners;       // corner ids along it, in order, from ... to
  std::vector<int> bendVertices;  // surface vertices it bends at
  double length = 0.0;
};

// A piece of a curve between two consecutive corners on it: the unit patches share.
struct LayoutSegment {
  int curve = -1;
  int from = -1, to = -1;         // corner ids, in the curve's direction
  std::vector<int> chain;         // layout-mesh vertices, from -> to
  std::vector<double> arcLength;  // cumulative along the chain (metres)
  double length = 0.0;
};

// Side k of a patch (corner k -> corner k+1) as segments: (segment id, reversed).
using PatchSideSegments = std::vector<std::pair<int, bool>>;

struct PatchLayout {
  const TriMesh* surface = nullptr;
  std::vector<SurfacePoint> cornerPoints;  // on the surface
  std::vector<Eigen::Vector3d> corners;    // positions
  std::vector<double>
      cornerOffsets;  // how far each requested corner was moved (snapping, T-junctions)
  std::vector<LayoutCurve> curves;
  std::vector<std::array<int, 4>> patches;  // corner ids in order around each patch
  // Derived by finishLayout:
  LayoutMesh mesh;
  std::vector<int> cornerVertex;  // corner -> layout-mesh vertex
  std::vector<LayoutSegment> segments;
  std::vector<std::array<PatchSideSegments, 4>> patchSides;
  std::vector<std::string> curveProblems;  // per curve: why it cannot bound a patch ("" = fine)
  struct Crossing {
    int curveA = -1, curveB = -1;
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
  };
  std::vector<Crossing> crossings;  // curves that cross away from a corner, each pair once
  int propagations = 0;             // traces spent
  double seconds = 0.0;
};

// From given corners and quads of corner indices (the scene's layout). A side (a, b) of one patch
// that another side path a - t - b (of other patches) runs along makes t a T-junction on the
// curve a - b: t is moved onto it. Throws InvalidInput naming the corner or patch for corners off
// the surface, repeated corners in a patch, or a quad that uses an edge twice.
PatchLayout makeLayout(const TriMesh& surface, const geodesic::DistanceSolver& surfaceSolver,
                       const std::vector<Eigen::Vector3d>& corners,
                       const std::vector<std::array<int, 4>>& patches,
                       const LayoutOptions& options = {});

// Corner on curve `curve` at arc length `s` (a new T-junction; the curve is not retraced).
int addCornerOnCurve(PatchLayout& layout, int curve, double arcLength);
// A new corner inside the surface (for a split at a peak).
int addCorner(PatchLayout& layout, const SurfacePoint& point);
// A new curve traced between two corners.
int addCurve(PatchLayout& layout, const geodesic::DistanceSolver& surfaceSolver, int from, int to,
             const LayoutOptions& options);

// Builds the layout mesh, the segments and the patch sides; records curve problems (sides that
// cross, wrap around a hole). Throws InvalidInput for a patch side no curve carries.
void finishLayout(PatchLayout& layout, const LayoutOptions& options);

// Two patches that overlap: their sides cross away from a corner, or (overlapFaces) they share
// surface between their sides.
struct PatchOverlap {
  int a = -1, b = -1;  // patch ids, a < b
  std::string what;    // "their sides 1-2 and 4-5 cross at (x, y, z)", "they share 2.1 m²"
};
// Pairs of distinct patches whose sides cross (finishLayout's crossings; sides of one patch that
// cross each other make that patch infeasible, not an overlap).
std::vector<PatchOverlap> crossingPatches(const PatchLayout& layout);
// Pairs of patches that share layout-mesh faces (`patchFaces[p]`: LayoutPatch::layoutFace, empty
// when not cut), with the area they share.
std::vector<PatchOverlap> overlapFaces(const PatchLayout& layout,
                                       const std::vector<std::vector<int>>& patchFaces);

// The layout's patch `index` cut from the layout mesh: its sides are the layout's chains. Throws
// InfeasiblePatch (sides that cross or leave the surface, a hole inside, criterion iv).
struct LayoutPatch {
  Patch patch;
  std::vector<int> layoutVertex;  // per patch vertex: layout-mesh vertex
  std::vector<int> surfaceFace;   // per patch face: the surface face it lies in
  std::vector<int> layoutFace;    // per patch face: layout-mesh face
};
LayoutPatch cutLayoutPatch(const PatchLayout& layout, int index, const LayoutOptions& options = {});

// Point of a curve at arc length s (on the surface) and the arc length of the curve's point nearest
// to `p`.
SurfacePoint curvePoint(const PatchLayout& layout, int curve, double arcLength);
double nearestArcLength(const PatchLayout& layout, int curve, const Eigen::Vector3d& p);

}  // namespace egg::patching
