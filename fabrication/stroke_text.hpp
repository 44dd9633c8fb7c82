#pragma once
// Text as single-stroke outlines from the Hershey "futural" font (Debian hershey-fonts-data, read
// by libhersheyfont), so that no CAM tool needs a font: a label is a set of open polylines that a
// laser engraves or a router traces, in every format alike (DXF, SVG, PDF).
#include "fabrication/drawing.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

// The strokes of `text` with capital height `heightMm`, the baseline's left end at the origin
// (y up). Characters the font lacks are drawn as a space. Throws IoError naming the package when
// the font cannot be loaded.
std::vector<std::vector<Eigen::Vector2d>> textStrokes(const std::string& text, double heightMm);

// The advance width of `text` at capital height `heightMm` (the font's own glyph widths).
double strokeTextWidthMm(const std::string& text, double heightMm);

// The strokes of a DrawText placed as it asks: horizontally by its alignment, vertically centred
// on the capital height at the anchor.
std::vector<std::vector<Eigen::Vector2d>> placedStrokes(const DrawText& text);

}  // namespace egg::fabrication
