#pragma once
// The labels of an assembly drawing page (assembly_drawings.cpp), laid out so that none overlaps
// another, a connection dot or a notch arrow (core/drawing/label_layout.hpp), and drawn last with
// a white mask so that the lines under them do not cut through the text. A label with no free spot
// is left out and counted: on a dense corner there is no room for every connection id, and an
// overlapped id is one a crew misreads. Page millimetres, y down.
#include "core/drawing/label_layout.hpp"
#include "fabrication/pdf_pages.hpp"

#include <Eigen/Core>

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

namespace egg::fabrication {

class PageLabels {
 public:
  static constexpr double kHaloMm = 0.25;
  PageLabels(cairo_t* cr, const PageFrame& f);
  // Keeps labels off a square of half side `half` around `centre` (a dot, a point of an arrow).
  void reserve(const Eigen::Vector2d& centre, double half);
  void reserve(const drawing::LabelBox& box) { layout_.reserve(box); }
  // A connection's dot and its notch arrows (page directions, `arrowLength` long).
  void reserveDot(const Eigen::Vector2d& q, double radius,
                  std::initializer_list<Eigen::Vector2d> arrows, double arrowLength);
  // The label's box as {width, height}: its advance and the font's ascent + descent, as a PDF
  // reader measures a word, plus the halo across.
  Eigen::Vector2d extent(const std::string& text, double size) const;
  // Takes the first of `centres` where the label's box is free; false when none is.
  bool place(const std::string& text, double size, const std::vector<Eigen::Vector2d>& centres,
             const std::array<double, 3>& rgb);
  // Centres beside a dot at `q` for a label of `box`: the four diagonal quadrants (right above
  // first), then right, left, above and below, `gap` from the dot.
  static std::vector<Eigen::Vector2d> besideDot(const Eigen::Vector2d& q,
                                                const Eigen::Vector2d& box, double gap);
  // Centres beyond a member's end `e`, going on along `d` (unit, page): further out step by step,
  // each also shifted a line to either side.
  static std::vector<Eigen::Vector2d> beyondEnd(const Eigen::Vector2d& e, const Eigen::Vector2d& d,
                                                const Eigen::Vector2d& box);
  // Draws every placed label: a white mask, then the text as PDF text (pdftotext reads it).
  void draw() const;

 private:
  struct Placed {
    std::string text;
    double size;
    Eigen::Vector2d centre;
    std::array<double, 3> rgb;
  };
  cairo_t* cr_;
  drawing::LabelLayout layout_;
  std::vector<Placed> placed_;
};

// Where a member's id may go on a page: its two visible ends and, for each, the direction the
// label moves away in (outwards at a real end, inwards where the page's window cut the member).
struct MemberLabelSpot {
  std::string id;
  bool isU = true;
  Eigen::Vector2d end[2];
  Eigen::Vector2d away[2];
};
struct PageLabelCounts {
  int connections = 0, connectionsLeftOut = 0, membersLeftOut = 0;
};

// Lamella ids first (at both ends; each lamella needs one), then the connections' ids beside
// their `dots` (already reserved with their arrows), in `connectionSize`; then draws them all.
PageLabelCounts layOutLabels(PageLabels& labels, const std::vector<MemberLabelSpot>& members,
                             const std::vector<std::string>& connectionIds,
                             const std::vector<Eigen::Vector2d>& dots, double connectionSize);

// The title band's words on what `counts` left out ("" when nothing), for patch `patchId`.
std::string leftOutNote(const PageLabelCounts& counts, int patchId);

}  // namespace egg::fabrication
