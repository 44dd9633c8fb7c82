#include "core/egg/grid_io.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace egg {
namespace {

using nlohmann::json;

json vec(const Eigen::Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); }
json vec(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }

const char* originName(MemberOrigin origin) {
  switch (origin) {
    case MemberOrigin::Boundary: return "boundary";
    case MemberOrigin::LengthExtremum: return "length_extremum";
    case MemberOrigin::CurvatureExtremum: return "curvature_extremum";
    case MemberOrigin::Filled: return "filled";
    case MemberOrigin::Even: return "even";
    case MemberOrigin::Given: return "given";
  }
  return "unknown";
}

json members(const std::vector<GridMember>& list, const FamilyMembers& placed) {
  json out = json::array();
  for (const auto& m : list) {
    json spatial = json::array();
    for (const auto& p : m.spatial) spatial.push_back(vec(p));
    out.push_back({{"index", m.index},
                   {"boundary", m.boundary},
                   {"origin", originName(placed.origin[m.index])},
                   {"x1", m.x1},
                   {"x2", m.x2},
                   {"length_m", m.planarLength},
                   {"spatial_length_m", m.spatialLength},
                   {"planar_m", json::array({vec(m.planarStart), vec(m.planarEnd)})},
                   {"spatial_m", spatial}});
  }
  return out;
}

}  // namespace

std::string gridJson(const EggResult& r, int patchId) {
  const EggGrid& g = r.grid;
  json doc;
  doc["patch"] = {{"id", patchId},
                  {"corners_m", json::array({vec(r.patch.corners[0]), vec(r.patch.corners[1]),
                                             vec(r.patch.corners[2]), vec(r.patch.corners[3])})},
                  {"side_lengths_m", r.patch.sideLengths},
                  {"inner_angles_rad", r.patch.innerAngles},
                  {"area_m2", r.patch.area},
                  {"vertices", r.patch.mesh.n_vertices()},
                  {"faces", r.patch.mesh.n_faces()}};
  json intervals = json::array();
  for (const auto& i : r.alphaBar.feasibleIntervals) intervals.push_back({i.lo, i.hi});
  doc["alpha_bar"] = {{"value_rad", r.alphaBar.alphaBar},
                      {"range_rad", {r.alphaBar.alphaMin, r.alphaBar.alphaMax}},
                      {"range_found", r.alphaBar.rangeFound},
                      {"feasible_intervals_rad", intervals},
                      {"surface_angle_rad", r.maps.alphaSpatial},
                      {"slope_min", r.alphaBar.slopeMin},
                      {"slope_max", r.alphaBar.slopeMax},
                      {"degenerate", r.alphaBar.degenerate},
                      {"status", r.alphaBar.status}};
  doc["uniqueness"] = {{"eta_u", r.uniqueness.etaU},
                       {"eta_v", r.uniqueness.etaV},
                       {"eta_before_smoothing", r.uniqueness.etaBeforeSmoothing},
                       {"gaussian_max_per_m2", r.uniqueness.gaussianMax},
                       {"injectivity_bound_m", std::isfinite(r.uniqueness.injectivityBoundM)
                                                   ? json(r.uniqueness.injectivityBoundM)
                                                   : json(nullptr)},
                       {"longest_geodesic_m", r.uniqueness.longestGeodesicM},
                       {"smoothing_rounds", r.uniqueness.smoothingRounds},
                       {"smoothing_displacement_m", r.uniqueness.smoothingDisplacementM}};
  doc["planar_quad_m"] = json::array({vec(g.quad.corners[0]), vec(g.quad.corners[1]),
                                      vec(g.quad.corners[2]), vec(g.quad.corners[3])});
  doc["members"] = {{"u", members(g.u, r.membersU)}, {"v", members(g.v, r.membersV)}};
  json connections = json::array();
  for (const auto& c : g.connections)
    connections.push_back({{"u", c.memberU},
                           {"v", c.memberV},
                           {"on_boundary", c.onBoundary},
                           {"spatial_m", vec(c.spatial)},
                           {"normal", vec(c.normal)},
                           {"planar_m", vec(c.planar)},
                           {"s_u_m", c.sU},
                           {"s_bar_u_m", c.sBarU},
                           {"notch_u_m", c.notchU},
                           {"s_v_m", c.sV},
                           {"s_bar_v_m", c.sBarV},
                           {"notch_v_m", c.notchV}});
  doc["connections"] = connections;
  json anchors = json::array();
  for (const auto& a : g.anchors)
    anchors.push_back({{"connection", a.connection},
                       {"reason", a.reason},
                       {"spatial_m", vec(g.connections[a.connection].spatial)}});
  doc["anchors"] = anchors;
  doc["max_notch_m"] = g.maxNotch;
  doc["max_length_mismatch_relative"] = g.maxLengthMismatch;
  doc["timings_s"] = {{"patch", r.seconds.patch},
                      {"uniqueness", r.seconds.uniqueness},
                      {"distance_maps", r.seconds.distanceMaps},
                      {"sqp", r.seconds.sqp},
                      {"members", r.seconds.members},
                      {"tracing", r.seconds.tracing},
                      {"total", r.seconds.total}};
  return doc.dump(1);
}

