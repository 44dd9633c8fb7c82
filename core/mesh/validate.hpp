#pragma once
// Validation and repair of an input surface (docs/architecture.md "Stage table", row "surface";
// thesis 4.4.1: "our system works with triangular meshes"). Everything downstream (cotangent
// Laplacians, heat-method distances, angle-defect curvature) silently produces garbage on NaN
// coordinates, zero-area faces or non-manifold edges, so we reject such input here with a message
// that names the vertex, triangle or edge, and repair only what can be repaired without changing
// the design surface.
//
// checkMesh works on the TriangleSoup an importer or generator produced (OpenMesh refuses some
// non-manifold configurations outright, so they must be found before a TriMesh exists).
#include "core/mesh/mesh.hpp"

#include <string>
#include <vector>

namespace egg {

enum class ComponentPolicy {
  Reject,       // several connected components are an error
  KeepLargest,  // keep the component with the largest area, warn about the rest
};

struct MeshCheckOptions {
  // Vertices closer than this fraction of the bounding-box diagonal are the same vertex (STL
  // stores each triangle corner separately; float round-off of ~1e-7 must still merge).
  double mergeToleranceRelative = 1e-7;
  // Repair: merge duplicate vertices (then drop collapsed and repeated triangles).
  bool mergeDuplicateVertices = true;
  // Repair: drop vertices no triangle uses (importers keep stray points, e.g. OBJ "v" lines).
  bool dropUnreferencedVertices = true;
  // Repair: flip triangles so neighbours agree on orientation (lossless on an orientable surface).
  bool fixOrientation = false;
  // What to do with several connected components.
  ComponentPolicy components = ComponentPolicy::Reject;
  // A face is degenerate (zero area) below this fraction of the squared mean edge length.
  double degenerateAreaRelative = 1e-12;
  // A face is a sliver when its smallest angle is below this (radians, ~0.057 degrees): cotangent
  // weights of such faces exceed ~1000 and wreck Laplacians.
  double sliverMinAngleRad = 1e-3;
  // Sliver faces are an error (true) or only reported (false).
  bool rejectSlivers = true;
  // At most this many elements are named in one message (the count is always given).
  int maxNamedElements = 5;

  void validate() const;  // throws InvalidInput naming the field
};

enum class MeshIssueKind {
  Empty,                    // no triangles or no vertices
  IndexOutOfRange,          // a triangle refers to a vertex that does not exist
  NonFiniteVertex,          // NaN or infinite coordinate
  RepeatedVertex,           // a triangle uses the same vertex twice
  DuplicateVertices,        // distinct vertices at the same place (within the merge tolerance)
  DuplicateTriangles,       // two triangles on the same three vertices
  DegenerateFaces,          // zero area
  SliverFaces,              // smallest angle below the threshold
  NonManifoldEdges,         // an edge shared by more than two triangles
  NonManifoldVertices,      // a vertex whose triangles form several fans (bow tie)
  IsolatedVertices,         // vertices no triangle uses
  SeveralComponents,        // more than one connected component
  InconsistentOrientation,  // neighbouring triangles run their shared edge the same way
  NotOrientable,            // no consistent orientation exists (Moebius strip)
};

std::string toString(MeshIssueKind kind);

struct MeshIssue {
  MeshIssueKind kind = MeshIssueKind::Empty;
  int count = 0;            // how many elements are affected
  bool repairable = false;  // prepareMesh fixes it with the given options (reported as a warning)
  std::string message;      // names the elements (vertex / triangle / edge indices of the soup)
};

struct MeshCheckResult {
  std::vector<MeshIssue> issues;  // in the order of the checks
  int vertices = 0;               // in the input soup
  int triangles = 0;              // in the input soup
  int verticesAfterRepair = 0;
  int trianglesAfterRepair = 0;
  int components = 0;
  int boundaryEdges = 0;
  double meanEdgeLengthM = 0.0;
  double minFaceAreaM2 = 0.0;
  double minAngleRad = 0.0;  // smallest triangle angle found
  int worstFace = -1;        // triangle with that smallest angle (input numbering)
  bool hasErrors = false;    // an issue prepareMesh would refuse
  double seconds = 0.0;

  bool has(MeshIssueKind kind) const;
  const MeshIssue* find(MeshIssueKind kind) const;
  // True when no issue is left that prepareMesh would refuse.
  bool acceptable() const;
  // All issue messages, one per line.
  std::string summary() const;
};

// Checks a soup and reports every issue with counts and named elements. Never throws on a bad
// mesh (only on bad options).
MeshCheckResult checkMesh(const TriangleSoup& soup, const MeshCheckOptions& options = {});

struct MeshRepairDiagnostics {
  int mergedVertices = 0;
  int droppedCollapsedTriangles = 0;
  int droppedDuplicateTriangles = 0;
  int droppedUnreferencedVertices = 0;
  int droppedComponentTriangles = 0;
  int removedComponents = 0;
  int flippedTriangles = 0;
  std::vector<std::string> warnings;  // what was repaired or dropped, in words
  MeshCheckResult check;              // the check of the repaired soup
  double seconds = 0.0;
};

// Repairs what the options allow (merge duplicates, drop collapsed/duplicate triangles and
// unreferenced vertices, keep the largest component, fix orientation), checks the result and
// builds the TriMesh. Throws InvalidInput listing every remaining issue (naming elements)
// otherwise.
TriMesh prepareMesh(TriangleSoup soup, const MeshCheckOptions& options,
                    MeshRepairDiagnostics& diagnostics);

}  // namespace egg
