#include "pipeline/elevations.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"
#include "patching/plan_drawing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg::pipeline {
namespace {
namespace elevation {

namespace plan = patching::plan;

// One panel: what is horizontal on the page (x, or y with north to the right) and, for a section,
// the plane.
struct Panel {
  std::string id, title;
  bool horizontalX = true;
  const SectionPlane* section = nullptr;
  double left = 0.0, top = 0.0;  // page px of the panel's (hmin, zmax) corner
};

struct Frame {
  double scale = 1.0;  // px per m
  double zmin = 0.0, zmax = 0.0;
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;
  double hmin(const Panel& p) const { return p.horizontalX ? xmin : ymin; }
  double hmax(const Panel& p) const { return p.horizontalX ? xmax : ymax; }
  double px(const Panel& p, double h) const { return p.left + (h - hmin(p)) * scale; }
  double py(const Panel& p, double z) const { return p.top + (zmax - z) * scale; }
};

double along(const Panel& p, const Eigen::Vector3d& q) { return p.horizontalX ? q.x() : q.y(); }

// The design surface's silhouette seen across the panel: per column of ~1.5 px, the z range the
// surface's triangles cover on the column's centre line; consecutive covered columns make one
// polygon (upper edge left to right, lower edge back).
std::string silhouetteSvg(const TriMesh& surface, const Frame& f, const Panel& panel) {
  const double h0 = f.hmin(panel), width = std::max(f.hmax(panel) - h0, 1e-9);
  const int bins = std::max(2, static_cast<int>(std::ceil(width * f.scale / 1.5)));
  const double binW = width / bins;
  std::vector<double> lo(bins, std::numeric_limits<double>::infinity()), hi(bins, -lo[0]);
  for (auto fh : surface.faces()) {
    const auto fv = faceVertices(surface, fh.idx());
    Eigen::Vector2d q[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = toEigen(surface.point(TriMesh::VertexHandle(fv[k])));
      q[k] = {along(panel, p), p.z()};
    }
    const double a = std::min({q[0].x(), q[1].x(), q[2].x()});
    const double b = std::max({q[0].x(), q[1].x(), q[2].x()});
    const int first = std::max(0, static_cast<int>(std::ceil((a - h0) / binW - 0.5)));
    const int last = std::min(bins - 1, static_cast<int>(std::floor((b - h0) / binW - 0.5)));
    for (int i = first; i <= last; ++i) {
      const double hc = h0 + (i + 0.5) * binW;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& u = q[k];
        const Eigen::Vector2d& v = q[(k + 1) % 3];
        if ((u.x() - hc) * (v.x() - hc) > 0.0 || u.x() == v.x()) continue;
        const double z = u.y() + (hc - u.x()) / (v.x() - u.x()) * (v.y() - u.y());
        lo[i] = std::min(lo[i], z), hi[i] = std::max(hi[i], z);
      }
    }
  }
  std::string d;
  for (int i = 0; i < bins;) {
    if (!(hi[i] >= lo[i])) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < bins && hi[j + 1] >= lo[j + 1]) ++j;
    for (int k = i; k <= j; ++k)
      d += fmt::format("{}{:.1f},{:.1f}", k == i ? "M" : "L", f.px(panel, h0 + (k + 0.5) * binW),
                       f.py(panel, hi[k]));
    for (int k = j; k >= i; --k)
      d += fmt::format("L{:.1f},{:.1f}", f.px(panel, h0 + (k + 0.5) * binW), f.py(panel, lo[k]));
    d += "Z";
    i = j + 1;
  }
  return fmt::format(
      "<path class=\"design\" fill=\"#dde4ee\" stroke=\"#7d8fa8\" stroke-width=\"0.8\" "
      "stroke-linejoin=\"round\" d=\"{}\"/>\n",
      d);
}

