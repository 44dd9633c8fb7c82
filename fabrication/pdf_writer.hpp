#pragma once
// The PDF of cut sheets (cut/sheets.pdf), through cairo, in one of three ways
// (FabricationOptions::sheetPdf):
//  - fit: each sheet on one ISO page (landscape where the sheet is wider than high) at the largest
//    standard scale 1:n that fits, with a title band (the sheet's title, size, scale and paper)
//    and a scale bar;
//  - tile: each sheet at 1:1 over as many ISO pages as it takes (the orientation that takes fewer),
//    each page titled with its row and column and carrying a scale bar to check the print;
//  - true_size: one page of the sheet's own size per sheet, lines 0.0254 mm (0.001 in, the
//    hairline laser print drivers take as a vector cut).
// Layers in their colours (drawing.hpp), texts as single-stroke outlines (stroke_text.hpp).
#include "fabrication/drawing.hpp"
#include "fabrication/options.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

// Throws WriteError when cairo fails.
std::string toPdf(const std::vector<Drawing>& sheets, SheetPdf mode = SheetPdf::Fit,
                  PaperSize paper = PaperSize::A3);

// How many pages `toPdf` writes for one sheet in tile mode.
int tilePageCount(const Drawing& sheet, PaperSize paper);

}  // namespace egg::fabrication
