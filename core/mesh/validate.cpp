#include "core/mesh/validate.hpp"

#include "core/errors.hpp"
#include "core/mesh/soup_repair.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace egg {
namespace {

enum class Severity { Repaired, Warning, Error };

// The soup being repaired, with the input index of every current vertex and triangle, so that
// messages name elements as the user's file numbers them (0-based).
struct WorkingSoup {
  TriangleSoup soup;
  std::vector<int> vertexOrigin;
  std::vector<int> triangleOrigin;

  void applyVertexMap(const std::vector<int>& oldToNew) {
    std::vector<int> origin(soup.vertices.size(), -1);
    for (size_t i = 0; i < oldToNew.size(); ++i) {
      const int k = oldToNew[i];
      if (k >= 0 && origin[k] < 0) origin[k] = vertexOrigin[i];
    }
    vertexOrigin = std::move(origin);
  }
  void applyTriangleSelection(const std::vector<int>& kept) {
    std::vector<int> origin(kept.size());
    for (size_t j = 0; j < kept.size(); ++j) origin[j] = triangleOrigin[kept[j]];
    triangleOrigin = std::move(origin);
  }
};

std::string formatNumber(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// NaN printed as "nan" (iostreams print "-nan" for a NaN with the sign bit set), inf as "inf".
std::string formatCoordinate(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.precision(9);
  s << x;
  return s.str();
}

std::string formatPoint(const Eigen::Vector3d& p) {
  return "(" + formatCoordinate(p.x()) + ", " + formatCoordinate(p.y()) + ", " +
         formatCoordinate(p.z()) + ")";
}

class Checker {
 public:
  Checker(WorkingSoup& work, const MeshCheckOptions& options, MeshCheckResult& result,
          MeshRepairDiagnostics& diagnostics)
      : w_(work), o_(options), r_(result), d_(diagnostics) {}

  void run();

 private:
  std::string vertexName(int v) const {
    return "vertex " + std::to_string(w_.vertexOrigin[v]) + " at " +
           formatPoint(w_.soup.vertices[v]);
  }
  std::string triangleName(int t) const {
    const auto& tri = w_.soup.triangles[t];
    return "triangle " + std::to_string(w_.triangleOrigin[t]) + " (vertices " +
           std::to_string(w_.vertexOrigin[tri[0]]) + ", " +
           std::to_string(w_.vertexOrigin[tri[1]]) + ", " +
           std::to_string(w_.vertexOrigin[tri[2]]) + ")";
  }
  std::string edgeName(int a, int b) const {
    if (w_.vertexOrigin[a] > w_.vertexOrigin[b]) std::swap(a, b);
    return "edge (" + std::to_string(w_.vertexOrigin[a]) + ", " +
           std::to_string(w_.vertexOrigin[b]) + ")";
  }
  // "a, b, c and 12 more"
  std::string list(const std::vector<std::string>& names, int total) const {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i) s += (i ? "; " : "") + names[i];
    if (total > static_cast<int>(names.size()))
      s += "; and " + std::to_string(total - names.size()) + " more";
    return s;
  }
  void add(MeshIssueKind kind, int count, Severity severity, const std::string& message) {
    MeshIssue issue;
    issue.kind = kind;
    issue.count = count;
    issue.repairable = severity == Severity::Repaired;
    issue.message = message;
    r_.issues.push_back(issue);
    if (severity == Severity::Error) errors_.push_back(kind);
    if (severity != Severity::Error) d_.warnings.push_back(message);
  }

  bool checkIndices();
  void mergeDuplicates(double tolerance);
  void handleComponents();
  void handleIsolatedVertices();
  void checkFinite();
  void checkFaceShapes();
  void checkEdgesAndOrientation();
  void checkVertexFans();

  WorkingSoup& w_;
  const MeshCheckOptions& o_;
  MeshCheckResult& r_;
  MeshRepairDiagnostics& d_;
  std::vector<MeshIssueKind> errors_;
};

bool Checker::checkIndices() {
  const int n = static_cast<int>(w_.soup.vertices.size());
  std::vector<std::string> named;
  int bad = 0;
  for (size_t t = 0; t < w_.soup.triangles.size(); ++t) {
    const auto& tri = w_.soup.triangles[t];
    if (std::all_of(tri.begin(), tri.end(), [&](int v) { return v >= 0 && v < n; })) continue;
    if (++bad <= o_.maxNamedElements)
      named.push_back("triangle " + std::to_string(t) + " (" + std::to_string(tri[0]) + ", " +
                      std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")");
  }
  if (bad == 0) return true;
  add(MeshIssueKind::IndexOutOfRange, bad, Severity::Error,
      std::to_string(bad) + " triangle(s) refer to vertices that do not exist (there are " +
          std::to_string(n) + " vertices): " + list(named, bad));
  return false;
}

void Checker::mergeDuplicates(double tolerance) {
  // Triangles that repeat a vertex in the input itself.
  std::vector<std::string> repeated;
  int repeatedCount = 0;
  for (size_t t = 0; t < w_.soup.triangles.size(); ++t) {
    const auto& tri = w_.soup.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      if (++repeatedCount <= o_.maxNamedElements)
        repeated.push_back(triangleName(static_cast<int>(t)));
  }
  if (o_.mergeDuplicateVertices) {
    // Bitwise-equal copies are how OBJ (through the importer) and STL store a vertex that faces
    // share, not a defect: merged first and silently. Only the near-duplicates left within the
    // tolerance are reported (issue 39: a clean 961-vertex OBJ warned of 4,439 merges).
    std::vector<int> exactToNew;
    const int exact = mergeDuplicateVertices(w_.soup, 0.0, &exactToNew);
    w_.applyVertexMap(exactToNew);
    std::vector<int> oldToNew, kept;
    const int merged = mergeDuplicateVertices(w_.soup, tolerance, &oldToNew);
    w_.applyVertexMap(oldToNew);
    const auto [collapsed, duplicates] = dropCollapsedAndDuplicateTriangles(w_.soup, &kept);
    w_.applyTriangleSelection(kept);
    d_.mergedVertices = exact + merged;
    d_.droppedCollapsedTriangles = collapsed;
    d_.droppedDuplicateTriangles = duplicates;
    std::ostringstream tol;
    tol << tolerance;
    if (merged > 0)
      add(MeshIssueKind::DuplicateVertices, merged, Severity::Repaired,
          "merged " + std::to_string(merged) + " duplicate vertices (tolerance " + tol.str() +
              " m)");
    if (collapsed > 0)
      add(MeshIssueKind::RepeatedVertex, collapsed, Severity::Repaired,
          "dropped " + std::to_string(collapsed) + " collapsed triangle(s) that repeat a vertex" +
              (repeatedCount ? " (in the input: " + list(repeated, repeatedCount) + ")"
                             : std::string()));
    if (duplicates > 0)
      add(MeshIssueKind::DuplicateTriangles, duplicates, Severity::Repaired,
          "dropped " + std::to_string(duplicates) + " duplicate triangle(s)");
    return;
  }
  // No merging allowed: report what merging would have fixed as errors.
  if (repeatedCount > 0)
    add(MeshIssueKind::RepeatedVertex, repeatedCount, Severity::Error,
        std::to_string(repeatedCount) +
            " triangle(s) repeat a vertex: " + list(repeated, repeatedCount));
  TriangleSoup copy = w_.soup;
  std::vector<int> oldToNew;
  const int merged = mergeDuplicateVertices(copy, tolerance, &oldToNew);
  if (merged > 0) {
    std::vector<std::string> pairs;
    std::vector<int> firstOf(copy.vertices.size(), -1);
    int shown = 0;
    for (size_t i = 0; i < oldToNew.size(); ++i) {
      int& first = firstOf[oldToNew[i]];
      if (first < 0)
        first = static_cast<int>(i);
      else if (shown++ < o_.maxNamedElements)
        pairs.push_back(vertexName(static_cast<int>(i)) + " duplicates vertex " +
                        std::to_string(w_.vertexOrigin[first]));
    }
    add(MeshIssueKind::DuplicateVertices, merged, Severity::Error,
        std::to_string(merged) +
            " duplicate vertices (they leave cracks; enable merging): " + list(pairs, merged));
  }
  std::vector<int> kept;
  TriangleSoup copy2 = w_.soup;
  const auto [collapsed, duplicates] = dropCollapsedAndDuplicateTriangles(copy2, &kept);
  (void)collapsed;
  if (duplicates > 0)
    add(MeshIssueKind::DuplicateTriangles, duplicates, Severity::Error,
        std::to_string(duplicates) + " triangle(s) duplicate another triangle");
}

void Checker::handleComponents() {
  int count = 0;
  const std::vector<int> component = triangleComponents(w_.soup, count);
  r_.components = count;
  if (count <= 1) return;
  if (o_.components == ComponentPolicy::KeepLargest) {
    std::vector<int> kept, oldToNew;
    const int dropped = keepLargestComponent(w_.soup, &kept, &oldToNew);
    w_.applyTriangleSelection(kept);
    w_.applyVertexMap(oldToNew);
    d_.droppedComponentTriangles = dropped;
    d_.removedComponents = count - 1;
    add(MeshIssueKind::SeveralComponents, count - 1, Severity::Repaired,
        "the mesh has " + std::to_string(count) +
            " connected components; kept the largest by area (" +
            std::to_string(w_.soup.triangles.size()) + " triangles) and dropped " +
            std::to_string(dropped) + " triangles of the other " + std::to_string(count - 1));
    r_.components = 1;
    return;
  }
  std::vector<int> size(count, 0), first(count, -1);
  for (size_t t = 0; t < component.size(); ++t) {
    if (component[t] >= count) continue;
    ++size[component[t]];
    if (first[component[t]] < 0) first[component[t]] = static_cast<int>(t);
  }
  std::vector<std::string> named;
  for (int c = 0; c < count && c < o_.maxNamedElements; ++c)
    named.push_back("component " + std::to_string(c) + ": " + std::to_string(size[c]) +
                    " triangles from " + triangleName(first[c]));
  add(MeshIssueKind::SeveralComponents, count, Severity::Error,
      "the mesh has " + std::to_string(count) +
          " connected components (to keep only the largest, set the scene's "
          "surface.keep_largest_component to true): " +
          list(named, count));
}

void Checker::handleIsolatedVertices() {
  std::vector<char> used(w_.soup.vertices.size(), 0);
  for (const auto& tri : w_.soup.triangles)
    for (int v : tri) used[v] = 1;
  const int isolated = static_cast<int>(std::count(used.begin(), used.end(), 0));
  if (isolated == 0) return;
  if (o_.dropUnreferencedVertices) {
    std::vector<int> oldToNew;
    d_.droppedUnreferencedVertices = dropUnreferencedVertices(w_.soup, &oldToNew);
    w_.applyVertexMap(oldToNew);
    add(MeshIssueKind::IsolatedVertices, isolated, Severity::Repaired,
        "dropped " + std::to_string(isolated) + " vertices that no triangle uses");
    return;
  }
  std::vector<std::string> named;
  for (size_t v = 0; v < used.size() && static_cast<int>(named.size()) < o_.maxNamedElements; ++v)
    if (!used[v]) named.push_back(vertexName(static_cast<int>(v)));
  add(MeshIssueKind::IsolatedVertices, isolated, Severity::Error,
      std::to_string(isolated) + " vertices are used by no triangle: " + list(named, isolated));
}

void Checker::checkFinite() {
  std::vector<std::string> named;
  int bad = 0;
  for (size_t v = 0; v < w_.soup.vertices.size(); ++v)
    if (!w_.soup.vertices[v].allFinite() && ++bad <= o_.maxNamedElements)
      named.push_back(vertexName(static_cast<int>(v)));
  if (bad > 0)
    add(MeshIssueKind::NonFiniteVertex, bad, Severity::Error,
        std::to_string(bad) + " vertices have a NaN or infinite coordinate: " + list(named, bad));
}

void Checker::checkFaceShapes() {
  const auto& V = w_.soup.vertices;
  double edgeSum = 0.0;
  int edgeCount = 0;
  for (const auto& tri : w_.soup.triangles)
    for (int k = 0; k < 3; ++k) {
      const double l = (V[tri[(k + 1) % 3]] - V[tri[k]]).norm();
      if (std::isfinite(l)) edgeSum += l, ++edgeCount;
    }
  r_.meanEdgeLengthM = edgeCount ? edgeSum / edgeCount : 0.0;
  const double areaThreshold = o_.degenerateAreaRelative * r_.meanEdgeLengthM * r_.meanEdgeLengthM;

  std::vector<std::string> degenerate;
  int degenerateCount = 0, sliverCount = 0, worstSliver = -1;
  double worstSliverAngle = std::numeric_limits<double>::infinity();
  r_.minFaceAreaM2 = std::numeric_limits<double>::infinity();
  r_.minAngleRad = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < w_.soup.triangles.size(); ++t) {
    const auto& tri = w_.soup.triangles[t];
    const Eigen::Vector3d& a = V[tri[0]];
    const Eigen::Vector3d& b = V[tri[1]];
    const Eigen::Vector3d& c = V[tri[2]];
    if (!a.allFinite() || !b.allFinite() || !c.allFinite()) continue;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    // Interior angles from atan2 (accurate for tiny and near-pi angles alike).
    double minAngle = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = V[tri[(k + 1) % 3]] - V[tri[k]];
      const Eigen::Vector3d e2 = V[tri[(k + 2) % 3]] - V[tri[k]];
      minAngle = std::min(minAngle, std::atan2(e1.cross(e2).norm(), e1.dot(e2)));
    }
    r_.minFaceAreaM2 = std::min(r_.minFaceAreaM2, area);
    if (minAngle < r_.minAngleRad) {
      r_.minAngleRad = minAngle;
      r_.worstFace = w_.triangleOrigin[t];
    }
    if (area <= areaThreshold) {
      if (++degenerateCount <= o_.maxNamedElements) {
        std::ostringstream s;
        s << triangleName(static_cast<int>(t)) << " area " << area << " m2";
        degenerate.push_back(s.str());
      }
    } else if (minAngle < o_.sliverMinAngleRad) {
      ++sliverCount;
      if (minAngle < worstSliverAngle)
        worstSliverAngle = minAngle, worstSliver = static_cast<int>(t);
    }
  }
  if (degenerateCount > 0)
    add(MeshIssueKind::DegenerateFaces, degenerateCount, Severity::Error,
        std::to_string(degenerateCount) + " zero-area triangle(s) (area below " +
            formatNumber(o_.degenerateAreaRelative) +
            " x mean edge length squared): " + list(degenerate, degenerateCount));
  if (sliverCount > 0) {
    std::ostringstream s;
    s << sliverCount << " sliver triangle(s) with an angle below "
      << o_.sliverMinAngleRad * 180.0 / std::numbers::pi << " degrees; the worst is "
      << triangleName(worstSliver) << " with " << worstSliverAngle * 180.0 / std::numbers::pi
      << " degrees";
    add(MeshIssueKind::SliverFaces, sliverCount,
        o_.rejectSlivers ? Severity::Error : Severity::Warning, s.str());
  }
}

