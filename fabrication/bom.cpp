#include "fabrication/fabricate.hpp"
#include "fabrication/fasteners.hpp"

#include <fmt/printf.h>
#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace egg::fabrication {
namespace {

// The sheets (or boards) lamella i's pieces are on, in piece order: "L03 L07".
std::string sheetsOf(const FabricationResult& r, size_t i) {
  std::string text;
  if (i >= r.pieceSheets.size()) return text;
  for (int sheet : r.pieceSheets[i]) {
    if (sheet < 0 || sheet >= static_cast<int>(r.sheetIds.size())) continue;
    text += (text.empty() ? "" : " ") + r.sheetIds[sheet];
  }
  return text;
}

// Bolts and washers by size: a bolt clamps two lamellas, three where both patches' members meet a
// shared boundary lamella at one hole (one layer more per further merged connection).
std::string fastenerRows(const FabricationResult& r) {
  const auto& o = r.options;
  std::map<int, int> boltsByLayers;  // layers -> bolts
  for (const auto& plan : r.lamellae) {
    for (const auto& f : plan.features) {
      if (f.alsoConnections.empty()) continue;
      ++boltsByLayers[2 + static_cast<int>(f.alsoConnections.size())];
    }
  }
  // Every other connection is a bolt through two lamellas.
  int total = r.connections;
  for (const auto& [layers, count] : boltsByLayers) total -= count;
  if (total > 0) boltsByLayers[2] += total;
  std::ostringstream s;
  for (const auto& [layers, count] : boltsByLayers) {
    const BoltSize b = boltSize(o.boltDiameterMm, layers * o.lamellaThicknessMm);
    s << "bolt_size," << b.name << "," << count << "," << fmt::sprintf("%.0f", b.lengthMm)
      << ",,,,,," << layers << " lamellas (grip " << fmt::sprintf("%.0f", b.gripMm) << " mm); "
      << b.note << "\n";
  }
  const BoltSize any = boltSize(o.boltDiameterMm, 2.0 * o.lamellaThicknessMm);
  s << "washer_size," << any.washerName << "," << 2 * r.connections << ",,,"
    << fmt::sprintf("%.1f", any.washerThicknessMm) << ",,,,two per bolt; " << any.washerNote
    << "\n";
  return s.str();
}

}  // namespace

