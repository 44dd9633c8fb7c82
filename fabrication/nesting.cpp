#include "fabrication/nesting.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <sstream>

namespace egg::fabrication {
namespace {

constexpr double kSlack = 1e-9;

struct Row {
  double heightMm = 0.0;        // the widest part in it
  double usedMm = 0.0;          // parts' lengths plus the gaps between them
  std::vector<size_t> members;  // part indices, in their order along the row
};

struct Packer {
  const std::vector<NestPart>& parts;
  double usableX, usableY, gap;

  double roomAfter(const Row& row, const NestPart& p) const {
    const double x = row.members.empty() ? 0.0 : row.usedMm + gap;
    return usableX - (x + p.lengthMm);
  }
  bool fits(const Row& row, const NestPart& p) const {
    return p.widthMm <= row.heightMm + kSlack && roomAfter(row, p) >= -kSlack;
  }
  void add(Row& row, size_t index) const {
    const NestPart& p = parts[index];
    row.usedMm = (row.members.empty() ? 0.0 : row.usedMm + gap) + p.lengthMm;
    row.heightMm = std::max(row.heightMm, p.widthMm);
    row.members.push_back(index);
  }
  // Best fit: the row this part leaves the least room in (the narrowest tall enough first).
  Row* bestRow(std::vector<Row>& rows, const NestPart& p, const Row* skip = nullptr) const {
    Row* best = nullptr;
    for (auto& row : rows) {
      if (&row == skip || !fits(row, p)) continue;
      if (!best || row.heightMm < best->heightMm - kSlack ||
          (row.heightMm <= best->heightMm + kSlack && roomAfter(row, p) < roomAfter(*best, p)))
        best = &row;
    }
    return best;
  }
};

// Minimum bin slack (Gupta and Ho 1999): row by row, the longest part left and the subset of the
// others that fills the row best (a depth-first search over the parts, longest first, of at most
// kNodeBudget nodes per row; it stops early at a full row).
std::vector<Row> minimumSlackRows(const Packer& packer, const std::vector<size_t>& order) {
  constexpr long kNodeBudget = 20000;
  std::vector<size_t> left = order;  // longest first within each width (the caller's order)
  std::vector<Row> rows;
  const double capacity = packer.usableX + packer.gap;  // every part takes its length + gap
  auto size = [&](size_t index) { return packer.parts[index].lengthMm + packer.gap; };
  while (!left.empty()) {
    const size_t first = left.front();
    const double height = packer.parts[first].widthMm;
    std::vector<size_t> chosen, best;
    double bestFill = -1.0;
    long nodes = 0;
    // Candidates: the other parts no wider than the first (rows hold one width band), longest
    // first, so that the search jumps straight to the first part that still fits (a binary
    // search) and past a run of equal lengths (trying the second of two equal parts after
    // skipping the first repeats): each step of the loop below is then a node of the search, and
    // the budget bounds the work, not only the depth (the Yas: 2,136 rows of up to 1,000 parts).
    std::vector<size_t> candidates;
    for (size_t k = 1; k < left.size(); ++k) {
      if (packer.parts[left[k]].widthMm <= height + kSlack) candidates.push_back(left[k]);
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [&](size_t a, size_t b) { return size(a) > size(b) + kSlack; });
    std::vector<double> sizes(candidates.size());
    for (size_t k = 0; k < candidates.size(); ++k) sizes[k] = size(candidates[k]);
    std::vector<size_t> nextLength(candidates.size());  // first later index of another length
    for (size_t k = candidates.size(); k-- > 0;) {
      nextLength[k] = k + 1 < candidates.size() && std::abs(sizes[k + 1] - sizes[k]) <= kSlack
                          ? nextLength[k + 1]
                          : k + 1;
    }
    const auto search = [&](auto&& self, size_t from, double fill) -> void {
      if (fill > bestFill) bestFill = fill, best = chosen;
      if (capacity - bestFill <= kSlack || ++nodes > kNodeBudget) return;
      const double room = capacity + kSlack - fill;
      size_t k = static_cast<size_t>(
          std::lower_bound(sizes.begin() + static_cast<std::ptrdiff_t>(from), sizes.end(), room,
                           [](double s, double r) { return s > r; }) -
          sizes.begin());
      for (; k < candidates.size(); k = nextLength[k]) {
        chosen.push_back(candidates[k]);
        self(self, k + 1, fill + sizes[k]);
        chosen.pop_back();
        if (capacity - bestFill <= kSlack || nodes > kNodeBudget) return;
      }
    };
    search(search, 0, size(first));
    Row row;
    packer.add(row, first);
    for (size_t index : best) packer.add(row, index);
    std::vector<size_t> remaining;
    for (size_t k = 1; k < left.size(); ++k) {
      if (std::find(best.begin(), best.end(), left[k]) == best.end()) remaining.push_back(left[k]);
    }
    left = std::move(remaining);
    rows.push_back(std::move(row));
  }
  return rows;
}

// Rows best-fit decreasing (or, with `minimumSlack`, by minimum bin slack), then the 16 emptiest
// rows, emptiest first, dissolved where all its parts fit into the other rows (best fit again).
std::vector<Row> packRows(const Packer& packer, const std::vector<size_t>& order,
                          bool minimumSlack) {
  std::vector<Row> rows;
  if (minimumSlack) {
    rows = minimumSlackRows(packer, order);
  } else {
    for (size_t index : order) {
      Row* row = packer.bestRow(rows, packer.parts[index]);
      if (!row) {
        rows.emplace_back();
        row = &rows.back();
      }
      packer.add(*row, index);
    }
  }
  for (bool removed = true; removed;) {
    removed = false;
    std::vector<size_t> byFill(rows.size());
    std::iota(byFill.begin(), byFill.end(), size_t{0});
    std::stable_sort(byFill.begin(), byFill.end(),
                     [&](size_t a, size_t b) { return rows[a].usedMm < rows[b].usedMm; });
    // The emptiest rows only: a full row's parts rarely fit elsewhere, and trying all of a
    // large run's thousands of rows costs seconds (the Yas: 2,136 rows).
    constexpr size_t kTried = 16;
    if (byFill.size() > kTried) byFill.resize(kTried);
    for (size_t candidate : byFill) {
      std::vector<Row> trial = rows;
      const Row leaving = trial[candidate];
      trial.erase(trial.begin() + static_cast<std::ptrdiff_t>(candidate));
      bool all = true;
      for (size_t index : leaving.members) {
        Row* row = packer.bestRow(trial, packer.parts[index]);
        if (!row) {
          all = false;
          break;
        }
        packer.add(*row, index);
      }
      if (all) {
        rows = std::move(trial);
        removed = true;
        break;
      }
    }
  }
  return rows;
}

// Rows onto sheets: tallest first, then fullest first, each onto the first sheet with room.
// Returns the sheet of every row and its y (relative to the margin).
int stackRows(std::vector<Row>& rows, double usableY, double gap, std::vector<int>& sheetOf,
              std::vector<double>& yOf) {
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    if (a.heightMm != b.heightMm) return a.heightMm > b.heightMm;
    return a.usedMm > b.usedMm;
  });
  std::vector<double> top;  // next free y on each sheet
  sheetOf.assign(rows.size(), 0);
  yOf.assign(rows.size(), 0.0);
  for (size_t r = 0; r < rows.size(); ++r) {
    int sheet = -1;
    for (size_t s = 0; s < top.size() && sheet < 0; ++s) {
      const double y = top[s] == 0.0 ? 0.0 : top[s] + gap;
      if (y + rows[r].heightMm <= usableY + kSlack) sheet = static_cast<int>(s);
    }
    if (sheet < 0) {
      sheet = static_cast<int>(top.size());
      top.push_back(0.0);
    }
    yOf[r] = top[sheet] == 0.0 ? 0.0 : top[sheet] + gap;
    top[sheet] = yOf[r] + rows[r].heightMm;
    sheetOf[r] = sheet;
  }
  return static_cast<int>(top.size());
}

