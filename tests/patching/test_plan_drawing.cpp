#include "patching/plan_drawing.hpp"

#include <gtest/gtest.h>

namespace egg::patching::plan {
namespace {

TEST(PlanDrawing, PlainNumbersGroupThousandsAndNeverUseAnExponent) {
  const std::string nnbsp = "\u202f";
  EXPECT_EQ(plainNumber(34170.4), "34" + nnbsp + "170");  // was "3.417e+04 m²" on the Yas plan
  EXPECT_EQ(plainNumber(1553.2), "1553");                 // four digits stay together
  EXPECT_EQ(plainNumber(0.004, 2), "0.00");
  EXPECT_EQ(plainNumber(-0.004, 2), "0.00");  // no "-0.00"
  EXPECT_EQ(plainNumber(-1234567.891, 2), "−1" + nnbsp + "234" + nnbsp + "567.89");
  EXPECT_EQ(plainNumber(97.25, 1), "97.2");  // round half to even, as printf
  EXPECT_EQ(plainNumber(1e12), "1" + nnbsp + "000" + nnbsp + "000" + nnbsp + "000" + nnbsp + "000");
}

TEST(PlanDrawing, RoundLengthIsOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(roundLength(19.4), 10.0);
  EXPECT_DOUBLE_EQ(roundLength(20.0), 20.0);
  EXPECT_DOUBLE_EQ(roundLength(0.73), 0.5);
  EXPECT_DOUBLE_EQ(roundLength(4999.0), 2000.0);
}

TEST(PlanDrawing, LabelLayoutTakesTheFirstFreeCandidateInsideThePage) {
  LabelLayout layout(200, 100);
  Eigen::Vector2d at;
  // 4 characters of 10 px: 0.62 * 10 * 4 + 4 = 28.8 px wide, 1.2 * 10 + 2 = 14 px tall.
  ASSERT_TRUE(layout.place({{50, 50}}, 4, 1, 10, at));
  EXPECT_EQ(at, Eigen::Vector2d(50, 50));
  const auto box = layout.taken().back();
  EXPECT_NEAR(box.x1 - box.x0, 28.8, 1e-12);
  EXPECT_NEAR(box.y1 - box.y0, 14.0, 1e-12);
  // The same place is taken; 20 px right still overlaps (28.8 wide); 30 px right is free.
  ASSERT_TRUE(layout.place({{50, 50}, {70, 50}, {80, 50}}, 4, 1, 10, at));
  EXPECT_EQ(at, Eigen::Vector2d(80, 50));
  // Off the page on every candidate: refused, nothing taken.
  EXPECT_FALSE(layout.place({{5, 50}, {195, 50}, {100, 3}}, 4, 1, 10, at));
  EXPECT_EQ(layout.taken().size(), 2u);
  // A reserved box (a marker) keeps labels off it.
  layout.reserve({120, 40, 140, 60});
  EXPECT_FALSE(layout.place({{130, 50}}, 1, 1, 10, at));
}

TEST(PlanDrawing, CandidatesRingTheirCentreAtEachStep) {
  const auto c = candidatesAround(10, 20, 5, 2);
  ASSERT_EQ(c.size(), 17u);
  EXPECT_EQ(c[0], Eigen::Vector2d(10, 20));
  for (size_t k = 1; k < c.size(); ++k)
    EXPECT_NEAR((c[k] - c[0]).norm(), k <= 8 ? 5.0 : 10.0, 1e-12) << k;
}

TEST(PlanDrawing, PathChunksKeepEveryDAttributeUnderTheLimitAndLoseNothing) {
  PathChunks chunks("fill=\"#000\"", 100);
  std::string all;
  for (int k = 0; k < 50; ++k) {
    const std::string sub = "M" + std::to_string(k) + ",0L1,1Z";
    chunks.add(sub);
    all += sub;
  }
  const std::string out = chunks.finish();
  std::string joined;
  int elements = 0;
  for (size_t at = out.find(" d=\""); at != std::string::npos; at = out.find(" d=\"", at + 1)) {
    const size_t end = out.find('"', at + 4);
    EXPECT_LE(end - (at + 4), 100u);
    joined += out.substr(at + 4, end - (at + 4));
    ++elements;
  }
  EXPECT_EQ(joined, all);
  EXPECT_GE(elements, 5);  // 50 subpaths of 9-10 bytes in 100-byte pieces
  EXPECT_EQ(out.rfind("<path fill=\"#000\" d=\"M0,0L1,1Z", 0), 0u);
  EXPECT_TRUE(PathChunks("x").finish().empty());
}

}  // namespace
}  // namespace egg::patching::plan
