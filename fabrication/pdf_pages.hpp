#pragma once
// A multi-page PDF on ISO 216 pages through cairo, with what every printed drawing carries: a
// title band (title, what is shown, the scale) and a scale bar, so that a print can be checked
// with a ruler whatever the printer did to it. Page coordinates are millimetres, y down, origin at
// the page's upper left corner. Used by pdf_writer (sheets.pdf) and assembly_drawings.
#include "fabrication/options.hpp"

#include <array>
#include <string>

// cairo's own declaration (cairo.h), so that this header does not need cairo's include path.
typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace egg::fabrication {

inline constexpr double kPointsPerMm = 72.0 / 25.4;

// A page's drawing area: the page less a 10 mm border and a 14 mm title band at the bottom.
struct PageFrame {
  double widthMm = 0.0, heightMm = 0.0;  // the page
  double areaX = 0.0, areaY = 0.0, areaWidth = 0.0, areaHeight = 0.0;
};
PageFrame pageFrame(PaperSize paper, bool landscape);
PageFrame pageFrameOfSize(double widthMm, double heightMm);

// The denominator n of the largest standard scale 1:n (1, 2, 2.5, 5 times a power of ten) at
// which `extentMm` fits `areaMm`.
double fittingScale(std::array<double, 2> extentMm, std::array<double, 2> areaMm);

// "1:20", "1:2.5".
std::string scaleText(double denominator);

class PdfDocument {
 public:
  PdfDocument();
  ~PdfDocument();
  PdfDocument(const PdfDocument&) = delete;
  PdfDocument& operator=(const PdfDocument&) = delete;
  // Starts a page of the frame's size and returns the context in page millimetres (y down).
  cairo_t* beginPage(const PageFrame& frame);
  void endPage();
  // The PDF's bytes. Throws WriteError when cairo failed.
  std::string finish();

 private:
  std::string bytes_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

// The title band of a page: the title left, `note` below it, `scale` (e.g. "1:20 on A3") and a
// scale bar of a round length at 1:`denominator` right.
void drawTitleBand(cairo_t* cr, const PageFrame& frame, const std::string& title,
                   const std::string& note, double denominator);

// A scale bar with its left end at (x, y) on the page: four alternating segments of a round
// length in model millimetres (at most `maxPageMm` long on the page), labelled in mm or m.
void drawScaleBar(cairo_t* cr, double x, double y, double denominator, double maxPageMm);

}  // namespace egg::fabrication
