#pragma once
// DXF of a drawing through dxflib: AutoCAD 2000 (AC1015, $INSUNITS = 4, millimetres) or, for old
// CAM software, R12 (AC1009: POLYLINE instead of LWPOLYLINE, no units variable: the numbers are
// millimetres). One layer per operation, each its own colour index (drawing.hpp); holes as
// CIRCLE, slots as closed polylines with half-circle bulges, marks as polylines, labels as open
// polylines of single-stroke text (stroke_text.hpp): no TEXT entity, no font.
#include "fabrication/drawing.hpp"
#include "fabrication/options.hpp"

#include <string>

namespace egg::fabrication {

// The DXF text of `drawing`. Its header sets up printing on `paper` (turned to the drawing's
// shape): the drawing centred at the largest standard scale that fits, so that a CAD program's
// print (LibreCAD's) shows the whole sheet. Throws WriteError when dxflib cannot write.
std::string toDxf(const Drawing& drawing, DxfVersion version = DxfVersion::R2000,
                  PaperSize paper = PaperSize::A3);

}  // namespace egg::fabrication