std::string bomCsv(const FabricationResult& r) {
  std::ostringstream s;
  const auto& o = r.options;
  s << "item,id,count,length_mm,width_mm,thickness_mm,area_m2,volume_m3,mass_kg,note,sheet\n";
  char line[512];
  const double rho = r.material.densityKgM3;
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& p = r.lamellae[i];
    int holes = 0, slots = 0;
    for (const auto& f : p.features) (f.kind == FeatureKind::Slot ? slots : holes)++;
    const double volume = p.lengthMm * p.widthMm * o.lamellaThicknessMm * 1e-9;
    const char* notCut = p.unspliceable.empty()
                             ? ""
                             : "; NOT CUT: no splice position (report.json unspliceable_lamellae)";
    std::snprintf(line, sizeof line,
                  "lamella,%s,1,%.2f,%.2f,%.2f,,%.6g,%.6g,%s; %d holes; %d slots; %zu segments; "
                  "stress ratio %.3f%s,%s\n",
                  p.id.c_str(), p.lengthMm, p.widthMm, o.lamellaThicknessMm, volume, volume * rho,
                  r.material.name.c_str(), holes, slots, p.segments.size(), r.stress[i].stressRatio,
                  notCut, sheetsOf(r, i).c_str());
    s << line;
  }
  s << "splice,," << r.splices - r.scarfJoints
    << ",,,,,,,butt joints with bolted plates clear of holes by "
    << fmt::sprintf("%.1f", o.effectiveSpliceClearanceMm())
    << " mm where a stock length allows, else at least "
    << fmt::sprintf("%.1f", o.effectiveMinSpliceClearanceMm()) << " mm\n";
  if (r.scarfJoints > 0) {
    s << "scarf,," << r.scarfJoints << "," << fmt::sprintf("%.1f", o.scarfLengthMm())
      << ",,,,,,glued scarf joints 1:" << fmt::sprintf("%g", o.scarfSlope)
      << " to 1:" << fmt::sprintf("%g", 2.0 * o.scarfSlope)
      << " (length_mm: the shortest), glued before assembly; the pieces overlap on the slope\n";
  }
  // Every splice: where along its lamella (length_mm = the cut's distance from the strip's start).
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& p = r.lamellae[i];
    for (size_t k = 0; k < p.splicesMm.size(); ++k) {
      if (k < p.spliceIsScarf.size() && p.spliceIsScarf[k]) {
        std::snprintf(line, sizeof line,
                      "splice_joint,%s S%zu,1,%.2f,%.2f,%.2f,,,,scarf between pieces %zu and %zu; "
                      "feather ends %.1f mm from "
                      "the nearest hole or slot; %.0f mm long; stress ratio %.3f\n",
                      p.id.c_str(), k + 1, p.splicesMm[k], p.widthMm, o.lamellaThicknessMm, k + 1,
                      k + 2, p.spliceClearancesMm[k],
                      p.segments[k].endMm - p.segments[k + 1].startMm, r.stress[i].scarfRatios[k]);
      } else {
        std::snprintf(line, sizeof line,
                      "splice_joint,%s S%zu,1,%.2f,%.2f,%.2f,,,,between pieces %zu and %zu; %.1f "
                      "mm free each side\n",
                      p.id.c_str(), k + 1, p.splicesMm[k], p.widthMm, o.lamellaThicknessMm, k + 1,
                      k + 2, p.spliceClearancesMm[k]);
        s << line;
        // Its plates: one on each face, as long as the free length both sides of the cut allows
        // (at most twice splice_clearance_mm), the lamella's width; thickness and bolting of the
        // plates are the engineer's (not designed here).
        const double plate =
            2.0 * std::min(p.spliceClearancesMm[k], o.effectiveSpliceClearanceMm());
        std::snprintf(line, sizeof line,
                      "splice_plate,%s S%zu,2,%.1f,%.2f,,,,,one each face; the longest clear of "
                      "holes and slots; thickness and bolts by the engineer\n",
                      p.id.c_str(), k + 1, plate, p.widthMm);
      }
      s << line;
    }
  }
  s << "bolt,," << r.connections << ",,,,,,,diameter " << fmt::sprintf("%.1f", o.boltDiameterMm)
    << " mm; one per connection (merged on shared lamellas)\n";
  s << "washer,," << 2 * r.connections << ",,,,,,,two per bolt\n";
  s << fastenerRows(r);
  s << "brass_sleeve,," << r.counts.slots << ",,,,,,,one per slot (Section 3.5.1)\n";
  s << "ptfe_sticker,," << r.stickers.size() << ",,,," << fmt::sprintf("%.6g", r.stickerAreaM2)
    << ",,,two per notched connection (Section 3.5.1)\n";
  s << "support,," << r.supports.size() << ",,,,,,,see supports/supports.csv\n";
  for (const auto& bracket : r.ringBeamBrackets)
    s << "ring_beam_bracket," << bracket.endId << ",1,,,,,,,steel angle fixing the member end to "
      << bracket.lamellaId << " (its own layer: it butts against it); one bolt through each at "
      << "the holes engraved " << bracket.endId << "; size by the engineer\n";
  const bool boards = o.stock == CutStock::Boards;
  s << (boards ? "board,," : "lamella_sheet,,") << r.lamellaNesting.sheets << ","
    << (boards ? o.stockLengthMm : o.sheetMm[0]) << ","
    << (boards ? o.lamellaWidthMm : o.sheetMm[1]) << "," << o.lamellaThicknessMm << ",,,,yield "
    << fmt::sprintf("%.3f", r.lamellaNesting.yield) << "\n";
  for (size_t k = 0; k < r.sheetIds.size(); ++k) {
    s << (boards ? "board," : "lamella_sheet,") << r.sheetIds[k] << ",1,,,,,,,utilisation "
      << fmt::sprintf("%.3f", r.lamellaNesting.sheetUtilisation[k]) << "," << r.sheetIds[k] << "\n";
  }
  s << "sticker_sheet,," << r.stickerNesting.sheets << "," << o.effectiveStickerSheetMm()[0] << ","
    << o.effectiveStickerSheetMm()[1] << ",,,,,PTFE foil\n";
  s << "total_lamellae,," << r.lamellae.size() << ","
    << fmt::sprintf("%.2f", r.totalLengthM * 1000.0) << ",,,," << fmt::sprintf("%.6g", r.volumeM3)
    << "," << fmt::sprintf("%.6g", r.massKg) << ",self-weight "
    << fmt::sprintf("%.1f", r.massKg * 9.81) << " N\n";
  // Rows without a sheet get an empty last field: every row has the header's 11 fields.
  std::string padded;
  std::istringstream rows(s.str());
  for (std::string row; std::getline(rows, row);) {
    padded += row;
    if (std::count(row.begin(), row.end(), ',') == 9) padded += ',';
    padded += '\n';
  }
  return padded;
}

}  // namespace egg::fabrication
