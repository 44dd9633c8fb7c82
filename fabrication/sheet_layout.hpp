#pragma once
// Lamella segments and stickers drawn onto a sheet (millimetres, y up). In a part's own frame x
// runs along the strip from its start and y across it, 0 .. w; the centreline is y = w/2. With h
// the label height (FabricationOptions::effectiveLabelHeightMm) and r the bolt radius:
//  - outline: a closed CUT rectangle;
//  - hole: a CUT circle of radius r at (x, w/2); slot: a CUT stadium from (x, w/2) to (x + slide,
//  w/2);
//  - connection id: LABEL text of height 0.7 h, left-aligned at (feature end + 0.25 h, w/2), or
//  ending
//    0.25 h before the feature where it would run off the segment (the single-stroke font's
//    widths);
//  - slide arrow: ENGRAVE polyline at y = (w/2 - r)/2, from x towards x + slide (at least 2 h
//  long),
//    with a two-stroke head at its tip;
//  - lamella id (with "k/n" when spliced): LABEL text of height h centred in the longest stretch of
//    the strip free of features and their labels;
//  - splice: ENGRAVE line across the strip at clearance/2 inside every spliced end; a scarf: at
//    the other piece's feather end (where the slope begins);
//  - a slot or hole a scarf cuts through (a slit of overlapping slots): a closed CUT polygon, the
//    part of its stadium inside the piece.
#include "fabrication/drawing.hpp"
#include "fabrication/lamella_plan.hpp"
#include "fabrication/stickers.hpp"

namespace egg::fabrication {

// The length of a text line in the single-stroke font (stroke_text.hpp).
double textLengthMm(const std::string& text, double heightMm);

// The sheet's REFERENCE layer: its outline and "<id>  <note>" in the bottom margin (text height
// 0.6 of the margin, 2..30 mm; with a margin under 2 mm the text overlaps the parts' band, but on
// a layer that is neither cut nor engraved).
void drawSheetFrame(const std::string& id, const std::string& note, double marginMm,
                    Drawing& drawing);

// Draws segment `segment` of `plan` with the part's lower left corner at `origin`.
void drawLamellaSegment(const LamellaPlan& plan, int segment, const Eigen::Vector2d& origin,
                        const FabricationOptions& options, Drawing& drawing);

// The outline of the stadium from (x0, 0) to (x1, 0) of the given radius clipped to lo <= x <= hi:
// a convex polygon (empty when they do not overlap).
std::vector<Eigen::Vector2d> clippedStadium(double x0, double x1, double radius, double lo,
                                            double hi);

// The text engraved as a segment's lamella label: the id, plus " k/n" when the lamella is spliced.
std::string segmentLabel(const LamellaPlan& plan, int segment);

// A sticker: CUT outline, the CUT slot (or hole) at the bolt, LABEL "connection id" and "lamella
// id" in the longer free end, at height min(h, 0.3 w).
void drawSticker(const Sticker& sticker, const Eigen::Vector2d& origin,
                 const FabricationOptions& options, Drawing& drawing);

}  // namespace egg::fabrication
