#include "fabrication/pdf_pages.hpp"

#include "core/errors.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace egg::fabrication {
namespace {

constexpr double kBorderMm = 10.0, kTitleBandMm = 14.0;

cairo_status_t appendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void text(cairo_t* cr, double x, double y, double size, const std::string& s) {
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

// `s` broken at spaces into lines no wider than `width` at `size` (a word longer than the width
// gets a line of its own).
std::vector<std::string> wrapped(cairo_t* cr, const std::string& s, double size, double width) {
  cairo_set_font_size(cr, size);
  std::vector<std::string> lines{""};
  size_t from = 0;
  while (from <= s.size()) {
    const size_t to = std::min(s.find(' ', from), s.size());
    const std::string word = s.substr(from, to - from);
    const std::string trial = lines.back().empty() ? word : lines.back() + " " + word;
    cairo_text_extents_t e;
    cairo_text_extents(cr, trial.c_str(), &e);
    if (e.x_advance > width && !lines.back().empty())
      lines.push_back(word);
    else
      lines.back() = trial;
    from = to + 1;
  }
  return lines;
}

}  // namespace

PageFrame pageFrameOfSize(double widthMm, double heightMm) {
  PageFrame f;
  f.widthMm = widthMm;
  f.heightMm = heightMm;
  f.areaX = kBorderMm;
  f.areaY = kBorderMm;
  f.areaWidth = widthMm - 2.0 * kBorderMm;
  f.areaHeight = heightMm - 2.0 * kBorderMm - kTitleBandMm;
  return f;
}

PageFrame pageFrame(PaperSize paper, bool landscape) {
  const auto size = paperSizeMm(paper);
  return landscape ? pageFrameOfSize(size[1], size[0]) : pageFrameOfSize(size[0], size[1]);
}

double fittingScale(std::array<double, 2> extentMm, std::array<double, 2> areaMm) {
  const double least = std::max(extentMm[0] / areaMm[0], extentMm[1] / areaMm[1]);
  for (double decade = 1.0;; decade *= 10.0) {
    for (double step : {1.0, 2.0, 2.5, 5.0}) {
      if (step * decade >= least * (1.0 - 1e-12)) return step * decade;
    }
  }
}

std::string scaleText(double denominator) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "1:%g", denominator);
  return buffer;
}

PdfDocument::PdfDocument() {
  surface_ = cairo_pdf_surface_create_for_stream(appendToString, &bytes_, 595.0, 842.0);
  cr_ = cairo_create(surface_);
}

PdfDocument::~PdfDocument() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

cairo_t* PdfDocument::beginPage(const PageFrame& frame) {
  cairo_pdf_surface_set_size(surface_, frame.widthMm * kPointsPerMm, frame.heightMm * kPointsPerMm);
  cairo_save(cr_);
  cairo_scale(cr_, kPointsPerMm, kPointsPerMm);
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  return cr_;
}

void PdfDocument::endPage() {
  cairo_restore(cr_);
  cairo_show_page(cr_);
}

std::string PdfDocument::finish() {
  const cairo_status_t status = cairo_status(cr_);
  cairo_destroy(cr_);
  cr_ = nullptr;
  cairo_surface_finish(surface_);
  const cairo_status_t surfaceStatus = cairo_surface_status(surface_);
  cairo_surface_destroy(surface_);
  surface_ = nullptr;
  if (status != CAIRO_STATUS_SUCCESS || surfaceStatus != CAIRO_STATUS_SUCCESS) {
    throw WriteError(
        std::string("cairo could not write the PDF: ") +
        cairo_status_to_string(status != CAIRO_STATUS_SUCCESS ? status : surfaceStatus));
  }
  return std::move(bytes_);
}

void drawScaleBar(cairo_t* cr, double x, double y, double denominator, double maxPageMm) {
  // The longest round model length (1, 2 or 5 times a power of ten) whose bar fits.
  double length = 1.0;
  for (double decade = 1.0; decade < 1e9; decade *= 10.0) {
    for (double step : {1.0, 2.0, 5.0}) {
      if (step * decade / denominator <= maxPageMm) length = step * decade;
    }
  }
  const double page = length / denominator, h = 2.0;
  cairo_save(cr);
  cairo_set_line_width(cr, 0.2);
  for (int k = 0; k < 4; ++k) {
    cairo_rectangle(cr, x + k * page / 4.0, y, page / 4.0, h);
    cairo_set_source_rgb(cr, k % 2 ? 1.0 : 0.0, k % 2 ? 1.0 : 0.0, k % 2 ? 1.0 : 0.0);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_stroke(cr);
  }
  const bool metres = length >= 1000.0;
  char label[32];
  std::snprintf(label, sizeof label, metres ? "%g m" : "%g mm", metres ? length / 1000.0 : length);
  text(cr, x, y + h + 3.0, 2.5, "0");
  cairo_text_extents_t e;
  cairo_set_font_size(cr, 2.5);
  cairo_text_extents(cr, label, &e);
  text(cr, x + page - e.width, y + h + 3.0, 2.5, label);
  cairo_restore(cr);
}

void drawTitleBand(cairo_t* cr, const PageFrame& frame, const std::string& title,
                   const std::string& note, double denominator) {
  const double top = frame.heightMm - kBorderMm - kTitleBandMm + 2.0;
  cairo_save(cr);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_set_line_width(cr, 0.3);
  cairo_move_to(cr, kBorderMm, top - 1.0);
  cairo_line_to(cr, frame.widthMm - kBorderMm, top - 1.0);
  cairo_stroke(cr);
  text(cr, kBorderMm, top + 4.5, 4.0, title);
  const double barMax = std::min(80.0, frame.areaWidth / 4.0);
  const double barX = frame.widthMm - kBorderMm - barMax;
  // The note on one line left of the scale bar, else on two in a smaller size (what a page left
  // out, which must not run under the bar).
  const double noteWidth = barX - kBorderMm - 4.0;
  std::vector<std::string> lines = wrapped(cr, note, 2.8, noteWidth);
  if (lines.size() == 1) {
    text(cr, kBorderMm, top + 10.0, 2.8, note);
  } else {
    lines = wrapped(cr, note, 2.2, noteWidth);
    for (size_t k = 0; k < lines.size() && k < 2; ++k) {
      const bool cut = k == 1 && lines.size() > 2;
      text(cr, kBorderMm, top + 8.6 + 2.9 * static_cast<double>(k), 2.2,
           lines[k] + (cut ? " ..." : ""));
    }
  }
  text(cr, barX, top + 3.5, 3.0, "scale " + scaleText(denominator));
  drawScaleBar(cr, barX, top + 5.0, denominator, barMax);
  cairo_restore(cr);
}

}  // namespace egg::fabrication
