#pragma once
// Nesting of rectangular parts (lamella strips, PTFE stickers) on stock sheets. Strips do not turn
// (plywood's face grain runs along a lamella), so the problem is one of cutting stock: parts are
// packed end to end into rows along the sheet's first side (a one-dimensional bin packing, rows of
// the usable length), then rows are stacked onto sheets. Rows are packed two ways, best-fit
// decreasing (each part, longest first, into the row it leaves the least room in) and by minimum
// bin slack (each row, started with the longest part left, filled by the subset of the others
// that leaves least room), each followed by trying to dissolve its emptiest rows into the others;
// the one with fewer sheets is kept. shelfSheets reports what the first-fit shelves eggshell used
// before take, for comparison.
// Sheets hold their fullest rows first, so the last sheet's offcut is the largest.
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
  double yield = 0.0;                    // parts' area over the sheets' area
  std::vector<double> sheetUtilisation;  // per sheet: its parts' area over its area
  int rows = 0;                          // rows of parts
  int rowsLowerBound = 0;                // no packing has fewer rows (binPackingLowerBound)
  int shelfSheets = 0;                   // what first-fit shelves (eggshell before issue 38) take
};

// Places every part at least `marginMm` inside a sheet of `sheetMm` and `gapMm` (kerf, or a
// router bit) from its neighbours. Throws InvalidInput naming the part and `field` (e.g.
// "fabrication.sheet_mm") when a part does not fit an empty sheet.
Nesting nestParts(const std::vector<NestPart>& parts, std::array<double, 2> sheetMm, double gapMm,
                  double marginMm, const std::string& field);

// A number of bins that no packing of `sizes` into bins of `capacity` goes below: the larger of
// ceil(sum / capacity) and Martello and Toth's L2 (parts above half the capacity each need a bin
// of their own, and what they leave free bounds what smaller parts can share). Equal to the rows
// nestParts() found, it proves them the fewest.
int binPackingLowerBound(std::vector<double> sizes, double capacity);

// The second side of a sheet that holds `rows` rows of strips `stripWidthMm` wide exactly:
// rows w + (rows - 1) gap + 2 margin.
double sheetWidthForRows(int rows, double stripWidthMm, double gapMm, double marginMm);

// The sheet width that wastes least for strips of one width: of the widths that hold exactly as
// many rows as `sheetMm` does and one row more, the one with the higher yield when the parts are
// nested on it (ties: the narrower).
struct SheetWidthSuggestion {
  double widthMm = 0.0;  // the sheet's second side
  int rowsPerSheet = 0;
  int sheets = 0;
  double yield = 0.0;
};
SheetWidthSuggestion suggestSheetWidth(const std::vector<NestPart>& parts,
                                       std::array<double, 2> sheetMm, double gapMm,
                                       double marginMm);

}  // namespace egg::fabrication
