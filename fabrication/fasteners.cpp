#include "fabrication/fasteners.hpp"

#include <fmt/printf.h>
#include <cmath>
#include <cstdio>

namespace egg::fabrication {
namespace {

struct IsoBoltRow {
  double d, pitch, nut, washerInner, washerOuter, washerThickness;
};
// ISO 261 coarse pitch, ISO 4032 nut height m, ISO 7089 washer d1 x d2 x h.
constexpr IsoBoltRow kRows[] = {
    {6, 1.0, 5.2, 6.4, 12, 1.6},   {8, 1.25, 6.8, 8.4, 16, 1.6}, {10, 1.5, 8.4, 10.5, 20, 2.0},
    {12, 1.75, 10.8, 13, 24, 2.5}, {14, 2.0, 12.8, 15, 28, 2.5}, {16, 2.0, 14.8, 17, 30, 3.0},
    {20, 2.5, 18.0, 21, 37, 3.0},  {24, 3.0, 21.5, 25, 44, 4.0}, {30, 3.5, 25.6, 31, 56, 4.0}};

double standardLength(double mm) {
  const double step = mm <= 80.0 ? 5.0 : mm <= 200.0 ? 10.0 : 20.0;
  return std::ceil(mm / step - 1e-9) * step;
}

}  // namespace

BoltSize boltSize(double diameterMm, double gripMm) {
  BoltSize b;
  b.gripMm = gripMm;
  for (const IsoBoltRow& row : kRows) {
    if (std::abs(row.d - diameterMm) > 1e-9) continue;
    const double needed = gripMm + 2.0 * row.washerThickness + row.nut + 2.0 * row.pitch;
    b.lengthMm = standardLength(needed);
    b.name = fmt::sprintf("M%gx%g", row.d, b.lengthMm);
    b.note = fmt::sprintf("grip + 2 washers + nut %.1f mm + 2 pitches = %.1f mm; rounded up",
                          row.nut, needed) +
             "; add the PTFE stickers' thickness";
    b.washerName =
        fmt::sprintf("ISO 7089 %gx%gx%g", row.washerInner, row.washerOuter, row.washerThickness);
    b.washerThicknessMm = row.washerThickness;
    b.washerNote = "for M" + fmt::sprintf("%g", row.d);
    return b;
  }
  b.lengthMm = gripMm;
  b.name = fmt::sprintf("d%gx%g", diameterMm, gripMm);
  b.note =
      "not a standard metric size (M6..M30): length_mm is the grip alone; size bolt; nut and "
      "washers with the supplier";
  b.washerName = fmt::sprintf("d%g", diameterMm);
  b.washerNote = "not a standard metric size: size with the supplier";
  return b;
}

}  // namespace egg::fabrication
