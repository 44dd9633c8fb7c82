#pragma once
// DXF (AutoCAD 2000, AC1015) of a drawing, through dxflib: $INSUNITS = 4 (millimetres), layers
// CUT (red), ENGRAVE (blue), LABEL (blue); holes as CIRCLE, slots as closed LWPOLYLINE with
// half-circle bulges, marks as LWPOLYLINE, labels as TEXT aligned at their middle.
#include "fabrication/drawing.hpp"

#include <string>

namespace egg::fabrication {

// The DXF text of `drawing`. Throws WriteError when dxflib cannot write its temporary file.
std::string toDxf(const Drawing& drawing);

}  // namespace egg::fabrication