// Eggshell's shelves before issue 38: each part, widest then longest first, onto the first shelf
// it fits, a new shelf on the first sheet with room. Only its sheet count is kept, to compare.
int shelfSheetCount(const Packer& packer, const std::vector<size_t>& order) {
  std::vector<Row> shelves;
  std::vector<int> sheetOfShelf;
  std::vector<double> top;
  for (size_t index : order) {
    const NestPart& p = packer.parts[index];
    Row* target = nullptr;
    for (auto& shelf : shelves) {
      if (packer.fits(shelf, p)) {
        target = &shelf;
        break;
      }
    }
    if (!target) {
      int sheet = -1;
      for (size_t s = 0; s < top.size() && sheet < 0; ++s) {
        const double y = top[s] == 0.0 ? 0.0 : top[s] + packer.gap;
        if (y + p.widthMm <= packer.usableY + kSlack) sheet = static_cast<int>(s);
      }
      if (sheet < 0) {
        sheet = static_cast<int>(top.size());
        top.push_back(0.0);
      }
      top[sheet] = (top[sheet] == 0.0 ? 0.0 : top[sheet] + packer.gap) + p.widthMm;
      shelves.push_back({p.widthMm, 0.0, {}});
      target = &shelves.back();
    }
    packer.add(*target, index);
  }
  return static_cast<int>(top.size());
}

}  // namespace

