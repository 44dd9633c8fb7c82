// Extreme cases of issue 5: converge or report why, never NaN, never hang.
#include "core/rods/stress_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace egg::rods {
namespace {

TEST(StressCases, CoverTheRangesOfTheIssue) {
  double minScale = 1e9, maxScale = 0, minRatio = 1e9, maxRatio = 0, minE = 1e99, maxE = 0,
         minRho = 1e9, maxRho = 0;
  for (const StressCase& c : stressCases()) {
    minScale = std::min(minScale, 3.0 * c.scale);
    maxScale = std::max(maxScale, 3.0 * c.scale);
    minRatio = std::min(minRatio, c.widthToThickness);
    maxRatio = std::max(maxRatio, c.widthToThickness);
    minE = std::min(minE, c.youngsModulusPa);
    maxE = std::max(maxE, c.youngsModulusPa);
    minRho = std::min(minRho, c.densityKgM3);
    maxRho = std::max(maxRho, c.densityKgM3);
  }
  EXPECT_NEAR(minScale, 0.1, 1e-12);
  EXPECT_NEAR(maxScale, 220.0, 1e-9);
  EXPECT_EQ(minRatio, 5.0);
  EXPECT_EQ(maxRatio, 100.0);
  EXPECT_EQ(minE, 0.5e9);
  EXPECT_EQ(maxE, 210.0e9);
  EXPECT_EQ(minRho, 400.0);
  EXPECT_EQ(maxRho, 7850.0);
}

TEST(StressCases, ExtremeCornersConvergeOrSayWhyAndStayFinite) {
  for (const StressCase& c : stressCases()) {
    if (c.name.find(',') == std::string::npos && c.name != "base")
      continue;  // base and the two corners
    const StressOutcome o = runStressCase(c, /*timeLimit_s=*/8.0, /*maxIterations=*/300);
    EXPECT_TRUE(o.finite) << c.name;
    EXPECT_TRUE(o.converged || !o.reason.empty()) << c.name;
    EXPECT_LT(o.seconds, 30.0) << c.name;  // limits hold: no hang
    EXPECT_TRUE(std::isfinite(o.rmseM)) << c.name;
    if (c.name == "base") {
      EXPECT_TRUE(o.converged) << o.reason;
      EXPECT_LT(o.nrmse, 0.02);  // a 3 m vault of 50 x 5 mm plywood stays within 2 % of its size
      EXPECT_LT(o.sagM, 0.01 * o.extentM);
    }
    if (c.name.rfind("soft heavy", 0) == 0) {
      // A 220 m vault of 0.5 GPa strips 11 cm x 1.1 cm at steel density: its weight per length
      // is ~10^4 times what a lone strip arch of that size can carry (~14 EI/R^3), and sliding
      // lets it fall through; after 300 iterations (the weightless deployment alone takes over 150)
      // it is ~46 m down, moving.
      EXPECT_EQ(o.status, SolverStatus::Collapsed) << o.reason;
      EXPECT_GT(o.sagM, 0.05 * o.extentM);
    }
  }
}

}  // namespace
}  // namespace egg::rods
