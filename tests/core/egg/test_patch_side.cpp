// The side table of core/egg/patch_side.hpp against the rules it replaced (Section 2.4.4): u
// members run from side 3 to side 1, v members from side 0 to side 2, sides 2 and 3 against their
// corners; the boundary member along side k is the other family's first or last member.
#include "core/egg/patch_side.hpp"

#include "core/egg/patch_maps.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TEST(PatchSide, MembersStartAndEndOnTheSidesOfSection244) {
  EXPECT_EQ(PatchSide::whereMembersEnd(Family::U, false).index(), 3);
  EXPECT_EQ(PatchSide::whereMembersEnd(Family::U, true).index(), 1);
  EXPECT_EQ(PatchSide::whereMembersEnd(Family::V, false).index(), 0);
  EXPECT_EQ(PatchSide::whereMembersEnd(Family::V, true).index(), 2);
  for (Family f : {Family::U, Family::V})
    for (bool end : {false, true}) {
      const PatchSide side = PatchSide::whereMembersEnd(f, end);
      EXPECT_EQ(side.endingFamily(), f);
      EXPECT_EQ(side.isMembersEnd(), end);
      EXPECT_EQ(familySide(f, end), std::make_pair(side.index(), side.againstCorners()));
    }
}

TEST(PatchSide, TheBoundaryMemberIsTheOtherFamilysFirstOrLast) {
  // Side 0 = u member 0, side 1 = last v member, side 2 = last u member, side 3 = v member 0.
  const Family family[4] = {Family::U, Family::V, Family::U, Family::V};
  const int member[4] = {0, 6, 4, 0};  // of 5 u members and 7 v members
  for (int k = 0; k < 4; ++k) {
    const PatchSide side(k);
    EXPECT_EQ(side.boundaryFamily(), family[k]) << k;
    EXPECT_NE(side.boundaryFamily(), side.endingFamily()) << k;
    EXPECT_EQ(side.boundaryMember(side.boundaryFamily() == Family::U ? 5 : 7), member[k]) << k;
    EXPECT_EQ(side.againstCorners(), k >= 2) << k;
  }
}

TEST(PatchSide, AQuadHasFourSides) {
  EXPECT_THROW(PatchSide(4), std::out_of_range);
  EXPECT_THROW(PatchSide(-1), std::out_of_range);
}

}  // namespace
}  // namespace egg
