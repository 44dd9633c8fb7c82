#pragma once
// What the two plan sheets share (plan.svg, the architect's plan in site_plan.hpp, and
// curvature.svg, the analytical sheet in curvature_sheet.hpp): the page projection (plan xy, north
// up), text with a halo, boundary loops, patch outlines, a scale bar with its north arrow, a
// legend column, and labels placed so that they never overlap or leave the page.
#include "core/drawing/label_layout.hpp"
#include "core/mesh/mesh.hpp"
#include "patching/layout.hpp"
#include "patching/patch_graph.hpp"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace egg::patching::plan {

// Map from metres (plan xy) to page pixels: x to the right, north (y) up.
struct Projection {
  double xmin = 0.0, ymax = 0.0, scale = 1.0, left = 0.0, top = 0.0;
  double px(double x) const { return left + (x - xmin) * scale; }
  double py(double y) const { return top + (ymax - y) * scale; }
};

std::string point(const Projection& p, const Eigen::Vector3d& q);  // "x,y" in px
std::string pointList(const Projection& p, const std::vector<Eigen::Vector3d>& points);
// One closed path "M..L..L..Z" per face of `mesh` in `faces`. `owner` starts the message when a
// face is not the mesh's ("plan.svg: cut-off 2": "... lists face 9 of a layout mesh with 8 faces").
std::vector<std::string> facePaths(const TriMesh& mesh, const std::vector<int>& faces,
                                   const Projection& p, const std::string& owner);

// Text with a white halo, so labels stay readable over colours and lines.
std::string label(double x, double y, const std::string& text, double size,
                  const std::string& extra = "", const std::string& anchor = "middle");

// A round length for a scale bar: 1, 2 or 5 times a power of ten, at most `target`.
double roundLength(double target);

// Boundary loops of a mesh (each a closed list of vertex positions) and the index of the loop with
// the largest plan area (the outline; the others are holes).
std::vector<std::vector<Eigen::Vector3d>> boundaryLoops(const TriMesh& mesh);
size_t outerLoop(const std::vector<std::vector<Eigen::Vector3d>>& loops);
double signedAreaXY(const std::vector<Eigen::Vector3d>& loop);
// Area centroid of a polygon in plan (the vertex mean for a degenerate one).
Eigen::Vector2d centroidXY(const std::vector<Eigen::Vector3d>& loop);

// Outline of layout patch p: its four sides' segment chains, corner to corner.
std::vector<Eigen::Vector3d> patchOutline(const PatchLayout& layout, int p);

// Where a cut-off's label goes: the deepest face (most face steps from the cut-off's border; the
// one nearest the centroid among those), since the centroid of a ring lies outside it.
Eigen::Vector3d cutOffLabelPoint(const TriMesh& layoutMesh, const CutOff& cut);

// Greedy word wrap at `width` characters.
std::vector<std::string> wrap(const std::string& text, size_t width);

// A number as an architect reads it: fixed decimals, thousands grouped by a narrow space
// (34170.4 -> "34 170"), never an exponent.
std::string plainNumber(double value, int decimals = 0);

// <path> elements sharing `attributes`, their d data added a subpath at a time ("M...L...Z") and
// split so that no d attribute passes `maxBytes`: libxml2 (under librsvg, browsers' importers,
// Inkscape) refuses an attribute above 10 MB, which the K map of a 140k-face mesh was (issue 40).
class PathChunks {
 public:
  explicit PathChunks(std::string attributes, size_t maxBytes = size_t{1} << 20)
      : attributes_(std::move(attributes)), maxBytes_(maxBytes) {}
  void add(const std::string& subpath);
  bool empty() const { return out_.empty() && current_.empty(); }
  std::string finish();  // the elements, each on its own line

 private:
  std::string attributes_, out_, current_;
  size_t maxBytes_;
};

// Legend rows, laid out top to bottom from (x, y).
struct Legend {
  double x = 0.0, y = 0.0;
  std::string svg;
  void gap(double h) { y += h; }
  void text(const std::string& t, double size = 12, const std::string& extra = "");
  // A swatch (any SVG drawn in a 30 x 14 box at the origin) and its text.
  void item(const std::string& swatch, const std::string& t);
};

// A scale bar `barY` px from the top at x = `barX` (a round length near a fifth of `widthM`) with
// "0" and "<n> m" under it (ids "scale-bar" and "scale-label"), and a north arrow at `northX`
// (none when it is negative: an elevation has no north).
std::string scaleBarSvg(const Projection& proj, double widthM, double barX, double barY,
                        double northX);

// The label layout of core/drawing, with the SVG sheets' text estimate: widths at 0.62 em a
// character (DejaVu Sans, the sheets' font, averages 0.55 em over digits and lower case), heights
// at 1.2 em a line, so a placed label keeps clear of its neighbours in any of the fonts the sheets
// name.
class LabelLayout : public drawing::LabelLayout {
 public:
  using Box = drawing::LabelBox;
  LabelLayout(double width, double height)
      : drawing::LabelLayout({0.0, 0.0, width, height}, 16.0) {}
  // The box of a label of `lines` lines (the longest `chars` characters) of `size` px, centred on
  // (cx, cy).
  static Box boxAround(double cx, double cy, size_t chars, int lines, double size);
  // The first of `centres` (in order of preference) where the box fits; false when none does.
  bool place(const std::vector<Eigen::Vector2d>& centres, size_t chars, int lines, double size,
             Eigen::Vector2d& at);
};

using drawing::candidatesAround;

}  // namespace egg::patching::plan