int binPackingLowerBound(std::vector<double> sizes, double capacity) {
  if (sizes.empty()) return 0;
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  const double total = std::accumulate(sizes.begin(), sizes.end(), 0.0);
  int best = static_cast<int>(std::ceil(total / capacity - 1e-9));  // L1
  // prefix[k]: the sum of the k largest sizes.
  std::vector<double> prefix(sizes.size() + 1, 0.0);
  for (size_t k = 0; k < sizes.size(); ++k) prefix[k + 1] = prefix[k] + sizes[k];
  // The first index whose size is at most x (sizes descending).
  const auto firstAtMost = [&](double x) {
    return static_cast<size_t>(
        std::lower_bound(sizes.begin(), sizes.end(), x + kSlack, std::greater<>()) - sizes.begin());
  };
  // L2 (Martello and Toth 1990, Lemma 8.2): for a threshold alpha <= C/2, the parts above C - alpha
  // (J1) and those above C/2 (J2) each need a bin of their own; the parts from alpha to C/2 (J3)
  // fit only into what J2's bins leave free, or need bins of their own beyond that.
  const size_t half = firstAtMost(0.5 * capacity);  // J1 + J2 = [0, half)
  best = std::max(best, static_cast<int>(half));
  for (size_t a = half; a < sizes.size(); ++a) {
    if (a > half && sizes[a] == sizes[a - 1]) continue;  // each distinct alpha once
    const double alpha = sizes[a];
    const size_t j1 = firstAtMost(capacity - alpha);  // J1 = [0, j1), J2 = [j1, half)
    // J3: parts in [alpha, C/2]: indices [half, last index with size >= alpha].
    const size_t j3last = static_cast<size_t>(
        std::upper_bound(sizes.begin(), sizes.end(), alpha - kSlack, std::greater<>()) -
        sizes.begin());
    const double j2Sum = prefix[half] - prefix[std::min(j1, half)];
    const double j2Count = static_cast<double>(half - std::min(j1, half));
    const double j3Sum = prefix[j3last] - prefix[half];
    const double spill = j3Sum - (j2Count * capacity - j2Sum);
    const int bound =
        static_cast<int>(half) + std::max(0, static_cast<int>(std::ceil(spill / capacity - 1e-9)));
    best = std::max(best, bound);
  }
  return best;
}

