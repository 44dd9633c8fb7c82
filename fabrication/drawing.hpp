#pragma once
// A cut sheet as plain 2D geometry in millimetres (y up, origin at the sheet's lower left corner),
// written by the SVG, DXF and PDF writers. One layer per operation, each its own colour, because
// laser and CNC software assign operations by colour: CUT (red, through), ENGRAVE (blue, marks:
// arrows, splice lines), LABEL (green, engraved single-stroke text), REFERENCE (grey, not cut: the
// sheet's outline and id), TOOLPATH (magenta, a router bit's centre path, only with a tool
// diameter).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace egg::fabrication {

enum class Layer { Cut, Engrave, Label, Reference, Toolpath };
inline constexpr Layer kLayers[] = {Layer::Cut, Layer::Engrave, Layer::Label, Layer::Reference,
                                    Layer::Toolpath};
const char* layerName(Layer layer);  // "CUT", "ENGRAVE", "LABEL", "REFERENCE", "TOOLPATH"
int layerAci(Layer layer);  // AutoCAD colour index: 1 red, 5 blue, 3 green, 8 grey, 6 magenta
const char* layerRgb(Layer layer);  // the same colour as "#rrggbb" (ezdxf's ACI table)

struct DrawCircle {
  Layer layer = Layer::Cut;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

// A stadium (an elongated hole): every point within `radius` of the segment a-b.
struct DrawSlot {
  Layer layer = Layer::Cut;
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

struct DrawPolyline {
  Layer layer = Layer::Cut;
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
};

enum class TextAlign { Left, Centre };  // horizontally; vertically the anchor is the text's middle

struct DrawText {
  Layer layer = Layer::Label;
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();
  double height = 0.0;
  std::string text;
  TextAlign align = TextAlign::Left;
};

struct Drawing {
  std::string title;
  double widthMm = 0.0, heightMm = 0.0;
  std::vector<DrawCircle> circles;
  std::vector<DrawSlot> slots;
  std::vector<DrawPolyline> polylines;
  std::vector<DrawText> texts;
};

// The four corners of the stadium's straight sides, counter-clockwise starting at a's right side:
// a - r n, b - r n, b + r n, a + r n with n the left normal of a->b (a degenerate slot uses +x).
std::vector<Eigen::Vector2d> slotCorners(const DrawSlot& slot);

// The stroke width of the SVG and the fitted PDF, for viewing only (CAM software ignores it): a
// thousandth of the sheet's longer side, at least 0.1 mm, so that a sheet shown whole on a screen
// (about 1000 pixels across) still has one-pixel lines.
double viewingStrokeMm(const Drawing& drawing);

// SVG 1.1 in millimetres (width/height in mm, viewBox in mm, y flipped so the sheet reads as in the
// DXF): one <g> per layer in its colour, texts as single-stroke paths (stroke_text.hpp).
std::string toSvg(const Drawing& drawing);

}  // namespace egg::fabrication
