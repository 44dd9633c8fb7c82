#pragma once
// Bolt, nut and washer sizes for the bill of materials: metric hexagon bolts with ISO 4032 nuts and
// ISO 7089 washers, from a table of the standard sizes M6..M30 (coarse thread).
#include <string>

namespace egg::fabrication {

struct BoltSize {
  std::string name;        // "M16x150", or "d16x150" where the diameter is not a standard size
  double lengthMm = 0.0;   // rounded up to the standard steps (5 mm to 80, 10 to 200, then 20)
  double gripMm = 0.0;     // what it clamps
  std::string note;        // how the length is made up
  std::string washerName;  // "ISO 7089 17x30x3"
  double washerThicknessMm = 0.0;
  std::string washerNote;
};

// The bolt of diameter `diameterMm` (fabrication.bolt_diameter_mm) through `gripMm` of lamellas:
// grip + two washers + the nut + two thread pitches beyond it, rounded up to a standard length.
// A diameter not in the table gets the grip alone and a note to size it with the supplier.
BoltSize boltSize(double diameterMm, double gripMm);

}  // namespace egg::fabrication
