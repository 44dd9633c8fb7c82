#pragma once
// PTFE stickers (Section 3.5.1, Table 3.1: PTFE on PTFE slides at mu = 0.091 against 0.273 for
// plywood on plywood). Every notched connection gets two stickers, one per lamella, covering the
// lamella-to-lamella contact over the whole slide range and over every crossing angle between the
// planar and the deployed state, plus a margin, with the slot (or hole) cut out.
#include "fabrication/lamella_plan.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

struct Sticker {
  std::string id;  // "<connection id>/<lamella id>"
  std::string connectionId;
  std::string lamellaId;
  double lengthMm = 0.0;  // along the lamella
  double widthMm = 0.0;   // across: the lamella width
  double boltXMm = 0.0;   // bolt centre in the planar state, from the sticker's start
  double slideMm = 0.0;   // slot: the bolt moves to boltXMm + slideMm (0: a plain hole)
  double planarAngleRad = 0.0, deployedAngleRad = 0.0;  // crossing angles of the two lamellas
  bool clipped =
      false;  // shortened to half the way to the neighbouring connections (or the strip end)
  double areaM2() const { return lengthMm * widthMm * 1e-6; }
};

// Half the length along lamella A that lamella B (same width w) covers when they cross at
// `angleRad`: w (1 + |cos a|) / (2 sin a), the half-diagonal of the rhombus projected on A.
double contactHalfLengthMm(double widthMm, double angleRad);

// The crossing angle (0..pi) of two lines with directions a and b.
double crossingAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Stickers of all notched connections of the grid of `patch` (both lamellas of a connection
// where at least one of them has a slot), read from the lamella plans of that patch. A sticker
// reaches at most halfway to the neighbouring connections on its lamella and not beyond the strip
// (at the small crossing angles of a compact planar grid the swept footprint would otherwise run
// over the next connections), and always covers the slot plus a bolt radius.
std::vector<Sticker> planStickers(const FabricationPatch& patch,
                                  const std::vector<LamellaPlan>& plans,
                                  const FabricationOptions& options);

}  // namespace egg::fabrication