std::uint64_t undirectedKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

void Checker::checkEdgesAndOrientation() {
  struct Use {
    std::uint64_t key;
    int triangle;
    int from, to;
  };
  // Sorting half-edge uses by undirected key groups each edge's triangles (and orders messages).
  std::vector<Use> all;
  all.reserve(3 * w_.soup.triangles.size());
  for (size_t t = 0; t < w_.soup.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = w_.soup.triangles[t][k], b = w_.soup.triangles[t][(k + 1) % 3];
      all.push_back({undirectedKey(a, b), static_cast<int>(t), a, b});
    }
  std::sort(all.begin(), all.end(), [](const Use& x, const Use& y) {
    return x.key < y.key || (x.key == y.key && x.triangle < y.triangle);
  });

  std::vector<std::string> nonManifold, conflicts;
  int nonManifoldCount = 0, conflictCount = 0;
  r_.boundaryEdges = 0;
  std::vector<Use> uses;
  for (size_t begin = 0; begin < all.size();) {
    size_t end = begin;
    while (end < all.size() && all[end].key == all[begin].key) ++end;
    uses.assign(all.begin() + begin, all.begin() + end);
    begin = end;
    if (uses.size() == 1) ++r_.boundaryEdges;
    if (uses.size() > 2 && ++nonManifoldCount <= o_.maxNamedElements) {
      std::string s = edgeName(uses[0].from, uses[0].to) + " is shared by " +
                      std::to_string(uses.size()) + " triangles (";
      for (size_t i = 0; i < uses.size(); ++i)
        s += (i ? ", " : "") + std::to_string(w_.triangleOrigin[uses[i].triangle]);
      nonManifold.push_back(s + ")");
    }
    if (uses.size() == 2 && uses[0].from == uses[1].from && ++conflictCount <= o_.maxNamedElements)
      conflicts.push_back(edgeName(uses[0].from, uses[0].to) + " runs the same way in triangles " +
                          std::to_string(w_.triangleOrigin[uses[0].triangle]) + " and " +
                          std::to_string(w_.triangleOrigin[uses[1].triangle]));
  }
  if (nonManifoldCount > 0)
    add(MeshIssueKind::NonManifoldEdges, nonManifoldCount, Severity::Error,
        std::to_string(nonManifoldCount) +
            " non-manifold edge(s): " + list(nonManifold, nonManifoldCount));
  if (conflictCount == 0) return;
  if (!o_.fixOrientation) {
    add(MeshIssueKind::InconsistentOrientation, conflictCount, Severity::Error,
        "inconsistent orientation at " + std::to_string(conflictCount) +
            " edge(s) (turn the faces so that neighbours agree, e.g. unify the normals in the "
            "modelling tool): " +
            list(conflicts, conflictCount));
    return;
  }
  const int flipped = orientConsistently(w_.soup);
  if (flipped < 0) {
    add(MeshIssueKind::NotOrientable, conflictCount, Severity::Error,
        "the surface is not orientable (a Moebius band): no choice of triangle orientations agrees "
        "at " +
            list(conflicts, conflictCount));
    return;
  }
  d_.flippedTriangles = flipped;
  add(MeshIssueKind::InconsistentOrientation, conflictCount, Severity::Repaired,
      "flipped " + std::to_string(flipped) + " triangle(s) to make the orientation consistent");
}