void writeGridJson(const EggResult& result, const std::string& path, int patchId) {
  writeFileAtomically(path, gridJson(result, patchId));
}

void writeGridObj(const EggGrid& grid, const std::string& path, int patchId) {
  std::ostringstream out;
  out.precision(12);
  out << "# eggshell spatial grid: u members, v members (polylines on the surface), metres\n";
  int next = 1;
  for (const auto* family : {&grid.u, &grid.v})
    for (const auto& m : *family) {
      const std::string id = "P" + std::to_string(patchId) + "-" +
                             (m.family == Family::U ? "U" : "V") + std::to_string(m.index);
      out << "o " << id << "\ng " << id << "\n";
      for (const auto& p : m.spatial) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
      out << "l";
      for (size_t k = 0; k < m.spatial.size(); ++k) out << " " << next + static_cast<int>(k);
      out << "\n";
      next += static_cast<int>(m.spatial.size());
    }
  writeFileAtomically(path, out.str());
}

void writePlanarSvg(const EggGrid& grid, const std::string& path) {
  Eigen::Vector2d lo = grid.quad.corners[0], hi = lo;
  for (const auto& c : grid.quad.corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const double extent = std::max((hi - lo).maxCoeff(), 1e-9);
  const double size = 1000.0, margin = 40.0, scale = (size - 2 * margin) / extent;
  const auto map = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(margin + (p.x() - lo.x()) * scale,
                           size - margin - (p.y() - lo.y()) * scale);
  };
  std::ostringstream out;
  out.precision(6);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << size << "\" height=\"" << size
      << "\" viewBox=\"0 0 " << size << " " << size
      << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (const auto* family : {&grid.u, &grid.v})
    for (const auto& m : *family) {
      const auto a = map(m.planarStart), b = map(m.planarEnd);
      out << "<line x1=\"" << a.x() << "\" y1=\"" << a.y() << "\" x2=\"" << b.x() << "\" y2=\""
          << b.y() << "\" stroke=\"" << (m.family == Family::U ? "#1f77b4" : "#ff7f0e")
          << "\" stroke-width=\"" << (m.boundary ? 3 : 1.5) << "\"/>\n";
    }
  for (const auto& c : grid.connections) {
    const auto p = map(c.planar);
    for (int family = 0; family < 2; ++family) {
      const double notch = family == 0 ? c.notchU : c.notchV;
      if (notch == 0.0) continue;
      const GridMember& m = family == 0 ? grid.u[c.memberU] : grid.v[c.memberV];
      const Eigen::Vector2d direction = (m.planarEnd - m.planarStart).normalized();
      const auto q = map(c.planar + notch * direction);
      out << "<line x1=\"" << p.x() << "\" y1=\"" << p.y() << "\" x2=\"" << q.x() << "\" y2=\""
          << q.y() << "\" stroke=\"" << (family == 0 ? "#0b3d66" : "#8a4500")
          << "\" stroke-width=\"5\" stroke-linecap=\"round\"/>\n";
    }
    out << "<circle cx=\"" << p.x() << "\" cy=\"" << p.y() << "\" r=\"2\" fill=\"black\"/>\n";
  }
  for (const auto& a : grid.anchors) {
    const auto p = map(grid.connections[a.connection].planar);
    out << "<rect x=\"" << p.x() - 6 << "\" y=\"" << p.y() - 6
        << "\" width=\"12\" height=\"12\" fill=\"none\" stroke=\"red\" stroke-width=\"2\"/>\n";
  }
  out << "</svg>\n";
  writeFileAtomically(path, out.str());
}

}  // namespace egg
