#include "fabrication/drawing.hpp"

#include "core/io/xml_text.hpp"
#include "fabrication/stroke_text.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>

namespace egg::fabrication {

const char* layerName(Layer layer) {
  switch (layer) {
    case Layer::Cut: return "CUT";
    case Layer::Engrave: return "ENGRAVE";
    case Layer::Label: return "LABEL";
    case Layer::Reference: return "REFERENCE";
    case Layer::Toolpath: return "TOOLPATH";
  }
  return "CUT";
}

int layerAci(Layer layer) {
  switch (layer) {
    case Layer::Cut: return 1;
    case Layer::Engrave: return 5;
    case Layer::Label: return 3;
    case Layer::Reference: return 8;
    case Layer::Toolpath: return 6;
  }
  return 7;
}

const char* layerRgb(Layer layer) {
  switch (layer) {
    case Layer::Cut: return "#ff0000";
    case Layer::Engrave: return "#0000ff";
    case Layer::Label: return "#00ff00";
    case Layer::Reference: return "#808080";
    case Layer::Toolpath: return "#ff00ff";
  }
  return "#000000";
}

double viewingStrokeMm(const Drawing& d) {
  return std::max(0.1, std::max(d.widthMm, d.heightMm) / 1000.0);
}

std::vector<Eigen::Vector2d> slotCorners(const DrawSlot& slot) {
  Eigen::Vector2d u = slot.b - slot.a;
  u = u.norm() > 0.0 ? Eigen::Vector2d(u.normalized()) : Eigen::Vector2d(1.0, 0.0);
  const Eigen::Vector2d n(-u.y(), u.x());
  const double r = slot.radius;
  return {slot.a - r * n, slot.b - r * n, slot.b + r * n, slot.a + r * n};
}

namespace {

// "%.4f" (0.1 µm), through std::to_chars: the same digits, locale-free, several times faster
// than snprintf (a Yas sheet set has millions of coordinates).
std::string number(double x) {
  char buffer[400];
  const auto [end, ec] =
      std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::fixed, 4);
  if (ec != std::errc()) return "0.0000";  // beyond 1e396: no coordinate of a drawing
  std::string s(buffer, end);
  if (s == "-0.0000") s = "0.0000";
  return s;
}

}  // namespace

std::string toSvg(const Drawing& d) {
  const double h = d.heightMm;
  auto X = [](const Eigen::Vector2d& p) { return number(p.x()); };
  auto Y = [h](const Eigen::Vector2d& p) { return number(h - p.y()); };
  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << number(d.widthMm)
    << "mm\" height=\"" << number(d.heightMm) << "mm\" viewBox=\"0 0 " << number(d.widthMm) << " "
    << number(d.heightMm) << "\">\n"
    << "<title>" << escapeXml(d.title) << "</title>\n"
    << "<desc>Millimetres. One group per layer, each its own colour (CUT red, ENGRAVE blue, LABEL "
       "green single-stroke text, REFERENCE grey, TOOLPATH magenta); stroke widths are for "
       "viewing only.</desc>\n";
  const std::string stroke =
      "fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-width=\"" +
      number(viewingStrokeMm(d)) + "\"";
  for (Layer layer : kLayers) {
    s << "<g id=\"" << layerName(layer) << "\">\n";
    for (const auto& c : d.circles) {
      if (c.layer != layer) continue;
      s << "<circle cx=\"" << X(c.centre) << "\" cy=\"" << Y(c.centre) << "\" r=\""
        << number(c.radius) << "\" " << stroke << " stroke=\"" << layerRgb(layer) << "\"/>\n";
    }
    for (const auto& slot : d.slots) {
      if (slot.layer != layer) continue;
      // Straight side, half circle around b, straight side back, half circle around a. In the
      // flipped (screen) frame the turn from -n through +u to +n is the positive sweep.
      const auto k = slotCorners(slot);
      const std::string r = number(slot.radius);
      s << "<path d=\"M " << X(k[0]) << " " << Y(k[0]) << " L " << X(k[1]) << " " << Y(k[1])
        << " A " << r << " " << r << " 0 0 0 " << X(k[2]) << " " << Y(k[2]) << " L " << X(k[3])
        << " " << Y(k[3]) << " A " << r << " " << r << " 0 0 0 " << X(k[0]) << " " << Y(k[0])
        << " Z\" " << stroke << " stroke=\"" << layerRgb(layer) << "\"/>\n";
    }
    for (const auto& p : d.polylines) {
      if (p.layer != layer || p.points.empty()) continue;
      s << "<" << (p.closed ? "polygon" : "polyline") << " points=\"";
      for (size_t i = 0; i < p.points.size(); ++i)
        s << (i ? " " : "") << X(p.points[i]) << "," << Y(p.points[i]);
      s << "\" " << stroke << " stroke=\"" << layerRgb(layer) << "\"/>\n";
    }
    for (const auto& t : d.texts) {
      if (t.layer != layer) continue;
      // One path per text, its strokes as subpaths; the text and where it is anchored kept in
      // the path's title and description (single-stroke text has no font to read it back from).
      s << "<path class=\"text\" d=\"";
      for (const auto& line : placedStrokes(t)) {
        for (size_t i = 0; i < line.size(); ++i)
          s << (i ? "L " : "M ") << X(line[i]) << " " << Y(line[i]) << " ";
      }
      s << "\" " << stroke << " stroke=\"" << layerRgb(layer) << "\"><title>" << escapeXml(t.text)
        << "</title><desc>anchor " << X(t.anchor) << " " << number(t.anchor.y()) << " height "
        << number(t.height) << (t.align == TextAlign::Left ? " left" : " centre")
        << "</desc></path>\n";
    }
    s << "</g>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace egg::fabrication
