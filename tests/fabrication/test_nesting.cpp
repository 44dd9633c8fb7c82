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

}  // namespace
}  // namespace egg::fabrication