// The deployed centrelines projected onto the panel, points closer than a pixel to the last one
// kept dropped (the Great Court's ~40k segments would otherwise weigh a megabyte a panel).
std::string rodsSvg(const std::vector<DeployedRod>& rods, const Frame& f, const Panel& panel) {
  plan::PathChunks paths(
      "class=\"deployed\" fill=\"none\" stroke=\"#222\" stroke-opacity=\"0.75\" "
      "stroke-width=\"0.6\"");
  std::string d;
  for (const auto& r : rods) {
    double lastX = 1e300, lastY = 1e300;
    d.clear();
    for (size_t i = 0; i < r.points.size(); ++i) {
      const double x = f.px(panel, along(panel, r.points[i])), y = f.py(panel, r.points[i].z());
      const bool end = i + 1 == r.points.size();
      if (i > 0 && !end && std::hypot(x - lastX, y - lastY) < 1.0) continue;
      d += fmt::format("{}{:.1f},{:.1f}", i == 0 ? "M" : "L", x, y);
      lastX = x, lastY = y;
    }
    paths.add(d);
  }
  return paths.finish();
}

// A section: the design surface cut by the plane (one segment per crossed triangle) and a dot
// where each lamella crosses it.
std::string sectionSvg(const TriMesh& surface, const std::vector<DeployedRod>& rods, const Frame& f,
                       const Panel& panel, int& cuts) {
  const SectionPlane& plane = *panel.section;
  const auto side = [&](const Eigen::Vector3d& p) {
    return (plane.alongX ? p.y() : p.x()) - plane.atM;
  };
  const auto crossing = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const double t = side(a) / (side(a) - side(b));
    return Eigen::Vector3d(a + t * (b - a));
  };
  plan::PathChunks cut(
      "class=\"design-cut\" fill=\"none\" stroke=\"#111\" stroke-width=\"2\" "
      "stroke-linecap=\"round\"");
  for (auto fh : surface.faces()) {
    const auto fv = faceVertices(surface, fh.idx());
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = toEigen(surface.point(TriMesh::VertexHandle(fv[k])));
    std::vector<Eigen::Vector3d> hits;
    for (int k = 0; k < 3; ++k) {
      const double a = side(p[k]), b = side(p[(k + 1) % 3]);
      if ((a < 0.0) != (b < 0.0)) hits.push_back(crossing(p[k], p[(k + 1) % 3]));
    }
    if (hits.size() != 2) continue;
    cut.add(fmt::format("M{:.1f},{:.1f}L{:.1f},{:.1f}", f.px(panel, along(panel, hits[0])),
                        f.py(panel, hits[0].z()), f.px(panel, along(panel, hits[1])),
                        f.py(panel, hits[1].z())));
  }
  std::string out = cut.finish() + "<g class=\"lamella-cuts\" fill=\"#c62828\">\n";
  cuts = 0;
  for (const auto& r : rods)
    for (size_t i = 0; i + 1 < r.points.size(); ++i) {
      const double a = side(r.points[i]), b = side(r.points[i + 1]);
      if ((a < 0.0) == (b < 0.0)) continue;
      const Eigen::Vector3d c = crossing(r.points[i], r.points[i + 1]);
      out += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.2\"/>",
                         f.px(panel, along(panel, c)), f.py(panel, c.z()));
      ++cuts;
    }
  return out + "</g>\n";
}

// A level mark (the architect's triangle on a short line) at height z right of the panel.
std::string levelSvg(double x, double y, const std::string& text) {
  return fmt::format(
      "<g class=\"level\"><path d=\"M{0:.1f},{1:.1f}h34M{2:.1f},{1:.1f}l-5,-7h10z\" "
      "stroke=\"#111\" "
      "stroke-width=\"0.9\" fill=\"#fff\"/><text x=\"{3:.1f}\" y=\"{4:.1f}\" font-size=\"10\">{5}"
      "</text></g>\n",
      x, y, x + 10, x + 38, y + 3.5, escapeXml(text));
}

// Levels as architects write them: +27.59, −1.20, and ±0.00 for zero.
std::string level(double z) {
  if (std::abs(z) < 0.005) return "±0.00";
  return (z < 0 ? "" : "+") + plan::plainNumber(z, 2);
}

}  // namespace elevation
}  // namespace

