#pragma once
// A cut sheet as plain 2D geometry in millimetres (y up, origin at the sheet's lower left corner),
// written by the SVG, DXF and PDF writers. Three layers as laser and CNC software expect them:
// CUT (red hairline, through), ENGRAVE (blue, marks: arrows, splice lines), LABEL (engraved text).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace egg::fabrication {

enum class Layer { Cut, Engrave, Label };
const char* layerName(Layer layer);  // "CUT", "ENGRAVE", "LABEL"

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

// SVG 1.1 in millimetres (width/height in mm, viewBox in mm, y flipped so the sheet reads as in the
// DXF): cut = red (#ff0000) hairline, engrave = blue (#0000ff) hairline, labels = blue text.
std::string toSvg(const Drawing& drawing);

}  // namespace egg::fabrication
