#pragma once
// Repairs on plain triangle soups, applied before a soup becomes a TriMesh (see validate.hpp).
// Importers hand over soups with duplicated vertices (STL stores every corner of every triangle),
// stray points and debris; these functions fix what can be fixed without changing the design
// surface, and report how much they changed so the caller can tell the user.
#include "core/mesh/mesh.hpp"

#include <utility>
#include <vector>

namespace egg {

// Merges vertices closer than `toleranceM` (greedy: a vertex joins the first earlier vertex within
// the tolerance; toleranceM = 0 merges bitwise-equal positions only). Non-finite vertices are never
// merged. Triangle indices are remapped; triangles may become collapsed (a repeated index), see
// dropCollapsedAndDuplicateTriangles. Returns the number of vertices removed.
// `oldToNew`, if given, receives the new index of every old vertex.
int mergeDuplicateVertices(TriangleSoup& soup, double toleranceM,
                           std::vector<int>* oldToNew = nullptr);

// Removes triangles that repeat a vertex index (they have zero area and, after merging, are the
// remains of edges shorter than the merge tolerance) and triangles with the same three vertices as
// an earlier one (in any order or orientation). Returns {collapsed removed, duplicates removed}.
// `keptTriangles`, if given, receives the old index of every kept triangle.
std::pair<int, int> dropCollapsedAndDuplicateTriangles(TriangleSoup& soup,
                                                       std::vector<int>* keptTriangles = nullptr);

// Removes vertices no triangle refers to and renumbers the rest, keeping their order.
// Returns the number of vertices removed.
int dropUnreferencedVertices(TriangleSoup& soup, std::vector<int>* oldToNew = nullptr);

// Connected components of triangles, where two triangles are connected when they share a vertex.
// Returns one component id per triangle (0 = the component holding triangle 0, ids in order of
// first appearance) and writes the number of components to `count`.
std::vector<int> triangleComponents(const TriangleSoup& soup, int& count);

// Keeps only the component with the largest surface area (then drops its unreferenced vertices).
// Returns the number of triangles removed.
// `keptTriangles` / `oldToNew` as above.
int keepLargestComponent(TriangleSoup& soup, std::vector<int>* keptTriangles = nullptr,
                         std::vector<int>* oldToNew = nullptr);

// Flips triangles so that every manifold edge (two triangles) is traversed in opposite directions,
// keeping the orientation the majority of each component's triangles already has. Edges with more
// than two triangles are ignored. Returns the number of flipped triangles, or -1 when the surface
// is not orientable (a Moebius strip); the soup is left unchanged in that case.
int orientConsistently(TriangleSoup& soup);

}  // namespace egg
