#include "fabrication/nesting.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <numeric>
#include <sstream>

namespace egg::fabrication {
namespace {

struct Shelf {
  int sheet = 0;
  double yMm = 0.0, heightMm = 0.0, usedMm = 0.0;  // usedMm: length taken along x, kerfs included
};

}  // namespace

Nesting nestParts(const std::vector<NestPart>& parts, std::array<double, 2> sheetMm, double kerfMm,
                  double marginMm, const std::string& field) {
  const double usableX = sheetMm[0] - 2.0 * marginMm, usableY = sheetMm[1] - 2.0 * marginMm;
  constexpr double slack = 1e-9;
  for (const auto& p : parts) {
    if (p.lengthMm > usableX + slack || p.widthMm > usableY + slack) {
      std::ostringstream msg;
      msg << field << ": part " << p.name << " (" << p.lengthMm << " x " << p.widthMm
          << " mm) does not fit a " << sheetMm[0] << " x " << sheetMm[1] << " mm sheet with a "
          << marginMm << " mm margin";
      if (p.lengthMm > usableX + slack && p.lengthMm <= usableY + slack)
        msg << " (strips run along the sheet's first side)";
      if (p.lengthMm > usableX + slack && field == "fabrication.sheet_mm") {
        msg << "; a shorter fabrication.stock_length_mm splices long lamellas";
      }
      throw InvalidInput(msg.str());
    }
  }
  std::vector<size_t> order(parts.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (parts[a].widthMm != parts[b].widthMm) return parts[a].widthMm > parts[b].widthMm;
    return parts[a].lengthMm > parts[b].lengthMm;
  });
  Nesting out;
  out.placements.resize(parts.size());
  std::vector<Shelf> shelves;
  std::vector<double> sheetTop;  // next free y on each sheet (relative to the margin)
  for (size_t index : order) {
    const NestPart& p = parts[index];
    Shelf* target = nullptr;
    for (auto& shelf : shelves) {
      const double x = shelf.usedMm == 0.0 ? 0.0 : shelf.usedMm + kerfMm;
      if (p.widthMm <= shelf.heightMm + slack && x + p.lengthMm <= usableX + slack) {
        target = &shelf;
        break;
      }
    }
    if (!target) {
      int sheet = -1;
      for (size_t s = 0; s < sheetTop.size(); ++s) {
        const double y = sheetTop[s] == 0.0 ? 0.0 : sheetTop[s] + kerfMm;
        if (y + p.widthMm <= usableY + slack) {
          sheet = static_cast<int>(s);
          break;
        }
      }
      if (sheet < 0) {
        sheet = static_cast<int>(sheetTop.size());
        sheetTop.push_back(0.0);
      }
      const double y = sheetTop[sheet] == 0.0 ? 0.0 : sheetTop[sheet] + kerfMm;
      shelves.push_back({sheet, y, p.widthMm, 0.0});
      sheetTop[sheet] = y + p.widthMm;
      target = &shelves.back();
    }
    const double x = target->usedMm == 0.0 ? 0.0 : target->usedMm + kerfMm;
    out.placements[index] = {target->sheet, marginMm + x, marginMm + target->yMm};
    target->usedMm = x + p.lengthMm;
  }
  out.sheets = static_cast<int>(sheetTop.size());
  double partArea = 0.0;
  for (const auto& p : parts) partArea += p.lengthMm * p.widthMm;
  out.yield = out.sheets > 0 ? partArea / (out.sheets * sheetMm[0] * sheetMm[1]) : 0.0;
  return out;
}

}  // namespace egg::fabrication