Nesting nestParts(const std::vector<NestPart>& parts, std::array<double, 2> sheetMm, double gapMm,
                  double marginMm, const std::string& field) {
  const double usableX = sheetMm[0] - 2.0 * marginMm, usableY = sheetMm[1] - 2.0 * marginMm;
  for (const auto& p : parts) {
    if (p.lengthMm > usableX + kSlack || p.widthMm > usableY + kSlack) {
      std::ostringstream msg;
      msg << field << ": part " << p.name << " (" << p.lengthMm << " x " << p.widthMm
          << " mm) does not fit a " << sheetMm[0] << " x " << sheetMm[1] << " mm sheet with a "
          << marginMm << " mm margin";
      if (p.lengthMm > usableX + kSlack && p.lengthMm <= usableY + kSlack)
        msg << " (strips run along the sheet's first side)";
      if (p.lengthMm > usableX + kSlack && field == "fabrication.sheet_mm") {
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
  const Packer packer{parts, usableX, usableY, gapMm};
  Nesting out;
  out.shelfSheets = shelfSheetCount(packer, order);
  // Both packings; the one with fewer sheets, then fewer rows, is kept (ties: best fit).
  std::vector<Row> rows = packRows(packer, order, false);
  std::vector<int> sheetOf;
  std::vector<double> yOf;
  out.sheets = stackRows(rows, usableY, gapMm, sheetOf, yOf);
  {
    std::vector<Row> slackRows = packRows(packer, order, true);
    std::vector<int> slackSheetOf;
    std::vector<double> slackYOf;
    const int slackSheets = stackRows(slackRows, usableY, gapMm, slackSheetOf, slackYOf);
    if (slackSheets < out.sheets || (slackSheets == out.sheets && slackRows.size() < rows.size())) {
      rows = std::move(slackRows);
      sheetOf = std::move(slackSheetOf);
      yOf = std::move(slackYOf);
      out.sheets = slackSheets;
    }
  }
  out.rows = static_cast<int>(rows.size());
  out.placements.resize(parts.size());
  out.sheetUtilisation.assign(out.sheets, 0.0);
  double total = 0.0;
  for (size_t r = 0; r < rows.size(); ++r) {
    double x = 0.0;
    for (size_t index : rows[r].members) {
      out.placements[index] = {sheetOf[r], marginMm + x, marginMm + yOf[r]};
      x += parts[index].lengthMm + gapMm;
      out.sheetUtilisation[sheetOf[r]] += parts[index].lengthMm * parts[index].widthMm;
    }
  }
  for (const auto& p : parts) total += p.lengthMm * p.widthMm;
  std::vector<double> sizes;
  for (const auto& p : parts) sizes.push_back(p.lengthMm + gapMm);
  out.rowsLowerBound = binPackingLowerBound(sizes, usableX + gapMm);
  for (auto& u : out.sheetUtilisation) u /= sheetMm[0] * sheetMm[1];
  out.yield = out.sheets > 0 ? total / (out.sheets * sheetMm[0] * sheetMm[1]) : 0.0;
  return out;
}

double sheetWidthForRows(int rows, double stripWidthMm, double gapMm, double marginMm) {
  return rows * stripWidthMm + (rows - 1) * gapMm + 2.0 * marginMm;
}

SheetWidthSuggestion suggestSheetWidth(const std::vector<NestPart>& parts,
                                       std::array<double, 2> sheetMm, double gapMm,
                                       double marginMm) {
  SheetWidthSuggestion best;
  if (parts.empty()) return best;
  double w = 0.0;
  for (const auto& p : parts) w = std::max(w, p.widthMm);
  const int now = std::max(
      1, static_cast<int>(std::floor((sheetMm[1] - 2.0 * marginMm + gapMm) / (w + gapMm) + 1e-9)));
  for (int rows : {now, now + 1}) {
    // Rounded up to the next tenth of a millimetre, so that the rows still fit.
    const double width =
        std::ceil(sheetWidthForRows(rows, w, gapMm, marginMm) * 10.0 - 1e-6) / 10.0;
    const Nesting n = nestParts(parts, {sheetMm[0], width}, gapMm, marginMm, "suggestion");
    if (best.sheets == 0 || n.yield > best.yield + 1e-12) best = {width, rows, n.sheets, n.yield};
  }
  return best;
}

}  // namespace egg::fabrication
