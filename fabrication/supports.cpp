#include "fabrication/supports.hpp"

#include "core/errors.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <sstream>

namespace egg::fabrication {

std::vector<Support> planSupports(const std::vector<FabricationPatch>& patches,
                                  const FabricationOptions& options, double* groundHeightM,
                                  int* innerAnchors) {
  std::vector<Support> supports;
  if (innerAnchors) *innerAnchors = 0;
  for (const auto& patch : patches) {
    const EggGrid& grid = *patch.grid;
    const int nu = static_cast<int>(grid.u.size()), nv = static_cast<int>(grid.v.size());
    // On a free side: row 0 (side 0) or the last row (side 2), column 0 (side 3) or the last (1).
    auto onFreeSide = [&](int k) {
      const int i = grid.connections[k].memberU, j = grid.connections[k].memberV;
      return (i == 0 && patch.freeSides[0]) || (j == nv - 1 && patch.freeSides[1]) ||
             (i == nu - 1 && patch.freeSides[2]) || (j == 0 && patch.freeSides[3]);
    };
    std::set<int> chosen;
    std::vector<std::pair<int, std::string>> picks;
    for (const auto& a : grid.anchors) {
      if (!onFreeSide(a.connection)) {
        // A patch's anchor on a side it shares (a corner where patches meet, a curvature extremum
        // of a seam): the neighbour's lamellas hold it, a block under it would stand in the air.
        if (innerAnchors && chosen.insert(a.connection).second) ++*innerAnchors;
        continue;
      }
      if (chosen.insert(a.connection).second)
        picks.emplace_back(a.connection, "anchor: " + a.reason);
    }
    if (options.supportsAtBoundaryConnections) {
      for (int k = 0; k < static_cast<int>(grid.connections.size()); ++k) {
        if (grid.connections[k].onBoundary && onFreeSide(k) && chosen.insert(k).second)
          picks.emplace_back(k, "boundary connection");
      }
    }
    std::sort(picks.begin(), picks.end());
    const auto add = [&](Support s) {
      // Patches meeting at a corner or a shared side anchor the same point: one support there.
      for (const auto& other : supports)
        if ((other.position - s.position).norm() < 1e-3) return;
      s.patchId = patch.patchId;
      s.normal = s.normal.normalized();
      if (s.normal.z() < 0.0) s.normal = -s.normal;
      s.inclinationDeg = std::acos(std::clamp(s.normal.z(), -1.0, 1.0)) * 180.0 / M_PI;
      s.directionDeg = std::hypot(s.normal.x(), s.normal.y()) > 1e-12
                           ? std::atan2(s.normal.y(), s.normal.x()) * 180.0 / M_PI
                           : 0.0;
      supports.push_back(s);
    };
    for (const auto& [k, reason] : picks) {
      const GridConnection& c = grid.connections[k];
      Support s;
      s.connection = k;
      s.connectionId = "P" + std::to_string(patch.patchId) + "-C" + std::to_string(c.memberU) +
                       "-" + std::to_string(c.memberV);
      s.reason = reason;
      s.position = c.spatial;
      s.normal = c.normal;
      add(s);
    }
    for (const auto& end : patch.endSupports) {
      Support s;
      s.connection = -1;
      s.connectionId = end.id;
      s.reason = "anchor: generalised member end";
      s.position = end.position;
      s.normal = end.normal;
      add(s);
    }
  }
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& s : supports) lowest = std::min(lowest, s.position.z());
  const double ground = options.groundHeightM.value_or(supports.empty() ? 0.0 : lowest - 0.1);
  for (size_t i = 0; i < supports.size(); ++i) {
    auto& s = supports[i];
    char id[32];
    std::snprintf(id, sizeof id, "S%03zu", i + 1);
    s.id = id;
    s.heightM = s.position.z() - ground;
    s.block = s.inclinationDeg <= 80.0;
    if (s.heightM <= 0.0) {
      throw InvalidInput("fabrication.ground_height_m: support " + s.id + " at " + s.connectionId +
                         " lies at or below the ground plane");
    }
  }
  if (groundHeightM) *groundHeightM = ground;
  return supports;
}

