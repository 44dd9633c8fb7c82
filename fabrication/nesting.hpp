#pragma once
// Nesting of rectangular parts (lamella strips, PTFE stickers) on stock sheets: shelf packing,
// first fit by decreasing height then length. Strips all share one width, so for lamellas the
// shelves are rows of strips laid end to end along the sheet's first side.
#include <array>
#include <string>
#include <vector>

namespace egg::fabrication {

struct NestPart {
  std::string name;       // for the error message of a part that does not fit
  double lengthMm = 0.0;  // along the sheet's first side (x)
  double widthMm = 0.0;   // along the second side (y)
};

struct NestPlacement {
  int sheet = 0;
  double xMm = 0.0, yMm = 0.0;  // lower left corner of the part on its sheet (y up)
};

struct Nesting {
  std::vector<NestPlacement> placements;  // one per part, in the input order
  int sheets = 0;
  double yield = 0.0;  // parts' area over the sheets' area
};

// Places every part at least `marginMm` inside a sheet of `sheetMm` and `kerfMm` from its
// neighbours. Throws InvalidInput naming the part and `field` (e.g. "fabrication.sheet_mm") when a
// part does not fit an empty sheet.
Nesting nestParts(const std::vector<NestPart>& parts, std::array<double, 2> sheetMm, double kerfMm,
                  double marginMm, const std::string& field);

}  // namespace egg::fabrication
