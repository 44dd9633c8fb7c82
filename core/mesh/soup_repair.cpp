#include "core/mesh/soup_repair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <unordered_map>

namespace egg {
namespace {

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  size_t operator()(const CellKey& k) const {
    return static_cast<size_t>(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
  }
};

std::uint64_t edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

int mergeDuplicateVertices(TriangleSoup& soup, double toleranceM, std::vector<int>* oldToNew) {
  const int n = static_cast<int>(soup.vertices.size());
  std::vector<int> representative(n, -1);
  std::vector<Eigen::Vector3d> kept;
  std::vector<int> newIndex(n, -1);
  kept.reserve(n);

  auto addNew = [&](int i) {
    newIndex[i] = static_cast<int>(kept.size());
    kept.push_back(soup.vertices[i]);
  };

  if (toleranceM <= 0.0) {
    // Exact: bitwise-equal coordinates (as STL writers produce them).
    std::map<std::array<double, 3>, int> seen;
    for (int i = 0; i < n; ++i) {
      const auto& p = soup.vertices[i];
      if (!p.allFinite()) {
        addNew(i);
        continue;
      }
      auto [it, inserted] = seen.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, -1);
      if (inserted) {
        addNew(i);
        it->second = newIndex[i];
      } else {
        newIndex[i] = it->second;
      }
    }
  } else {
    // Hash grid with cells of twice the tolerance: along each axis a partner within the tolerance
    // lies in the vertex's own cell or in the neighbour towards the nearer cell face, so 8 cells
    // are searched, not 27.
    std::unordered_map<CellKey, std::vector<int>, CellHash> grid;  // cell -> indices into `kept`
    grid.reserve(n);
    const double cellSize = 2.0 * toleranceM;
    const double tol2 = toleranceM * toleranceM;
    for (int i = 0; i < n; ++i) {
      const auto& p = soup.vertices[i];
      const Eigen::Vector3d scaled = p / cellSize;
      const Eigen::Vector3d cell = scaled.array().floor();
      if (!p.allFinite() || cell.cwiseAbs().maxCoeff() > 1e15) {
        addNew(i);
        continue;
      }
      const CellKey key{static_cast<std::int64_t>(cell.x()), static_cast<std::int64_t>(cell.y()),
                        static_cast<std::int64_t>(cell.z())};
      const Eigen::Vector3d fraction = scaled - cell;
      const int step[3] = {fraction.x() < 0.5 ? -1 : 1, fraction.y() < 0.5 ? -1 : 1,
                           fraction.z() < 0.5 ? -1 : 1};
      int match = -1;
      for (int corner = 0; corner < 8 && match < 0; ++corner) {
        auto it =
            grid.find({key.x + ((corner & 1) ? step[0] : 0), key.y + ((corner & 2) ? step[1] : 0),
                       key.z + ((corner & 4) ? step[2] : 0)});
        if (it == grid.end()) continue;
        for (int k : it->second)
          if ((kept[k] - p).squaredNorm() <= tol2) {
            match = k;
            break;
          }
      }
      if (match >= 0) {
        newIndex[i] = match;
      } else {
        addNew(i);
        grid[key].push_back(newIndex[i]);
      }
    }
  }
  for (auto& tri : soup.triangles)
    for (int& v : tri)
      if (v >= 0 && v < n) v = newIndex[v];
  const int removed = n - static_cast<int>(kept.size());
  soup.vertices = std::move(kept);
  if (oldToNew) *oldToNew = std::move(newIndex);
  return removed;
}

std::pair<int, int> dropCollapsedAndDuplicateTriangles(TriangleSoup& soup,
                                                       std::vector<int>* keptTriangles) {
  int collapsed = 0, duplicates = 0;
  std::set<std::array<int, 3>> seen;
  std::vector<std::array<int, 3>> kept;
  kept.reserve(soup.triangles.size());
  if (keptTriangles) keptTriangles->clear();
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++collapsed;
      continue;
    }
    std::array<int, 3> sorted = tri;
    std::sort(sorted.begin(), sorted.end());
    if (!seen.insert(sorted).second) {
      ++duplicates;
      continue;
    }
    kept.push_back(tri);
    if (keptTriangles) keptTriangles->push_back(static_cast<int>(t));
  }
  soup.triangles = std::move(kept);
  return {collapsed, duplicates};
}

int dropUnreferencedVertices(TriangleSoup& soup, std::vector<int>* oldToNew) {
  const int n = static_cast<int>(soup.vertices.size());
  std::vector<int> newIndex(n, -1);
  for (const auto& tri : soup.triangles)
    for (int v : tri)
      if (v >= 0 && v < n) newIndex[v] = 0;
  std::vector<Eigen::Vector3d> kept;
  for (int i = 0; i < n; ++i)
    if (newIndex[i] == 0) {
      newIndex[i] = static_cast<int>(kept.size());
      kept.push_back(soup.vertices[i]);
    }
  for (auto& tri : soup.triangles)
    for (int& v : tri)
      if (v >= 0 && v < n) v = newIndex[v];
  const int removed = n - static_cast<int>(kept.size());
  soup.vertices = std::move(kept);
  if (oldToNew) *oldToNew = std::move(newIndex);
  return removed;
}

