#include "patching/plan_drawing.hpp"

#include "core/errors.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg::patching::plan {

std::string point(const Projection& p, const Eigen::Vector3d& q) {
  return fmt::format("{:.1f},{:.1f}", p.px(q.x()), p.py(q.y()));
}

std::vector<std::string> facePaths(const TriMesh& mesh, const std::vector<int>& faces,
                                   const Projection& p, const std::string& owner) {
  std::vector<std::string> paths;
  paths.reserve(faces.size());
  for (int f : faces) {
    if (f < 0 || f >= static_cast<int>(mesh.n_faces()))
      throw InvalidInput(
          fmt::format("{} lists face {} of a layout mesh with {} faces", owner, f, mesh.n_faces()));
    const auto fv = faceVertices(mesh, f);
    std::string path;
    for (int k = 0; k < 3; ++k)
      path.append(k == 0 ? "M" : "L")
          .append(point(p, toEigen(mesh.point(TriMesh::VertexHandle(fv[k])))));
    paths.push_back(path + "Z");
  }
  return paths;
}

std::string pointList(const Projection& p, const std::vector<Eigen::Vector3d>& points) {
  std::string out;
  for (const auto& q : points) {
    if (!out.empty()) out += ' ';
    out += point(p, q);
  }
  return out;
}

std::string label(double x, double y, const std::string& text, double size,
                  const std::string& extra, const std::string& anchor) {
  return fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{:.0f}\" text-anchor=\"{}\" "
      "paint-order=\"stroke\" stroke=\"#fff\" "
      "stroke-width=\"3\" stroke-linejoin=\"round\"{}>{}</text>\n",
      x, y, size, anchor, extra, escapeXml(text));
}

double roundLength(double target) {
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= target) return m * decade;
  return decade;
}

std::vector<std::vector<Eigen::Vector3d>> boundaryLoops(const TriMesh& mesh) {
  std::vector<std::vector<Eigen::Vector3d>> loops;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    std::vector<Eigen::Vector3d> loop;
    for (auto g = h; !seen[g.idx()]; g = mesh.next_halfedge_handle(g)) {
      seen[g.idx()] = 1;
      loop.push_back(toEigen(mesh.point(mesh.from_vertex_handle(g))));
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

size_t outerLoop(const std::vector<std::vector<Eigen::Vector3d>>& loops) {
  size_t outer = 0;
  for (size_t i = 0; i < loops.size(); ++i)
    if (std::abs(signedAreaXY(loops[i])) > std::abs(signedAreaXY(loops[outer]))) outer = i;
  return outer;
}

double signedAreaXY(const std::vector<Eigen::Vector3d>& loop) {
  double a = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const auto& p = loop[i];
    const auto& q = loop[(i + 1) % loop.size()];
    a += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  return a;
}

Eigen::Vector2d centroidXY(const std::vector<Eigen::Vector3d>& loop) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero(), mean = Eigen::Vector2d::Zero();
  double a = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector2d p = loop[i].head<2>(), q = loop[(i + 1) % loop.size()].head<2>();
    const double w = p.x() * q.y() - q.x() * p.y();
    a += w, c += w * (p + q), mean += p;
  }
  if (loop.empty()) return c;
  if (std::abs(a) < 1e-12) return mean / static_cast<double>(loop.size());
  return c / (3.0 * a);
}

std::vector<Eigen::Vector3d> patchOutline(const PatchLayout& layout, int p) {
  std::vector<Eigen::Vector3d> outline;
  for (const PatchSideSegments& side : layout.patchSides[p])
    for (const auto& [segment, reversed] : side) {
      std::vector<int> chain = layout.segments[segment].chain;
      if (reversed) std::reverse(chain.begin(), chain.end());
      for (size_t i = 0; i + 1 < chain.size(); ++i)  // the last vertex starts the next piece
        outline.push_back(toEigen(layout.mesh.mesh.point(TriMesh::VertexHandle(chain[i]))));
    }
  return outline;
}

Eigen::Vector3d cutOffLabelPoint(const TriMesh& lm, const CutOff& cut) {
  std::vector<int> depth(lm.n_faces(), -2);  // -2 not in the cut-off, -1 not reached yet
  for (int f : cut.faces) depth[f] = -1;
  std::vector<int> queue;
  for (int f : cut.faces) {
    int neighbours = 0;
    for (auto g : lm.ff_range(TriMesh::FaceHandle(f))) neighbours += depth[g.idx()] != -2;
    if (neighbours < 3 && depth[f] == -1) depth[f] = 0, queue.push_back(f);
  }
  for (size_t i = 0; i < queue.size(); ++i)
    for (auto g : lm.ff_range(TriMesh::FaceHandle(queue[i])))
      if (depth[g.idx()] == -1) depth[g.idx()] = depth[queue[i]] + 1, queue.push_back(g.idx());
  Eigen::Vector3d at = cut.centroid;
  int bestDepth = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int f : cut.faces) {
    const auto fv = faceVertices(lm, f);
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += toEigen(lm.point(TriMesh::VertexHandle(fv[k]))) / 3.0;
    const double dist = (c - cut.centroid).head<2>().norm();
    if (depth[f] > bestDepth || (depth[f] == bestDepth && dist < best))
      bestDepth = depth[f], best = dist, at = c;
  }
  return at;
}

