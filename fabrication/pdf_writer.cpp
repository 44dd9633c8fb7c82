#include "fabrication/pdf_writer.hpp"

#include "fabrication/pdf_pages.hpp"
#include "fabrication/stroke_text.hpp"

#include <cairo.h>

#include <cmath>
#include <cstdio>

namespace egg::fabrication {
namespace {

void setColour(cairo_t* cr, Layer layer) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(layerRgb(layer), "#%02x%02x%02x", &r, &g, &b);
  cairo_set_source_rgb(cr, r / 255.0, g / 255.0, b / 255.0);
}

// The sheet's content in its own millimetres (y up): the caller has set the transform.
void drawSheet(cairo_t* cr, const Drawing& d, double lineMm) {
  cairo_set_line_width(cr, lineMm);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  auto stroke = [&](Layer layer) {
    setColour(cr, layer);
    cairo_stroke(cr);
  };
  auto polyline = [&](const std::vector<Eigen::Vector2d>& points, bool closed) {
    cairo_move_to(cr, points[0].x(), points[0].y());
    for (size_t i = 1; i < points.size(); ++i) cairo_line_to(cr, points[i].x(), points[i].y());
    if (closed) cairo_close_path(cr);
  };
  for (const auto& c : d.circles) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.centre.x(), c.centre.y(), c.radius, 0.0, 2.0 * M_PI);
    stroke(c.layer);
  }
  for (const auto& s : d.slots) {
    const auto k = slotCorners(s);
    const Eigen::Vector2d u = k[1] - k[0];
    const double angle = std::atan2(u.y(), u.x());
    cairo_move_to(cr, k[0].x(), k[0].y());
    cairo_line_to(cr, k[1].x(), k[1].y());
    cairo_arc(cr, s.b.x(), s.b.y(), s.radius, angle - M_PI / 2.0, angle + M_PI / 2.0);
    cairo_line_to(cr, k[3].x(), k[3].y());
    cairo_arc(cr, s.a.x(), s.a.y(), s.radius, angle + M_PI / 2.0, angle + 3.0 * M_PI / 2.0);
    cairo_close_path(cr);
    stroke(s.layer);
  }
  for (const auto& p : d.polylines) {
    if (p.points.size() < 2) continue;
    polyline(p.points, p.closed);
    stroke(p.layer);
  }
  for (const auto& t : d.texts) {
    for (const auto& line : placedStrokes(t)) polyline(line, false);
    stroke(t.layer);
  }
}

// Page millimetres (y down) to the sheet's (y up) with the sheet's point (x0, y0) at the page's
// (px, py) - the upper left corner of what shows - at 1:n.
void sheetTransform(cairo_t* cr, double px, double py, double x0, double y1, double n) {
  cairo_translate(cr, px, py);
  cairo_scale(cr, 1.0 / n, -1.0 / n);
  cairo_translate(cr, -x0, -y1);
}

std::string sizeText(const Drawing& d) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.0f x %.0f mm", d.widthMm, d.heightMm);
  return buffer;
}

// Tiles at 1:1: columns and rows of the page's drawing area, portrait or landscape (fewer pages).
struct Tiling {
  PageFrame frame;
  int columns = 1, rows = 1;
};

Tiling tiling(const Drawing& d, PaperSize paper) {
  Tiling best;
  for (bool landscape : {true, false}) {
    Tiling t;
    t.frame = pageFrame(paper, landscape);
    t.columns = std::max(1, static_cast<int>(std::ceil(d.widthMm / t.frame.areaWidth - 1e-9)));
    t.rows = std::max(1, static_cast<int>(std::ceil(d.heightMm / t.frame.areaHeight - 1e-9)));
    if (landscape || t.columns * t.rows < best.columns * best.rows) best = t;
  }
  return best;
}

}  // namespace

int tilePageCount(const Drawing& sheet, PaperSize paper) {
  const Tiling t = tiling(sheet, paper);
  return t.columns * t.rows;
}

std::string toPdf(const std::vector<Drawing>& sheets, SheetPdf mode, PaperSize paper) {
  PdfDocument pdf;
  for (const auto& d : sheets) {
    if (mode == SheetPdf::TrueSize) {
      cairo_t* cr = pdf.beginPage(pageFrameOfSize(d.widthMm, d.heightMm));
      sheetTransform(cr, 0.0, 0.0, 0.0, d.heightMm, 1.0);
      drawSheet(cr, d, 0.0254);
      pdf.endPage();
      continue;
    }
    if (mode == SheetPdf::Fit) {
      const bool landscape = d.widthMm >= d.heightMm;
      const PageFrame f = pageFrame(paper, landscape);
      const double n = fittingScale({d.widthMm, d.heightMm}, {f.areaWidth, f.areaHeight});
      cairo_t* cr = pdf.beginPage(f);
      cairo_save(cr);
      sheetTransform(cr, f.areaX, f.areaY, 0.0, d.heightMm, n);
      // The sheet's edge in grey, then the parts; lines 0.25 mm on paper.
      cairo_rectangle(cr, 0.0, 0.0, d.widthMm, d.heightMm);
      cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
      cairo_set_line_width(cr, 0.25 * n);
      cairo_stroke(cr);
      drawSheet(cr, d, 0.25 * n);
      cairo_restore(cr);
      drawTitleBand(cr, f, d.title,
                    "sheet " + sizeText(d) + ", scale " + scaleText(n) + " on " + toString(paper) +
                        "; red cut, blue engrave, green label, grey reference",
                    n);
      pdf.endPage();
      continue;
    }
    const Tiling t = tiling(d, paper);
    const PageFrame& f = t.frame;
    for (int row = 0; row < t.rows; ++row) {
      for (int column = 0; column < t.columns; ++column) {
        cairo_t* cr = pdf.beginPage(f);
        const double x0 = column * f.areaWidth, y1 = d.heightMm - row * f.areaHeight;
        cairo_save(cr);
        cairo_rectangle(cr, f.areaX, f.areaY, f.areaWidth, f.areaHeight);
        cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
        cairo_set_line_width(cr, 0.2);
        cairo_stroke_preserve(cr);
        cairo_clip(cr);
        sheetTransform(cr, f.areaX, f.areaY, x0, y1, 1.0);
        drawSheet(cr, d, 0.25);
        cairo_restore(cr);
        char where[160];
        std::snprintf(where, sizeof where,
                      "tile row %d of %d, column %d of %d: x %.0f..%.0f mm, y %.0f..%.0f mm of "
                      "the sheet (%s) at 1:1 on %s",
                      row + 1, t.rows, column + 1, t.columns, x0,
                      std::min(d.widthMm, x0 + f.areaWidth), std::max(0.0, y1 - f.areaHeight), y1,
                      sizeText(d).c_str(), toString(paper));
        drawTitleBand(cr, f, d.title, where, 1.0);
        pdf.endPage();
      }
    }
  }
  return pdf.finish();
}

}  // namespace egg::fabrication