std::vector<SectionPlane> sectionPlanes(const TriMesh& surface) {
  const BoundingBox box = boundingBox(surface);
  const Eigen::Vector3d c = 0.5 * (box.min + box.max);
  return {{"A", true, c.y()}, {"B", false, c.x()}};
}

std::string elevationsSvg(const TriMesh& surface, const std::vector<DeployedRod>& rods,
                          const std::string& caption) {
  using namespace elevation;  // NOLINT(google-build-using-namespace): this file's own helpers
  if (surface.n_faces() == 0) throw InvalidInput("elevations.svg: no design surface to draw");
  const BoundingBox box = boundingBox(surface);
  Frame f;
  f.xmin = box.min.x(), f.xmax = box.max.x(), f.ymin = box.min.y(), f.ymax = box.max.y();
  f.zmin = box.min.z(), f.zmax = box.max.z();
  double deployedTop = -std::numeric_limits<double>::infinity();
  for (const auto& r : rods)
    for (const auto& p : r.points) {
      if (!p.allFinite()) continue;
      f.xmin = std::min(f.xmin, p.x()), f.xmax = std::max(f.xmax, p.x());
      f.ymin = std::min(f.ymin, p.y()), f.ymax = std::max(f.ymax, p.y());
      f.zmin = std::min(f.zmin, p.z()), f.zmax = std::max(f.zmax, p.z());
      deployedTop = std::max(deployedTop, p.z());
    }
  const double dx = std::max(f.xmax - f.xmin, 1e-6), dy = std::max(f.ymax - f.ymin, 1e-6);
  const double dz = std::max(f.zmax - f.zmin, 1e-6);
  // One panel a row, all at one scale: the wider plan side fills the row, a tall shape is capped.
  const double pad = 30.0, levelRoom = 170.0, titleRoom = 26.0, groundRoom = 16.0;
  f.scale = std::min((1100.0 - 2 * pad - levelRoom) / std::max(dx, dy), 300.0 / dz);
  const double rowH = titleRoom + dz * f.scale + groundRoom + 14.0;
  const auto planes = sectionPlanes(surface);
  std::vector<Panel> panels = {
      {"elevation-south", "South elevation, looking north", true, nullptr},
      {"elevation-east", "East elevation, looking west", false, nullptr},
      {"section-a",
       fmt::format("Section A–A at y = {} m, looking north", plan::plainNumber(planes[0].atM, 2)),
       true, &planes[0]},
      {"section-b",
       fmt::format("Section B–B at x = {} m, looking west", plan::plainNumber(planes[1].atM, 2)),
       false, &planes[1]}};
  const double top0 = pad + 30.0;
  for (size_t k = 0; k < panels.size(); ++k) {
    panels[k].left = pad + 10.0;
    panels[k].top = top0 + k * rowH + titleRoom;
  }
  const double width = std::max(pad + 10.0 + std::max(dx, dy) * f.scale + levelRoom + pad, 800.0);
  const double legendY = top0 + panels.size() * rowH + 10.0;
  const double height = legendY + 70.0;
  std::string svg = fmt::format(
      "<svg id=\"elevations\" xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" "
      "width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\" "
      "data-px-per-m=\"{2:.9g}\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" "
      "font-size=\"12\" role=\"img\">\n<rect width=\"{0:.0f}\" height=\"{1:.0f}\" fill=\"#fff\"/>\n"
      "<text x=\"{3}\" y=\"{4}\" font-size=\"15\" font-weight=\"bold\">{5}</text>\n",
      width, height, f.scale, pad, pad + 6, escapeXml(caption));
  const double designTop = box.max.z();
  for (const Panel& panel : panels) {
    const double x0 = f.px(panel, f.hmin(panel)), x1 = f.px(panel, f.hmax(panel));
    const double ground = f.py(panel, box.min.z());
    // data-frame: the page px of (h_min, z_max) and the h_min, z_max they stand for, so a reader
    // (a test) maps the panel back to metres with data-px-per-m.
    svg += fmt::format(
        "<g id=\"{}\" data-frame=\"{:.3f} {:.3f} {:.9g} {:.9g}\">\n<text x=\"{:.1f}\" y=\"{:.1f}\" "
        "font-weight=\"bold\">{}</text>\n",
        panel.id, panel.left, panel.top, f.hmin(panel), f.zmax, x0, panel.top - 10,
        escapeXml(panel.title));
    int cuts = 0;
    if (panel.section == nullptr) {
      svg += silhouetteSvg(surface, f, panel);
      svg += rodsSvg(rods, f, panel);
    } else {
      svg += sectionSvg(surface, rods, f, panel, cuts);
    }
    // The ground: the design's lowest point, hatched below.
    svg += fmt::format(
        "<path class=\"ground\" d=\"M{0:.1f},{1:.1f}H{2:.1f}\" stroke=\"#111\" "
        "stroke-width=\"1.2\"/>\n",
        x0 - 6, ground, x1 + 6);
    std::string hatch;
    for (double x = x0 - 4; x < x1 + 6; x += 8)
      hatch += fmt::format("M{:.1f},{:.1f}l-6,7", x + 6, ground);
    svg += fmt::format("<path d=\"{}\" stroke=\"#777\" stroke-width=\"0.7\"/>\n", hatch);
    // Levels, right of the panel: ground, the design's top, the deployed grid's top.
    const double lx = x1 + 10;
    svg += levelSvg(lx, ground, level(box.min.z()) + " ground");
    double yDesign = f.py(panel, designTop);
    svg += levelSvg(lx, yDesign, level(designTop) + " design");
    if (std::isfinite(deployedTop)) {
      double y = f.py(panel, deployedTop);
      if (std::abs(y - yDesign) < 13.0) y = yDesign + (y >= yDesign ? 13.0 : -13.0);
      svg += levelSvg(lx, y, level(deployedTop) + " deployed");
    }
    if (panel.section != nullptr)
      svg += fmt::format(
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"#555\">{} "
          "lamellas cut</text>\n",
          x0, ground + 26, cuts);
    svg += "</g>\n";
  }
  // Scale bar and legend.
  plan::Projection proj;
  proj.scale = f.scale;
  svg += plan::scaleBarSvg(proj, dx, pad, legendY, -1.0);
  const double lx = pad + 260.0;
  svg += fmt::format(
      "<g id=\"elevations-legend\" font-size=\"11\">"
      "<rect x=\"{0:.1f}\" y=\"{1:.1f}\" width=\"26\" height=\"10\" fill=\"#dde4ee\" "
      "stroke=\"#7d8fa8\"/><text x=\"{2:.1f}\" y=\"{3:.1f}\">design surface (silhouette)</text>"
      "<path d=\"M{0:.1f},{4:.1f}h26\" stroke=\"#222\"/><text x=\"{2:.1f}\" y=\"{5:.1f}\">deployed "
      "lamella centrelines (simulated)</text>"
      "<path d=\"M{6:.1f},{1:.1f}v10\" stroke=\"#111\" stroke-width=\"2\" transform=\"rotate(60 "
      "{6:.1f} {7:.1f})\"/><text x=\"{8:.1f}\" y=\"{3:.1f}\">section: design surface</text>"
      "<circle cx=\"{6:.1f}\" cy=\"{4:.1f}\" r=\"2.2\" fill=\"#c62828\"/><text x=\"{8:.1f}\" "
      "y=\"{5:.1f}\">section: a lamella cut</text>"
      "<text x=\"{0:.1f}\" y=\"{9:.1f}\" fill=\"#555\" font-size=\"10\">levels in metres "
      "(design z); sections through the middle of the plan, marked on plan.svg</text></g>\n",
      lx, legendY, lx + 34, legendY + 9, legendY + 22, legendY + 26, lx + 290, legendY + 5,
      lx + 304, legendY + 46);
  return svg + "</svg>\n";
}

}  // namespace egg::pipeline