void Checker::checkVertexFans() {
  // A manifold vertex's triangles form one fan: they are connected through edges at the vertex
  // that two triangles share. Two or more fans (two cones touching at their tips) is a bow tie.
  const int n = static_cast<int>(w_.soup.vertices.size());
  std::vector<std::vector<int>> incident(n);
  for (size_t t = 0; t < w_.soup.triangles.size(); ++t)
    for (int v : w_.soup.triangles[t]) incident[v].push_back(static_cast<int>(t));
  std::vector<std::string> named;
  int bad = 0;
  std::vector<int> parent;
  std::vector<std::pair<int, int>> firstWithVertex;
  for (int v = 0; v < n; ++v) {
    const auto& tris = incident[v];
    if (tris.size() < 2) continue;
    parent.resize(tris.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    // Join triangles that share another vertex (i.e. share an edge at v). Valences are small, so
    // a linear scan beats a hash map.
    firstWithVertex.clear();
    for (size_t i = 0; i < tris.size(); ++i)
      for (int u : w_.soup.triangles[tris[i]]) {
        if (u == v) continue;
        auto it = std::find_if(firstWithVertex.begin(), firstWithVertex.end(),
                               [u](const auto& e) { return e.first == u; });
        if (it == firstWithVertex.end())
          firstWithVertex.push_back({u, static_cast<int>(i)});
        else
          parent[root(static_cast<int>(i))] = root(it->second);
      }
    int fans = 0;
    for (size_t i = 0; i < tris.size(); ++i)
      if (root(static_cast<int>(i)) == static_cast<int>(i)) ++fans;
    if (fans > 1 && ++bad <= o_.maxNamedElements)
      named.push_back(vertexName(v) + " joins " + std::to_string(fans) +
                      " separate fans of triangles");
  }
  if (bad > 0)
    add(MeshIssueKind::NonManifoldVertices, bad, Severity::Error,
        std::to_string(bad) + " non-manifold vertex(es): " + list(named, bad));
}

void Checker::run() {
  r_.vertices = static_cast<int>(w_.soup.vertices.size());
  r_.triangles = static_cast<int>(w_.soup.triangles.size());
  if (w_.soup.triangles.empty() || w_.soup.vertices.empty()) {
    add(MeshIssueKind::Empty, 0, Severity::Error,
        "the mesh is empty (" + std::to_string(r_.vertices) + " vertices, " +
            std::to_string(r_.triangles) + " triangles)");
    return;
  }
  if (!checkIndices()) return;
  BoundingBox box;
  box.min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  box.max = -box.min;
  for (const auto& p : w_.soup.vertices)
    if (p.allFinite()) box.min = box.min.cwiseMin(p), box.max = box.max.cwiseMax(p);
  const double diagonal = box.min.allFinite() ? box.size().norm() : 0.0;
  mergeDuplicates(o_.mergeToleranceRelative * diagonal);
  if (w_.soup.triangles.empty()) {
    add(MeshIssueKind::Empty, 0, Severity::Error,
        "no triangle is left after merging duplicate vertices");
    return;
  }
  handleComponents();
  handleIsolatedVertices();
  checkFinite();
  checkFaceShapes();
  checkEdgesAndOrientation();
  checkVertexFans();
  r_.verticesAfterRepair = static_cast<int>(w_.soup.vertices.size());
  r_.trianglesAfterRepair = static_cast<int>(w_.soup.triangles.size());
}

WorkingSoup makeWorking(TriangleSoup soup) {
  WorkingSoup work;
  work.vertexOrigin.resize(soup.vertices.size());
  std::iota(work.vertexOrigin.begin(), work.vertexOrigin.end(), 0);
  work.triangleOrigin.resize(soup.triangles.size());
  std::iota(work.triangleOrigin.begin(), work.triangleOrigin.end(), 0);
  work.soup = std::move(soup);
  return work;
}

bool isError(const MeshIssue& issue, const MeshCheckOptions& options) {
  if (issue.repairable) return false;
  return !(issue.kind == MeshIssueKind::SliverFaces && !options.rejectSlivers);
}

}  // namespace