std::vector<int> triangleComponents(const TriangleSoup& soup, int& count) {
  const int n = static_cast<int>(soup.vertices.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& tri : soup.triangles) {
    int root = -1;
    for (int v : tri) {
      if (v < 0 || v >= n) continue;
      const int r = findRoot(parent, v);
      if (root < 0)
        root = r;
      else if (r != root)
        parent[r] = root;
    }
  }
  std::unordered_map<int, int> idOfRoot;
  std::vector<int> component(soup.triangles.size(), -1);
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    int v = -1;
    for (int c : soup.triangles[t])
      if (c >= 0 && c < n) v = c;
    if (v < 0) {  // no valid index at all: a component of its own
      component[t] = static_cast<int>(idOfRoot.size()) + 1000000000;
      continue;
    }
    const int root = findRoot(parent, v);
    auto [it, inserted] = idOfRoot.emplace(root, static_cast<int>(idOfRoot.size()));
    component[t] = it->second;
  }
  count = static_cast<int>(idOfRoot.size());
  return component;
}

int keepLargestComponent(TriangleSoup& soup, std::vector<int>* keptTriangles,
                         std::vector<int>* oldToNew) {
  int count = 0;
  const std::vector<int> component = triangleComponents(soup, count);
  if (keptTriangles) keptTriangles->clear();
  if (count <= 1) {
    if (keptTriangles)
      for (size_t t = 0; t < soup.triangles.size(); ++t)
        keptTriangles->push_back(static_cast<int>(t));
    if (oldToNew) {
      oldToNew->resize(soup.vertices.size());
      std::iota(oldToNew->begin(), oldToNew->end(), 0);
    }
    return 0;
  }
  std::vector<double> area(count, 0.0);
  const int n = static_cast<int>(soup.vertices.size());
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    if (component[t] >= count ||
        std::any_of(tri.begin(), tri.end(), [&](int v) { return v < 0 || v >= n; }))
      continue;
    const double a = 0.5 * (soup.vertices[tri[1]] - soup.vertices[tri[0]])
                               .cross(soup.vertices[tri[2]] - soup.vertices[tri[0]])
                               .norm();
    if (std::isfinite(a)) area[component[t]] += a;
  }
  const int largest = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
  std::vector<std::array<int, 3>> kept;
  for (size_t t = 0; t < soup.triangles.size(); ++t)
    if (component[t] == largest) {
      kept.push_back(soup.triangles[t]);
      if (keptTriangles) keptTriangles->push_back(static_cast<int>(t));
    }
  const int removed = static_cast<int>(soup.triangles.size() - kept.size());
  soup.triangles = std::move(kept);
  dropUnreferencedVertices(soup, oldToNew);
  return removed;
}

int orientConsistently(TriangleSoup& soup) {
  const int m = static_cast<int>(soup.triangles.size());
  // Undirected edge -> (triangle, +1 if the triangle runs it from the smaller to the larger index).
  std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>> edges;
  edges.reserve(3 * m);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = soup.triangles[t][k], b = soup.triangles[t][(k + 1) % 3];
      edges[edgeKey(a, b)].push_back({t, a < b ? +1 : -1});
    }
  std::vector<int> flip(m, -1);  // -1 unvisited, 0 keep, 1 flip
  for (int seed = 0; seed < m; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    std::queue<int> queue;
    queue.push(seed);
    std::vector<int> members;
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop();
      members.push_back(t);
      for (int k = 0; k < 3; ++k) {
        const int a = soup.triangles[t][k], b = soup.triangles[t][(k + 1) % 3];
        const auto& users = edges[edgeKey(a, b)];
        if (users.size() != 2) continue;
        const auto& mine = users[0].first == t ? users[0] : users[1];
        const auto& other = users[0].first == t ? users[1] : users[0];
        if (other.first == t) continue;
        // Consistent neighbours run the shared edge in opposite directions.
        const int wanted = flip[t] ^ (mine.second == other.second ? 1 : 0);
        if (flip[other.first] < 0) {
          flip[other.first] = wanted;
          queue.push(other.first);
        } else if (flip[other.first] != wanted) {
          return -1;  // not orientable
        }
      }
    }
    // Keep the orientation most triangles of the component already have.
    const auto flips =
        std::count_if(members.begin(), members.end(), [&](int t) { return flip[t] == 1; });
    if (2 * flips > static_cast<long>(members.size()))
      for (int t : members) flip[t] ^= 1;
  }
  int flipped = 0;
  for (int t = 0; t < m; ++t)
    if (flip[t] == 1) {
      std::swap(soup.triangles[t][1], soup.triangles[t][2]);
      ++flipped;
    }
  return flipped;
}

}  // namespace egg
