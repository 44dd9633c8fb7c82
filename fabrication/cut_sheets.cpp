#include "fabrication/cut_sheets.hpp"

#include "fabrication/sheet_layout.hpp"

#include <cstdio>

namespace egg::fabrication {
namespace {

std::string idOf(char kind, int index) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%c%02d", kind, index + 1);
  return buffer;
}

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f %%", 100.0 * fraction);
  return buffer;
}

std::string size(double a, double b, double t) {
  char buffer[96];
  if (t > 0.0) {
    std::snprintf(buffer, sizeof buffer, "%.0f x %.0f x %.0f mm", a, b, t);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.0f x %.0f mm", a, b);
  }
  return buffer;
}

std::vector<Drawing> sheetsFor(const Nesting& n, std::array<double, 2> sizeMm, char kind,
                               const std::string& what, const std::string& stock, double marginMm,
                               std::vector<std::string>& ids) {
  std::vector<Drawing> sheets(n.sheets);
  ids.clear();
  for (int i = 0; i < n.sheets; ++i) {
    ids.push_back(idOf(kind, i));
    sheets[i].title = what + " " + ids.back() + " (" + std::to_string(i + 1) + " of " +
                      std::to_string(n.sheets) + ")";
    sheets[i].widthMm = sizeMm[0];
    sheets[i].heightMm = sizeMm[1];
    drawSheetFrame(ids.back(),
                   what + " " + std::to_string(i + 1) + "/" + std::to_string(n.sheets) + ", " +
                       stock + ", " + percent(n.sheetUtilisation[i]) + " used",
                   marginMm, sheets[i]);
  }
  return sheets;
}

}  // namespace

void layOutCutSheets(FabricationResult& r) {
  const auto& o = r.options;
  const double gap = o.partGapMm();
  std::vector<NestPart> parts;
  std::vector<std::pair<int, int>> partOf;  // (lamella, segment)
  r.pieceSheets.assign(r.lamellae.size(), {});
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& plan = r.lamellae[i];
    r.pieceSheets[i].assign(plan.segments.size(), -1);
    for (size_t k = 0; k < plan.segments.size(); ++k) {
      parts.push_back(
          {segmentLabel(plan, static_cast<int>(k)), plan.segments[k].lengthMm(), plan.widthMm});
      partOf.emplace_back(static_cast<int>(i), static_cast<int>(k));
    }
  }
  const std::string material = r.material.name;
  if (o.stock == CutStock::Boards) {
    // A board is one row: nest on a "sheet" one strip wide plus its margins, then draw the board
    // at its own width (margins only at its two trimmed ends).
    const double w = o.lamellaWidthMm;
    r.lamellaNesting = nestParts(parts, {o.stockLengthMm, w + 2.0 * o.marginMm}, gap, o.marginMm,
                                 "fabrication.stock_length_mm");
    for (auto& p : r.lamellaNesting.placements) p.yMm -= o.marginMm;
    for (auto& u : r.lamellaNesting.sheetUtilisation) u *= (w + 2.0 * o.marginMm) / w;
    r.lamellaNesting.yield *= (w + 2.0 * o.marginMm) / w;
    r.sheets =
        sheetsFor(r.lamellaNesting, {o.stockLengthMm, w}, 'B', "board",
                  size(o.stockLengthMm, w, o.lamellaThicknessMm) + " " + material, 0.0, r.sheetIds);
  } else {
    r.lamellaNesting = nestParts(parts, o.sheetMm, gap, o.marginMm, "fabrication.sheet_mm");
    r.sheetWidthSuggestion = suggestSheetWidth(parts, o.sheetMm, gap, o.marginMm);
    r.sheets = sheetsFor(r.lamellaNesting, o.sheetMm, 'L', "lamella sheet",
                         size(o.sheetMm[0], o.sheetMm[1], o.lamellaThicknessMm) + " " + material,
                         o.marginMm, r.sheetIds);
  }
  for (size_t p = 0; p < parts.size(); ++p) {
    const auto& at = r.lamellaNesting.placements[p];
    drawLamellaSegment(r.lamellae[partOf[p].first], partOf[p].second, {at.xMm, at.yMm}, o,
                       r.sheets[at.sheet]);
    r.pieceSheets[partOf[p].first][partOf[p].second] = at.sheet;
  }

  std::vector<NestPart> stickerParts;
  for (const auto& s : r.stickers)
    stickerParts.push_back({"sticker " + s.id, s.lengthMm, s.widthMm});
  const auto foil = o.effectiveStickerSheetMm();
  r.stickerNesting = nestParts(stickerParts, foil, gap, o.marginMm, "fabrication.sticker_sheet_mm");
  r.stickerSheets =
      sheetsFor(r.stickerNesting, foil, 'F', "PTFE sticker sheet",
                size(foil[0], foil[1], 0.0) + " PTFE foil", o.marginMm, r.stickerSheetIds);
  for (size_t p = 0; p < r.stickers.size(); ++p) {
    const auto& at = r.stickerNesting.placements[p];
    drawSticker(r.stickers[p], {at.xMm, at.yMm}, o, r.stickerSheets[at.sheet]);
  }
}

std::string boardsCsv(const FabricationResult& r) {
  std::string out = "board,piece,lamella,from_mm,to_mm,length_mm,waste_mm\n";
  // Pieces board by board, in their order along the board.
  struct Entry {
    int board;
    double x, length;
    std::string piece, lamella;
  };
  std::vector<Entry> entries;
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& plan = r.lamellae[i];
    for (size_t k = 0; k < plan.segments.size(); ++k) {
      entries.push_back({r.pieceSheets[i][k], 0.0, plan.segments[k].lengthMm(),
                         segmentLabel(plan, static_cast<int>(k)), plan.id});
    }
  }
  size_t p = 0;
  for (auto& e : entries) e.x = r.lamellaNesting.placements[p++].xMm;
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.board != b.board ? a.board < b.board : a.x < b.x;
  });
  char line[256];
  for (size_t k = 0; k < entries.size(); ++k) {
    const auto& e = entries[k];
    const bool last = k + 1 == entries.size() || entries[k + 1].board != e.board;
    // The waste after the board's last piece: up to its end (the trimmed end included).
    const double waste = last ? r.options.stockLengthMm - (e.x + e.length) : 0.0;
    std::snprintf(line, sizeof line, "%s,%s,%s,%.1f,%.1f,%.1f,%.1f\n", r.sheetIds[e.board].c_str(),
                  e.piece.c_str(), e.lamella.c_str(), e.x, e.x + e.length, e.length, waste);
    out += line;
  }
  return out;
}

}  // namespace egg::fabrication
