#pragma once
// The grid step of a multi-patch layout with C0 member ends (Sections 2.4.4-2.4.6, 3.4.4).
// Tracing keeps a member's start x1 and refines its end x2 until the geodesic and the planar
// segment have the same length (criterion i), which moves x2 off the propagated value (today by
// up to ~0.3 mm). So members are traced along their tracks, the sequences of member pieces that
// the propagation's joints (LayoutPropagation::joints) link across shared sides:
//   - a member whose start lies where its neighbour's member ends takes the neighbour's traced x2
//     as its x1 ("closed": the ends coincide to rounding);
//   - where both start on a side, both use the propagated value exactly ("both start");
//   - where a run of members must END on a fixed point (the corner of a smaller patch at a
//     T-junction of boundary members, or another run's traced end when members run head-on) and
//     its first start lies on a free side, that start is iterated (secant on the single member's
//     trace) until the traced end meets the point. A run whose start is held as well cannot move:
//     its gap is what tracing leaves, reported per side.
// Once every start is known each patch's grid is traced whole (the member traces are repeated
// bit for bit, so the grid's ends are the matched ones). The cut of a ring is reported, not
// closed (need not close, 3.7.1).
#include "core/egg/patch_design.hpp"
#include "propagation/layout_propagation.hpp"

#include <optional>
#include <string>
#include <vector>

namespace egg::propagation {

struct TracedPatch {
  std::optional<FamilyMembers> u, v;  // the members traced (x2 as propagated, before refinement)
  std::optional<EggGrid> grid;        // empty when not designed or the trace failed
  std::string failure;                // InfeasiblePatch / SolverFailure message
  double membersSeconds = 0.0, tracingSeconds = 0.0;
};

// How the member ends of two patches meet on a shared piece: one's ends start the other's
// members (closed), both start there, they met by iterating a start (head-on); or not at all: the
// cut of a ring, a different member count on each side, a patch not traced.
enum class GapKind { Closed, BothStart, HeadOn, RingCut, CountMismatch, NotTraced };
// "closed", "both start", "head-on", "ring cut", "count mismatch", "not traced".
const char* toString(GapKind kind);

// The traced member ends of the two patches on one shared boundary piece.
struct SideGap {
  int boundary = -1;  // PatchGraph boundary id
  int patchA = -1, patchB = -1;
  PieceKind piece = PieceKind::WholeSide;
  int membersA = 0, membersB = 0;  // members each side puts on the piece
  double maxGapM = 0.0;            // largest distance between corresponding member ends
  GapKind kind = GapKind::Closed;
};

struct LayoutTracing {
  std::vector<TracedPatch> patches;
  std::vector<SideGap> gaps;
  double c0MaxGapM = 0.0;  // over the pieces, ring cuts not included
  int matchedRuns = 0;     // runs whose start was iterated to meet a fixed end
  int heldRuns = 0;        // runs with a fixed end but no free start (their gap is reported)
  int memberTraces = 0;    // single-member traces spent on the tracks (matching included)
  int rounds = 0;          // rounds of runs (a run matching another's end waits for it)
  double seconds = 0.0;
};

// `designs[p]` null or infeasible: patch p gets no grid. A family propagation did not cover
// (fallback, or a lone patch) is placed by placeDesignMembers with the design's member options.
// Each patch is traced with its design's grid options.
LayoutTracing traceLayout(const std::vector<const PatchDesign*>& designs,
                          const LayoutPropagation& propagation);

}  // namespace egg::propagation
