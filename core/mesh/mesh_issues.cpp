// The names of mesh issues and the queries of a check's result (validate.hpp); the checks
// themselves are in validate.cpp.
#include "core/mesh/validate.hpp"

namespace egg {

std::string toString(MeshIssueKind kind) {
  switch (kind) {
    case MeshIssueKind::Empty: return "empty";
    case MeshIssueKind::IndexOutOfRange: return "index_out_of_range";
    case MeshIssueKind::NonFiniteVertex: return "non_finite_vertex";
    case MeshIssueKind::RepeatedVertex: return "repeated_vertex";
    case MeshIssueKind::DuplicateVertices: return "duplicate_vertices";
    case MeshIssueKind::DuplicateTriangles: return "duplicate_triangles";
    case MeshIssueKind::DegenerateFaces: return "degenerate_faces";
    case MeshIssueKind::SliverFaces: return "sliver_faces";
    case MeshIssueKind::NonManifoldEdges: return "non_manifold_edges";
    case MeshIssueKind::NonManifoldVertices: return "non_manifold_vertices";
    case MeshIssueKind::IsolatedVertices: return "isolated_vertices";
    case MeshIssueKind::SeveralComponents: return "several_components";
    case MeshIssueKind::InconsistentOrientation: return "inconsistent_orientation";
    case MeshIssueKind::NotOrientable: return "not_orientable";
  }
  return "unknown";
}

bool MeshCheckResult::has(MeshIssueKind kind) const { return find(kind) != nullptr; }

const MeshIssue* MeshCheckResult::find(MeshIssueKind kind) const {
  for (const auto& issue : issues)
    if (issue.kind == kind) return &issue;
  return nullptr;
}

bool MeshCheckResult::acceptable() const { return !hasErrors; }

std::string MeshCheckResult::summary() const {
  std::string s;
  for (const auto& issue : issues) s += (s.empty() ? "" : "\n") + issue.message;
  return s;
}

}  // namespace egg