void MeshCheckOptions::validate() const {
  if (!(mergeToleranceRelative >= 0.0 && mergeToleranceRelative < 0.01))
    throw InvalidInput("MeshCheckOptions.merge_tolerance_relative must be in [0, 0.01), got " +
                       formatNumber(mergeToleranceRelative));
  if (!(degenerateAreaRelative >= 0.0 && degenerateAreaRelative < 0.1))
    throw InvalidInput("MeshCheckOptions.degenerate_area_relative must be in [0, 0.1), got " +
                       formatNumber(degenerateAreaRelative));
  if (!(sliverMinAngleRad >= 0.0 && sliverMinAngleRad < std::numbers::pi / 3.0))
    throw InvalidInput("MeshCheckOptions.sliver_min_angle_rad must be in [0, pi/3), got " +
                       formatNumber(sliverMinAngleRad));
  if (maxNamedElements < 1)
    throw InvalidInput("MeshCheckOptions.max_named_elements must be at least 1, got " +
                       std::to_string(maxNamedElements));
}

MeshCheckResult checkMesh(const TriangleSoup& soup, const MeshCheckOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  WorkingSoup work = makeWorking(soup);
  MeshCheckResult result;
  MeshRepairDiagnostics diagnostics;
  Checker(work, options, result, diagnostics).run();
  for (const auto& issue : result.issues)
    result.hasErrors = result.hasErrors || isError(issue, options);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

TriMesh prepareMesh(TriangleSoup soup, const MeshCheckOptions& options,
                    MeshRepairDiagnostics& diagnostics) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  diagnostics = MeshRepairDiagnostics{};
  WorkingSoup work = makeWorking(std::move(soup));
  MeshCheckResult& result = diagnostics.check;
  Checker(work, options, result, diagnostics).run();
  std::string errors;
  for (const auto& issue : result.issues)
    if (isError(issue, options)) {
      result.hasErrors = true;
      errors += (errors.empty() ? "" : "; ") + issue.message;
    }
  if (result.hasErrors) throw InvalidInput("invalid mesh: " + errors);
  TriMesh mesh = meshFromSoup(work.soup);
  diagnostics.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.seconds = diagnostics.seconds;
  return mesh;
}

}  // namespace egg
