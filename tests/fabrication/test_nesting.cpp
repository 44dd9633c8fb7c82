#include "fabrication/nesting.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg::fabrication {
namespace {

TEST(Nesting, ShelvesOfStripsAtKnownPositions) {
  // Six 210 x 10 mm strips on a 500 x 300 mm sheet, 5 mm margin, 0.5 mm kerf: two per row
  // (210 + 0.5 + 210 = 420.5 <= 490), rows 10.5 mm apart.
  std::vector<NestPart> parts(6, NestPart{"", 210.0, 10.0});
  for (int k = 0; k < 6; ++k) parts[k].name = "strip " + std::to_string(k);
  const Nesting n = nestParts(parts, {500.0, 300.0}, 0.5, 5.0, "fabrication.sheet_mm");
  EXPECT_EQ(n.sheets, 1);
  const double expected[6][2] = {{5, 5},        {215.5, 5}, {5, 15.5},
                                 {215.5, 15.5}, {5, 26},    {215.5, 26}};
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(n.placements[k].sheet, 0);
    EXPECT_DOUBLE_EQ(n.placements[k].xMm, expected[k][0]) << k;
    EXPECT_DOUBLE_EQ(n.placements[k].yMm, expected[k][1]) << k;
  }
  EXPECT_NEAR(n.yield, 6 * 210.0 * 10.0 / (500.0 * 300.0), 1e-12);
}

TEST(Nesting, FullSheetsOpenNewOnes) {
  // 100 x 40 parts on a 210 x 100 sheet with no margin or kerf: 2 per row, 2 rows per sheet.
  std::vector<NestPart> parts(9, NestPart{"p", 100.0, 40.0});
  const Nesting n = nestParts(parts, {210.0, 100.0}, 0.0, 0.0, "f");
  EXPECT_EQ(n.sheets, 3);
  EXPECT_EQ(n.placements[8].sheet, 2);
  // No two parts on one sheet overlap.
  for (size_t a = 0; a < parts.size(); ++a) {
    for (size_t b = a + 1; b < parts.size(); ++b) {
      if (n.placements[a].sheet != n.placements[b].sheet) continue;
      const bool apart = n.placements[a].xMm + 100.0 <= n.placements[b].xMm ||
                         n.placements[b].xMm + 100.0 <= n.placements[a].xMm ||
                         n.placements[a].yMm + 40.0 <= n.placements[b].yMm ||
                         n.placements[b].yMm + 40.0 <= n.placements[a].yMm;
      EXPECT_TRUE(apart) << a << " " << b;
    }
  }
}

TEST(Nesting, PartLargerThanTheSheetIsAClearErrorNamingIt) {
  std::vector<NestPart> parts{{"P0-U1", 210.0, 10.0}, {"P2-V5", 600.0, 10.0}};
  try {
    nestParts(parts, {500.0, 300.0}, 0.5, 5.0, "fabrication.sheet_mm");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("fabrication.sheet_mm:", 0), 0u) << what;
    EXPECT_NE(what.find("P2-V5"), std::string::npos) << what;
    EXPECT_NE(what.find("600"), std::string::npos) << what;
  }
  // Too wide as well.
  EXPECT_THROW(
      nestParts({{"wide", 100.0, 295.0}}, {500.0, 300.0}, 0.5, 5.0, "fabrication.sheet_mm"),
      InvalidInput);
}

TEST(Nesting, TheRowBoundCountsPartsAboveHalfARowOneRowEach) {
  // Four parts of 51 in rows of 100: the lengths sum to 2.04 rows, but no two share a row.
  EXPECT_EQ(binPackingLowerBound({51, 51, 51, 51}, 100.0), 4);
  // 70, 70 alone (nothing of 40 fits beside them); 3 x 40 need 2 more rows: 4, where the sum
  // gives 3 (Martello and Toth's L2 with alpha = 40). Four rows are also what a packing takes.
  EXPECT_EQ(binPackingLowerBound({40, 70, 40, 70, 40}, 100.0), 4);
  // Small parts: the sum decides.
  EXPECT_EQ(binPackingLowerBound({30, 30, 30, 30, 30}, 100.0), 2);
  EXPECT_EQ(binPackingLowerBound({}, 100.0), 0);
  // Parts of exactly half a row pair up: 2 rows.
  EXPECT_EQ(binPackingLowerBound({50, 50, 50, 50}, 100.0), 2);
}

