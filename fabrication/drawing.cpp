#include "fabrication/drawing.hpp"

#include "core/io/xml_text.hpp"

#include <cstdio>
#include <sstream>

namespace egg::fabrication {

const char* layerName(Layer layer) {
  switch (layer) {
    case Layer::Cut: return "CUT";
    case Layer::Engrave: return "ENGRAVE";
    case Layer::Label: return "LABEL";
  }
  return "CUT";
}

std::vector<Eigen::Vector2d> slotCorners(const DrawSlot& slot) {
  Eigen::Vector2d u = slot.b - slot.a;
  u = u.norm() > 0.0 ? Eigen::Vector2d(u.normalized()) : Eigen::Vector2d(1.0, 0.0);
  const Eigen::Vector2d n(-u.y(), u.x());
  const double r = slot.radius;
  return {slot.a - r * n, slot.b - r * n, slot.b + r * n, slot.a + r * n};
}

namespace {

// Laser software keys on colour: pure red cuts, pure blue engraves. A hairline is 0.01 mm.
const char* colourOf(Layer layer) { return layer == Layer::Cut ? "#ff0000" : "#0000ff"; }

std::string number(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f", x);
  std::string s(buffer);
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
    << "<title>" << escapeXml(d.title) << "</title>\n";
  const std::string stroke = "fill=\"none\" stroke-width=\"0.01\"";
  for (Layer layer : {Layer::Cut, Layer::Engrave, Layer::Label}) {
    s << "<g id=\"" << layerName(layer) << "\">\n";
    for (const auto& c : d.circles) {
      if (c.layer != layer) continue;
      s << "<circle cx=\"" << X(c.centre) << "\" cy=\"" << Y(c.centre) << "\" r=\""
        << number(c.radius) << "\" " << stroke << " stroke=\"" << colourOf(layer) << "\"/>\n";
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
        << " Z\" " << stroke << " stroke=\"" << colourOf(layer) << "\"/>\n";
    }
    for (const auto& p : d.polylines) {
      if (p.layer != layer || p.points.empty()) continue;
      s << "<" << (p.closed ? "polygon" : "polyline") << " points=\"";
      for (size_t i = 0; i < p.points.size(); ++i)
        s << (i ? " " : "") << X(p.points[i]) << "," << Y(p.points[i]);
      s << "\" " << stroke << " stroke=\"" << colourOf(layer) << "\"/>\n";
    }
    for (const auto& t : d.texts) {
      if (t.layer != layer) continue;
      s << "<text x=\"" << X(t.anchor) << "\" y=\"" << Y(t.anchor)
        << "\" font-family=\"sans-serif\" font-size=\"" << number(t.height) << "\" text-anchor=\""
        << (t.align == TextAlign::Left ? "start" : "middle")
        << "\" dominant-baseline=\"central\" fill=\"" << colourOf(layer) << "\" stroke=\"none\">"
        << escapeXml(t.text) << "</text>\n";
    }
    s << "</g>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace egg::fabrication
