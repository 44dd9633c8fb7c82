#include "fabrication/pdf_writer.hpp"

#include "core/errors.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>

namespace egg::fabrication {
namespace {

constexpr double kPointsPerMm = 72.0 / 25.4;

cairo_status_t appendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void setColour(cairo_t* cr, Layer layer) {
  if (layer == Layer::Cut) {
    cairo_set_source_rgb(cr, 1.0, 0.0, 0.0);
  } else {
    cairo_set_source_rgb(cr, 0.0, 0.0, 1.0);
  }
}

void stroke(cairo_t* cr, Layer layer) {
  setColour(cr, layer);
  // A hairline does not show on paper: 0.1 mm, in the page's millimetre units.
  cairo_set_line_width(cr, 0.1);
  cairo_stroke(cr);
}

void drawPage(cairo_t* cr, const Drawing& d) {
  cairo_save(cr);
  // Millimetres with y up, origin at the sheet's lower left corner.
  cairo_scale(cr, kPointsPerMm, kPointsPerMm);
  cairo_translate(cr, 0.0, d.heightMm);
  cairo_scale(cr, 1.0, -1.0);
  // The sheet outline in grey, for orientation only (not a cut).
  cairo_rectangle(cr, 0.0, 0.0, d.widthMm, d.heightMm);
  cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
  cairo_set_line_width(cr, 0.2);
  cairo_stroke(cr);
  for (const auto& c : d.circles) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.centre.x(), c.centre.y(), c.radius, 0.0, 2.0 * M_PI);
    stroke(cr, c.layer);
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
    stroke(cr, s.layer);
  }
  for (const auto& p : d.polylines) {
    if (p.points.size() < 2) continue;
    cairo_move_to(cr, p.points[0].x(), p.points[0].y());
    for (size_t i = 1; i < p.points.size(); ++i)
      cairo_line_to(cr, p.points[i].x(), p.points[i].y());
    if (p.closed) cairo_close_path(cr);
    stroke(cr, p.layer);
  }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  for (const auto& t : d.texts) {
    cairo_save(cr);
    cairo_translate(cr, t.anchor.x(), t.anchor.y());
    cairo_scale(cr, 1.0, -1.0);  // text upright again
    cairo_set_font_size(cr, t.height);
    cairo_text_extents_t e;
    cairo_text_extents(cr, t.text.c_str(), &e);
    const double x = t.align == TextAlign::Left ? -e.x_bearing : -(e.x_bearing + e.width / 2.0);
    cairo_move_to(cr, x, -(e.y_bearing + e.height / 2.0));
    setColour(cr, t.layer);
    cairo_show_text(cr, t.text.c_str());
    cairo_restore(cr);
  }
  cairo_restore(cr);
}

}  // namespace

std::string toPdf(const std::vector<Drawing>& pages) {
  std::string bytes;
  const double w0 = pages.empty() ? 210.0 : pages[0].widthMm,
               h0 = pages.empty() ? 297.0 : pages[0].heightMm;
  cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(
      appendToString, &bytes, w0 * kPointsPerMm, h0 * kPointsPerMm);
  cairo_t* cr = cairo_create(surface);
  for (const auto& page : pages) {
    cairo_pdf_surface_set_size(surface, page.widthMm * kPointsPerMm, page.heightMm * kPointsPerMm);
    drawPage(cr, page);
    cairo_show_page(cr);
  }
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t surfaceStatus = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS || surfaceStatus != CAIRO_STATUS_SUCCESS) {
    throw WriteError(
        std::string("cairo could not write the PDF: ") +
        cairo_status_to_string(status != CAIRO_STATUS_SUCCESS ? status : surfaceStatus));
  }
  return bytes;
}

}  // namespace egg::fabrication