TEST(Nesting, MinimumSlackRowsBeatFirstFitShelves) {
  // Rows of 100 mm (no margin, kerf or gap), one row per sheet: parts 50, 40, 30, 30, 25, 25.
  // First fit decreasing: {50, 40}, {30, 30, 25}, {25} = 3 rows; best fit the same. The total is
  // 200 = 2 full rows, which minimum bin slack finds: {50, 25, 25}, {40, 30, 30}.
  std::vector<NestPart> parts;
  for (double length : {30.0, 50.0, 25.0, 40.0, 25.0, 30.0}) parts.push_back({"p", length, 10.0});
  const Nesting n = nestParts(parts, {100.0, 10.0}, 0.0, 0.0, "f");
  EXPECT_EQ(n.shelfSheets, 3);
  EXPECT_EQ(n.sheets, 2);
  EXPECT_EQ(n.rows, 2);
  EXPECT_EQ(n.rowsLowerBound, 2);
  ASSERT_EQ(n.sheetUtilisation.size(), 2u);
  EXPECT_DOUBLE_EQ(n.sheetUtilisation[0], 1.0);
  EXPECT_DOUBLE_EQ(n.sheetUtilisation[1], 1.0);
  EXPECT_DOUBLE_EQ(n.yield, 1.0);
  // Each sheet's parts end to end: lengths on one sheet sum to 100, none overlaps.
  double onFirst = 0.0;
  for (size_t k = 0; k < parts.size(); ++k) {
    if (n.placements[k].sheet == 0) onFirst += parts[k].lengthMm;
  }
  EXPECT_DOUBLE_EQ(onFirst, 100.0);
}

TEST(Nesting, UtilisationPerSheetAddsUpToTheYield) {
  // Five 90 x 40 parts on 200 x 100 sheets: 2 rows of 2 on the first, one part on the second.
  std::vector<NestPart> parts(5, NestPart{"p", 90.0, 40.0});
  const Nesting n = nestParts(parts, {200.0, 100.0}, 1.0, 5.0, "f");
  ASSERT_EQ(n.sheets, 2);
  EXPECT_DOUBLE_EQ(n.sheetUtilisation[0], 4 * 3600.0 / 20000.0);
  EXPECT_DOUBLE_EQ(n.sheetUtilisation[1], 3600.0 / 20000.0);
  EXPECT_NEAR(n.yield, (n.sheetUtilisation[0] + n.sheetUtilisation[1]) / 2.0, 1e-12);
}

TEST(Nesting, SuggestsTheSheetWidthThatHoldsAnotherRow) {
  // Strips 500 mm wide, 0.2 mm kerf, 10 mm margin: a 2500 mm sheet holds 4 rows (5 would need
  // 5 x 500 + 4 x 0.2 + 20 = 2520.8 mm). 20 strips of 13000 mm on 13500-long sheets: 5 sheets of
  // 4 rows; at 2520.8 mm, 4 sheets of 5.
  EXPECT_DOUBLE_EQ(sheetWidthForRows(5, 500.0, 0.2, 10.0), 2520.8);
  std::vector<NestPart> parts(20, NestPart{"s", 13000.0, 500.0});
  const Nesting now = nestParts(parts, {13500.0, 2500.0}, 0.2, 10.0, "f");
  EXPECT_EQ(now.sheets, 5);
  const SheetWidthSuggestion s = suggestSheetWidth(parts, {13500.0, 2500.0}, 0.2, 10.0);
  EXPECT_DOUBLE_EQ(s.widthMm, 2520.8);
  EXPECT_EQ(s.rowsPerSheet, 5);
  EXPECT_EQ(s.sheets, 4);
  EXPECT_NEAR(s.yield, 20 * 13000.0 * 500.0 / (4 * 13500.0 * 2520.8), 1e-12);
}

}  // namespace
}  // namespace egg::fabrication
