#include "fabrication/assembly_labels.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <cmath>

namespace egg::fabrication {

PageLabels::PageLabels(cairo_t* cr, const PageFrame& f)
    : cr_(cr), layout_({f.areaX, f.areaY, f.areaX + f.areaWidth, f.areaY + f.areaHeight}, 2.0) {}

void PageLabels::reserve(const Eigen::Vector2d& centre, double half) {
  layout_.reserve({centre.x() - half, centre.y() - half, centre.x() + half, centre.y() + half});
}

void PageLabels::reserveDot(const Eigen::Vector2d& q, double radius,
                            std::initializer_list<Eigen::Vector2d> arrows, double arrowLength) {
  reserve(q, radius + 0.1);
  for (const Eigen::Vector2d& a : arrows) {
    if (a.norm() <= 0.0) continue;
    for (double t : {0.35, 0.7, 1.0}) reserve(q + t * arrowLength * a.normalized(), 0.45);
  }
}

Eigen::Vector2d PageLabels::extent(const std::string& text, double size) const {
  cairo_set_font_size(cr_, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr_, text.c_str(), &e);
  cairo_font_extents_t fe;
  cairo_font_extents(cr_, &fe);
  return {e.x_advance + 2.0 * kHaloMm, fe.ascent + fe.descent};
}

bool PageLabels::place(const std::string& text, double size,
                       const std::vector<Eigen::Vector2d>& centres,
                       const std::array<double, 3>& rgb) {
  const Eigen::Vector2d half = 0.5 * extent(text, size);
  for (const auto& c : centres) {
    if (layout_.placeBox(
            {c.x() - half.x(), c.y() - half.y(), c.x() + half.x(), c.y() + half.y()})) {
      placed_.push_back({text, size, c, rgb});
      return true;
    }
  }
  return false;
}

std::vector<Eigen::Vector2d> PageLabels::besideDot(const Eigen::Vector2d& q,
                                                   const Eigen::Vector2d& box, double gap) {
  const double x = 0.5 * box.x() + gap, y = 0.5 * box.y() + 0.5 * gap;
  return {q + Eigen::Vector2d(x, -y),
          q + Eigen::Vector2d(x, y),
          q + Eigen::Vector2d(-x, -y),
          q + Eigen::Vector2d(-x, y),
          q + Eigen::Vector2d(x, 0),
          q + Eigen::Vector2d(-x, 0),
          q + Eigen::Vector2d(0, -y - 0.5 * box.y()),
          q + Eigen::Vector2d(0, y + 0.5 * box.y())};
}

std::vector<Eigen::Vector2d> PageLabels::beyondEnd(const Eigen::Vector2d& e,
                                                   const Eigen::Vector2d& d,
                                                   const Eigen::Vector2d& box) {
  const double along = 0.5 * (std::abs(d.x()) * box.x() + std::abs(d.y()) * box.y());
  const Eigen::Vector2d n(-d.y(), d.x());
  std::vector<Eigen::Vector2d> out;
  for (double gap : {1.0, 3.5, 6.0, 8.5, 11.0}) {
    const Eigen::Vector2d c = e + (gap + along) * d;
    for (double side : {0.0, 1.0, -1.0}) out.push_back(c + side * (box.y() + 0.3) * n);
  }
  return out;
}

void PageLabels::draw() const {
  for (const auto& l : placed_) {
    cairo_set_font_size(cr_, l.size);
    cairo_text_extents_t e;
    cairo_text_extents(cr_, l.text.c_str(), &e);
    cairo_font_extents_t fe;
    cairo_font_extents(cr_, &fe);
    // The box of extent() centred: its left at the advance's start, the baseline where the
    // ascent above and the descent below fill it.
    const double x = l.centre.x() - 0.5 * e.x_advance,
                 y = l.centre.y() + 0.5 * (fe.ascent - fe.descent);
    // A white mask behind the text (the label's box less a hair, as CAD text masks do): four
    // numbers a label, where a halo stroked along the glyphs' outlines made the Yas's drawings
    // 28 MB.
    cairo_new_path(cr_);
    cairo_rectangle(cr_, l.centre.x() - 0.5 * e.x_advance - 0.5 * kHaloMm,
                    l.centre.y() - 0.5 * (fe.ascent + fe.descent) + 0.1, e.x_advance + kHaloMm,
                    fe.ascent + fe.descent - 0.2);
    cairo_set_source_rgb(cr_, 1, 1, 1);
    cairo_fill(cr_);
    cairo_set_source_rgb(cr_, l.rgb[0], l.rgb[1], l.rgb[2]);
    cairo_move_to(cr_, x, y);
    cairo_show_text(cr_, l.text.c_str());
  }
}

PageLabelCounts layOutLabels(PageLabels& labels, const std::vector<MemberLabelSpot>& members,
                             const std::vector<std::string>& connectionIds,
                             const std::vector<Eigen::Vector2d>& dots, double connectionSize) {
  PageLabelCounts counts;
  for (const auto& m : members) {
    const std::array<double, 3> rgb{m.isU ? 0.75 : 0.0, 0.0, m.isU ? 0.0 : 0.75};
    const Eigen::Vector2d box = labels.extent(m.id, 2.2);
    const bool first =
        labels.place(m.id, 2.2, PageLabels::beyondEnd(m.end[0], m.away[0], box), rgb);
    const bool second =
        labels.place(m.id, 2.2, PageLabels::beyondEnd(m.end[1], m.away[1], box), rgb);
    if (!first && !second) ++counts.membersLeftOut;
  }
  counts.connections = static_cast<int>(connectionIds.size());
  for (size_t k = 0; k < connectionIds.size(); ++k) {
    const Eigen::Vector2d box = labels.extent(connectionIds[k], connectionSize);
    if (!labels.place(connectionIds[k], connectionSize, PageLabels::besideDot(dots[k], box, 0.6),
                      {0, 0, 0}))
      ++counts.connectionsLeftOut;
  }
  labels.draw();
  return counts;
}

std::string leftOutNote(const PageLabelCounts& counts, int patchId) {
  std::string note;
  if (counts.connectionsLeftOut > 0)
    note += fmt::format(
        "; {} of {} connection ids left out where they would overlap (P{}-Ci-j is where u "
        "lamella i crosses v lamella j)",
        counts.connectionsLeftOut, counts.connections, patchId);
  if (counts.membersLeftOut > 0)
    note += fmt::format("; {} lamella ids found no room (see the assembly order)",
                        counts.membersLeftOut);
  return note;
}

}  // namespace egg::fabrication
