#pragma once
// Lamella plans (Section 3.5, 3.6.1): every member becomes a straight strip of its planar length
// (plus an overhang beyond the end connections) and the lamella width, with a bolt hole at every
// fixed connection and a stadium slot at every notched one. Coordinates along a strip are
// millimetres from its start (the member's planarStart side, minus the overhang).
#include "fabrication/options.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

enum class FeatureKind { Hole, Slot };

// One bolt position on a lamella. A lamella collects features from every patch whose members
// it carries (a boundary lamella shared by two patches holds the holes of both).
struct LamellaFeature {
  FeatureKind kind = FeatureKind::Hole;
  double xMm = 0.0;  // bolt centre in the cut (planar) state, from the strip's start
  double slideMm =
      0.0;  // slots: the bolt moves from xMm to xMm + slideMm while deploying (l = s - s_bar)
  int patchId = 0;
  int connection = 0;                 // index into that patch's EggGrid::connections
  std::string connectionId;           // engraved next to the hole: "P<patch>-C<i>-<j>"
  bool demotedNotch = false;          // a notch shorter than min_notch_mm, cut as a plain hole
  bool droppedBoundaryNotch = false;  // a boundary member's notch (no notches there, 3.5.3)
  // Further connections this one bolt holds: a shared boundary lamella's hole where the members
  // of both patches meet it (mergeSharedBoundaries). (patch, connection) pairs.
  std::vector<std::pair<int, int>> alsoConnections;
  std::vector<std::string> alsoConnectionIds;  // their ids, "P<patch>-C<i>-<j>", in that order
  // connectionId, plus "=" and the other patch's connection id for every merged connection
  // ("P0-C8-0=P1-C0-3"): the crew finds the hole from either patch's drawing.
  std::string label() const;
  bool holds(int patch, int connection) const;
  // Extent along the strip of what is cut (the hole, or the slot including its round ends).
  double minXMm(double boltDiameterMm) const;
  double maxXMm(double boltDiameterMm) const;
};

// One piece cut from stock: a lamella shorter than the stock is one segment; a longer one is cut
// at its splices into several.
struct LamellaSegment {
  double startMm = 0.0, endMm = 0.0;  // along the lamella
  double lengthMm() const { return endMm - startMm; }
};

struct LamellaPlan {
  std::string id;  // "P<patch>-U<index>" or "P<patch>-V<index>"
  int patchId = 0;
  Family family = Family::U;
  int index = 0;
  bool boundary = false;
  double lengthMm = 0.0;  // whole strip, overhangs included
  double widthMm = 0.0;
  double overhangMm = 0.0;
  // Cut short at a bracket end (FabricationPatch::endTrims): strip coordinate x lies at arc length
  // (x + trimStartMm - overhangMm) / 1000 along the member.
  double trimStartMm = 0.0, trimEndMm = 0.0;
  std::vector<LamellaFeature> features;    // sorted along the strip
  std::vector<double> splicesMm;           // cut positions of the splices, ascending
  std::vector<double> spliceClearancesMm;  // per splice: the free length from the cut (a scarf: its
                                           // nearer feather end) to the nearest hole or slot
  // Per splice: a glued scarf (true) or a butt joint with bolted plates. At scarf k the pieces
  // overlap on the slope: from segments[k + 1].startMm to segments[k].endMm; splicesMm is its
  // middle.
  std::vector<bool> spliceIsScarf;
  std::vector<LamellaSegment>
      segments;  // pieces between splices (at least one; none when unspliceable)
  // Why no splice positions exist (placeSplices' message): the lamella is planned but not cut.
  std::string unspliceable;
};

// A patch side shared by two patches (Section 3.5.3: adjacent grids are joined along their common
// lamellas): boundary member `indexA` of family `familyA` in patch `patchA` and member B of patch B
// are one lamella. `reversed`: B runs from A's planarEnd towards its planarStart.
struct SharedBoundary {
  int patchA = 0;
  Family familyA = Family::U;
  int indexA = 0;
  int patchB = 0;
  Family familyB = Family::U;
  int indexB = 0;
  bool reversed = false;
};

// Strips of every member of every patch (u members first, then v, patch by patch) with holes and
// slots, shared boundaries merged (mergeSharedBoundaries, 0.5 mm), spliced into pieces of at most
// longestPieceMm(options); a lamella that cannot be spliced keeps no segments and the reason in
// `unspliceable` (the others can still be cut). Throws InvalidInput naming the patch when a grid is
// missing or inconsistent.
std::vector<LamellaPlan> planLamellae(const std::vector<FabricationPatch>& patches,
                                      const FabricationOptions& options,
                                      const std::vector<SharedBoundary>& shared = {});

// Moves the holes of every shared side's lamella B onto lamella A (x mirrored when reversed), one
// hole where a hole of A lies within `toleranceMm` (one bolt through the members of both patches),
// and removes B. Returns how many holes were merged into existing ones. Throws InvalidInput naming
// the side when a lamella is missing, not a boundary member, or the two lengths differ by more than
// `toleranceMm`. Call before placeSplices.
int mergeSharedBoundaries(std::vector<LamellaPlan>& plans,
                          const std::vector<SharedBoundary>& shared, double toleranceMm);

// Cut positions so that no segment exceeds `stockLengthMm` and every cut lies at least
// `clearanceMm` from every hole and slot (Section 3.5: architectural lamellas of 20-40 m never come
// in one piece): the furthest such position within each stock length. Where a stock length holds
// none (slots as long as their spacing leave shorter gaps, as on the Yas canopy), the cut goes to
// the middle of the widest gap there, provided that keeps `minClearanceMm` each side (a shorter
// splice plate or a glued joint; fabricate() warns). Fills plan.splicesMm, spliceClearancesMm and
// segments. Throws InvalidInput naming the lamella, the stretch, its widest gap and `field` when no
// position keeps minClearanceMm. minClearanceMm < 0 (the default) means clearanceMm: no fallback.
// joint (fabrication.splice_joint): "plate" as above; "scarf": every splice a glued scarf of
// scarfLengthMm to twice that, whose two feather ends lie between cut-outs (half a bolt diameter
// clear), the furthest such within each stock length if it ends at least 0.4 stock lengths on, else
// (slots merged into a slit) one scarf
// length ending at the stock length, through the slit; "plate_or_scarf": plates, and a scarf where
// a stretch has no position for a plate. With scarfs allowed it does not throw for want of room.
void placeSplices(LamellaPlan& plan, double stockLengthMm, double clearanceMm,
                  double boltDiameterMm, const std::string& field = "fabrication.stock_length_mm",
                  double minClearanceMm = -1.0, SpliceJoint joint = SpliceJoint::Plate,
                  double scarfLengthMm = 0.0);

// The longest piece a lamella is cut in: the stock length, or the sheet's usable first side when
// that is shorter (a strip cut from a sheet is no longer than the sheet).
double longestPieceMm(const FabricationOptions& options);

// Counts over plans, for the BOM and the report.
struct FeatureCounts {
  int holes = 0;            // round holes (fixed connections and demoted notches)
  int slots = 0;            // notches cut as slots
  int demoted = 0;          // notches shorter than min_notch_mm (cut as plain holes)
  int droppedBoundary = 0;  // notches on boundary members (cut as plain holes)
};
FeatureCounts countFeatures(const std::vector<LamellaPlan>& plans);

}  // namespace egg::fabrication