TriangleMesh supportSolid(const Support& support, double blockMm, double holeDiameterMm,
                          double holeDepthMm, double* bottomDropMm) {
  const Eigen::Vector3d n = support.normal;
  const double h = support.heightM * 1000.0;
  const double half = blockMm / 2.0;
  const Eigen::Vector3d top(0.0, 0.0, h);
  // Height of the contact plane above (x, y): n . (q - top) = 0.
  auto planeZ = [&](double x, double y) { return h - (n.x() * x + n.y() * y) / n.z(); };
  constexpr int perSide = 8;  // points per side of the square; the hole has 4 * perSide sides
  // Outer ring on the top face, counter-clockwise from the corner (-half, -half).
  std::vector<Eigen::Vector2d> ring;
  const Eigen::Vector2d corners[4] = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < perSide; ++k) {
      ring.push_back(corners[side] +
                     (corners[(side + 1) % 4] - corners[side]) * (double(k) / perSide));
    }
  }
  const int m = static_cast<int>(ring.size());
  double lowestTop = std::numeric_limits<double>::infinity();
  for (const auto& q : ring) lowestTop = std::min(lowestTop, planeZ(q.x(), q.y()));
  // The bottom is the ground (z = 0) unless the plane comes closer than 5 mm to it.
  const double bottom = std::min(0.0, lowestTop - 5.0);
  if (bottomDropMm) *bottomDropMm = -bottom;
  // The blind hole stays inside the block: its end above the bottom, its side off the block's
  // sides.
  double depth = std::min(holeDepthMm, 0.8 * (h - bottom) / n.z());
  const double sideways = std::sqrt(std::max(0.0, 1.0 - n.z() * n.z()));
  if (sideways > 1e-9) depth = std::min(depth, 0.9 * (half - holeDiameterMm / 2.0) / sideways);
  TriangleMesh mesh;
  auto add = [&](const Eigen::Vector3d& p) {
    mesh.vertices.push_back(p);
    return static_cast<int>(mesh.vertices.size()) - 1;
  };
  std::vector<int> outer(m), holeTop(m), holeBottom(m);
  // The hole's rim: the circle of the contact plane around the point, sampled at the same
  // horizontal directions as the outer ring so that the annulus triangulates as quads.
  const double r = holeDiameterMm / 2.0;
  for (int k = 0; k < m; ++k) {
    outer[k] = add({ring[k].x(), ring[k].y(), planeZ(ring[k].x(), ring[k].y())});
    const Eigen::Vector2d dir = ring[k].normalized();
    const Eigen::Vector3d lifted(dir.x(), dir.y(), -(n.x() * dir.x() + n.y() * dir.y()) / n.z());
    holeTop[k] = add(top + r * lifted.normalized());
  }
  for (int k = 0; k < m; ++k) holeBottom[k] = add(mesh.vertices[holeTop[k]] - depth * n);
  const int holeEnd = add(top - depth * n);
  int bottomCorner[4];
  for (int c = 0; c < 4; ++c) bottomCorner[c] = add({corners[c].x(), corners[c].y(), bottom});
  auto tri = [&](int a, int b, int c) { mesh.triangles.emplace_back(a, b, c); };
  for (int k = 0; k < m; ++k) {
    const int k1 = (k + 1) % m;
    // Top annulus (facing up: outer ring counter-clockwise, hole inside).
    tri(outer[k], outer[k1], holeTop[k1]);
    tri(outer[k], holeTop[k1], holeTop[k]);
    // Hole wall, facing the hole's axis.
    tri(holeTop[k], holeTop[k1], holeBottom[k1]);
    tri(holeTop[k], holeBottom[k1], holeBottom[k]);
    // Hole end, facing up into the hole.
    tri(holeBottom[k], holeBottom[k1], holeEnd);
  }
  // Sides: a fan from the bottom corner at the side's start over the side's top points.
  for (int side = 0; side < 4; ++side) {
    const int b0 = bottomCorner[side], b1 = bottomCorner[(side + 1) % 4];
    const int first = side * perSide;
    const int last = ((side + 1) * perSide) % m;  // the next corner on top
    tri(b0, b1, outer[last]);
    for (int k = perSide; k > 0; --k) {
      const int from = (first + k) % m, to = first + k - 1;
      tri(b0, outer[from], outer[to]);
    }
  }
  // Bottom, facing down.
  tri(bottomCorner[0], bottomCorner[2], bottomCorner[1]);
  tri(bottomCorner[0], bottomCorner[3], bottomCorner[2]);
  return mesh;
}

std::string toBinaryStl(const TriangleMesh& mesh, const std::string& header) {
  std::string out(80, ' ');
  std::memcpy(out.data(), header.data(), std::min<size_t>(header.size(), 80));
  auto put32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  auto putFloat = [&](double x) {
    const float f = static_cast<float>(x);
    out.append(reinterpret_cast<const char*>(&f), 4);
  };
  put32(static_cast<uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]],
                          &c = mesh.vertices[t[2]];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() > 0.0) normal.normalize();
    for (int i = 0; i < 3; ++i) putFloat(normal[i]);
    for (const auto* p : {&a, &b, &c}) {
      for (int i = 0; i < 3; ++i) putFloat((*p)[i]);
    }
    out.append(2, '\0');
  }
  return out;
}

std::string supportsCsv(const std::vector<Support>& supports) {
  std::ostringstream s;
  s << "id,connection,reason,x_m,y_m,z_m,nx,ny,nz,inclination_deg,direction_deg,height_m,kind,"
       "block_mm,below_ground_mm\n";
  char line[512];
  for (const auto& p : supports) {
    std::snprintf(line, sizeof line, "%s,%s,%s,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.3f,%.3f,%.6f,%s,",
                  p.id.c_str(), p.connectionId.c_str(), p.reason.c_str(), p.position.x(),
                  p.position.y(), p.position.z(), p.normal.x(), p.normal.y(), p.normal.z(),
                  p.inclinationDeg, p.directionDeg, p.heightM, p.block ? "block" : "bracket");
    s << line;
    if (p.block && p.blockMm > 0.0) {
      std::snprintf(line, sizeof line, "%.0f,%.1f", p.blockMm, p.belowGroundMm);
      s << line;
    } else {
      s << ",";
    }
    s << "\n";
  }
  return s.str();
}

}  // namespace egg::fabrication
