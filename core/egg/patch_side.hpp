#pragma once
// The four sides of a quad patch c0 c1 c2 c3, and the members that run along them and end on them
// (Sections 2.4.1, 2.4.4: the sides of a patch are members). Side k runs from corner k to corner
// k + 1. This is the one place that maps a side to its members; docs/architecture.md "Patch sides"
// draws the table:
//
//   side | its boundary member (runs along it)    | members that end on it
//   0    | u member 0, c0 -> c1, with the side    | v members start
//   1    | last v member, c1 -> c2, with the side | u members end
//   2    | last u member, c3 -> c2, against it    | v members end
//   3    | v member 0, c0 -> c3, against it       | u members start
//
// A family's distance-map parameter x runs along its start and end sides in the member's own
// direction, so it runs against the side's corner order on sides 2 and 3 (`againstCorners`).
#include "core/egg/planar_quad.hpp"

#include <stdexcept>

namespace egg {

class PatchSide {
 public:
  // Throws std::out_of_range for an index outside 0..3 (a programming error, not bad input).
  explicit constexpr PatchSide(int index) : index_(index) {
    if (index < 0 || index > 3) throw std::out_of_range("PatchSide: a quad patch has sides 0..3");
  }
  // The side on which members of `family` start (end = false) or end (end = true).
  static constexpr PatchSide whereMembersEnd(Family family, bool end) {
    if (family == Family::U) return PatchSide(end ? 1 : 3);
    return PatchSide(end ? 2 : 0);
  }

  constexpr int index() const { return index_; }
  // The side's direction is c_{k+1} -> c_k for the members along it and ending on it.
  constexpr bool againstCorners() const { return index_ >= 2; }

  // The boundary member: the first or last member of one family runs along the side.
  constexpr Family boundaryFamily() const { return index_ % 2 == 0 ? Family::U : Family::V; }
  constexpr bool boundaryIsLastMember() const { return index_ == 1 || index_ == 2; }
  // Index of the boundary member among `membersOfBoundaryFamily` members of its family.
  constexpr int boundaryMember(int membersOfBoundaryFamily) const {
    return boundaryIsLastMember() ? membersOfBoundaryFamily - 1 : 0;
  }

  // The other family's members end on the side: at their start (sides 0, 3) or end (sides 1, 2).
  constexpr Family endingFamily() const { return index_ % 2 == 1 ? Family::U : Family::V; }
  constexpr bool isMembersEnd() const { return index_ == 1 || index_ == 2; }

  friend constexpr bool operator==(PatchSide a, PatchSide b) { return a.index_ == b.index_; }

 private:
  int index_;
};

}  // namespace egg
