#pragma once
// Labels that never overlap: each label goes into the first of its candidate positions (in the
// caller's order of preference) whose box stays on the page and clear of every box taken before.
// A greedy placement, so the caller decides what matters most by what it places first (the plan's
// patch ids, the assembly drawings' lamella ids) and what it only reserves (markers, dots). Used by
// the site plan (patching/site_plan.cpp) and the assembly drawings (fabrication/).
// Boxes are kept in a uniform grid of cells, so a page of thousands of labels (a Yas patch's
// connections) costs about the labels times their candidates, not their square.
#include <Eigen/Core>

#include <vector>

namespace egg::drawing {

// An axis-aligned box in page units (any: px, mm), x0 <= x1, y0 <= y1.
struct LabelBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool overlaps(const LabelBox& o) const {
    return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
  LabelBox movedBy(double dx, double dy) const { return {x0 + dx, y0 + dy, x1 + dx, y1 + dy}; }
};

class LabelLayout {
 public:
  // Labels must stay inside `page`; `cell` is the grid's cell size, about a label's height.
  LabelLayout(const LabelBox& page, double cell);
  // Takes `box` whatever it overlaps (a marker that is drawn anyway, which labels must avoid).
  void reserve(const LabelBox& box);
  // True when `box` is inside the page and overlaps nothing taken.
  bool isFree(const LabelBox& box) const;
  // Takes `box` when it is free.
  bool placeBox(const LabelBox& box);
  // The first of `boxes` (in order of preference) that is free, taken; -1 when none is.
  int placeFirst(const std::vector<LabelBox>& boxes);
  const std::vector<LabelBox>& taken() const { return taken_; }
  const LabelBox& page() const { return page_; }

 private:
  template <class F>
  bool forCells(const LabelBox& box, F&& f) const;
  LabelBox page_;
  double cell_;
  int columns_ = 1, rows_ = 1;
  std::vector<std::vector<int>> cells_;  // indices into taken_, per cell (row-major)
  std::vector<LabelBox> taken_;
};

// Candidate centres around (x, y): the point itself, then rings of 8 directions (east first,
// counter-clockwise with y down) at steps of `step` out to `rings` rings.
std::vector<Eigen::Vector2d> candidatesAround(double x, double y, double step, int rings);

}  // namespace egg::drawing