std::vector<std::string> wrap(const std::string& text, size_t width) {
  std::vector<std::string> lines{""};
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width) lines.push_back("");
    if (!lines.back().empty()) lines.back() += ' ';
    lines.back() += word;
    start = end + 1;
  }
  return lines;
}

std::string plainNumber(double value, int decimals) {
  if (!std::isfinite(value)) return fmt::format("{}", value);
  std::string digits = fmt::format("{:.{}f}", std::abs(value), std::max(0, decimals));
  if (digits.find_first_not_of("0.") == std::string::npos) value = 0.0;  // no "-0"
  const size_t dot = digits.find('.');
  std::string whole = digits.substr(0, dot), grouped;
  const std::string fraction = dot == std::string::npos ? "" : digits.substr(dot);
  for (size_t i = 0; i < whole.size(); ++i) {
    if (i > 0 && (whole.size() - i) % 3 == 0 && whole.size() > 4) grouped += "\u202f";
    grouped += whole[i];
  }
  return (value < 0 ? "−" : "") + grouped + fraction;
}

void PathChunks::add(const std::string& subpath) {
  if (!current_.empty() && current_.size() + subpath.size() > maxBytes_) {
    out_ += "<path " + attributes_ + " d=\"" + current_ + "\"/>\n";
    current_.clear();
  }
  current_ += subpath;
}

std::string PathChunks::finish() {
  if (!current_.empty()) out_ += "<path " + attributes_ + " d=\"" + current_ + "\"/>\n";
  current_.clear();
  return std::move(out_);
}

void Legend::text(const std::string& t, double size, const std::string& extra) {
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{:.0f}\"{}>{}</text>\n", x,
                     y + size, size, extra, escapeXml(t));
  y += size + 5;
}

void Legend::item(const std::string& swatch, const std::string& t) {
  svg += fmt::format("<g transform=\"translate({:.1f},{:.1f})\">{}</g>\n", x, y, swatch);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"12\">{}</text>\n", x + 40, y + 11,
                     escapeXml(t));
  y += 20;
}

std::string scaleBarSvg(const Projection& proj, double widthM, double barX, double barY,
                        double northX) {
  const double barM = roundLength(0.2 * widthM), barPx = barM * proj.scale;
  std::string out = fmt::format(
      "<g id=\"scale\"><rect id=\"scale-bar\" x=\"{:.3f}\" y=\"{:.1f}\" width=\"{:.3f}\" "
      "height=\"8\" fill=\"#fff\" stroke=\"#000\" "
      "stroke-width=\"1.2\"/><rect x=\"{:.3f}\" y=\"{:.1f}\" width=\"{:.3f}\" height=\"8\" "
      "fill=\"#000\"/>\n",
      barX, barY, barPx, barX, barY, 0.5 * barPx);
  out +=
      fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"12\">0</text>", barX - 3, barY + 24);
  out += fmt::format(
      "<text id=\"scale-label\" x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"12\" "
      "text-anchor=\"middle\">{} m</text></g>\n",
      barX + barPx, barY + 24, fmt::format("{:g}", barM));
  if (northX < 0.0) return out;
  const double northY = barY - 6;
  out += fmt::format(
      "<g id=\"north\"><path d=\"M{0:.1f},{1:.1f}l-7,18l7,-5l7,5z\" fill=\"#000\"/>"
      "<text x=\"{0:.1f}\" y=\"{2:.1f}\" font-size=\"13\" font-weight=\"bold\" "
      "text-anchor=\"middle\">N</text></g>\n",
      northX, northY, northY + 32);
  return out;
}

LabelLayout::Box LabelLayout::boxAround(double cx, double cy, size_t chars, int lines,
                                        double size) {
  const double w = 0.62 * size * static_cast<double>(chars) + 4.0;  // + the 1.5 px halo each side
  const double h = 1.2 * size * lines + 2.0;
  return {cx - 0.5 * w, cy - 0.5 * h, cx + 0.5 * w, cy + 0.5 * h};
}

bool LabelLayout::place(const std::vector<Eigen::Vector2d>& centres, size_t chars, int lines,
                        double size, Eigen::Vector2d& at) {
  for (const Eigen::Vector2d& c : centres)
    if (placeBox(boxAround(c.x(), c.y(), chars, lines, size))) {
      at = c;
      return true;
    }
  return false;
}

}  // namespace egg::patching::plan
