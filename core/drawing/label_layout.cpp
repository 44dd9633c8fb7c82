#include "core/drawing/label_layout.hpp"

#include <algorithm>
#include <cmath>

namespace egg::drawing {

LabelLayout::LabelLayout(const LabelBox& page, double cell)
    : page_(page), cell_(std::max(cell, 1e-9)) {
  // At most 512 cells a side: a cell far smaller than the labels only costs memory.
  cell_ = std::max({cell_, (page_.x1 - page_.x0) / 512.0, (page_.y1 - page_.y0) / 512.0});
  columns_ = std::max(1, static_cast<int>(std::ceil((page_.x1 - page_.x0) / cell_)));
  rows_ = std::max(1, static_cast<int>(std::ceil((page_.y1 - page_.y0) / cell_)));
  cells_.resize(static_cast<size_t>(columns_) * rows_);
}

// Calls f(cell list) for every cell `box` touches (boxes reaching off the page are clamped to
// its edge cells); stops and returns false as soon as f does.
template <class F>
bool LabelLayout::forCells(const LabelBox& box, F&& f) const {
  const auto column = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - page_.x0) / cell_)), 0, columns_ - 1);
  };
  const auto row = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - page_.y0) / cell_)), 0, rows_ - 1);
  };
  for (int r = row(box.y0), r1 = row(box.y1); r <= r1; ++r)
    for (int c = column(box.x0), c1 = column(box.x1); c <= c1; ++c)
      if (!f(static_cast<size_t>(r) * columns_ + c)) return false;
  return true;
}

void LabelLayout::reserve(const LabelBox& box) {
  const int index = static_cast<int>(taken_.size());
  taken_.push_back(box);
  forCells(box, [&](size_t cell) {
    cells_[cell].push_back(index);
    return true;
  });
}

bool LabelLayout::isFree(const LabelBox& box) const {
  if (box.x0 < page_.x0 || box.y0 < page_.y0 || box.x1 > page_.x1 || box.y1 > page_.y1)
    return false;
  return forCells(box, [&](size_t cell) {
    return std::none_of(cells_[cell].begin(), cells_[cell].end(),
                        [&](int k) { return taken_[static_cast<size_t>(k)].overlaps(box); });
  });
}

bool LabelLayout::placeBox(const LabelBox& box) {
  if (!isFree(box)) return false;
  reserve(box);
  return true;
}

int LabelLayout::placeFirst(const std::vector<LabelBox>& boxes) {
  for (size_t k = 0; k < boxes.size(); ++k)
    if (placeBox(boxes[k])) return static_cast<int>(k);
  return -1;
}

std::vector<Eigen::Vector2d> candidatesAround(double x, double y, double step, int rings) {
  std::vector<Eigen::Vector2d> out{{x, y}};
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < 8; ++k) {
      const double a = k * M_PI / 4.0;
      out.emplace_back(x + r * step * std::cos(a), y - r * step * std::sin(a));
    }
  return out;
}

}  // namespace egg::drawing
