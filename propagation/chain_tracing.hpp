#pragma once
// The grid step of a multi-patch layout with C0 member ends (Sections 2.4.4-2.4.6, 3.4.4).
// Tracing keeps a member's start x1 and refines its end x2 until the geodesic and the planar
// segment have the same length (criterion i), which moves x2 off the propagated value (today by
// up to ~0.3 mm). So the patches are traced in the order the members run: a patch whose members
// enter over a side where the neighbour's members END (their moving end) takes its x1 from the
// neighbour's traced x2, and the two patches' member ends coincide on that side to rounding.
// Where both patches' members START on a shared side, both use the propagated value exactly.
// Where both END on it (members running head-on, which a consistently oriented layout avoids) the
// gap is what tracing leaves, reported per side; so is the cut of a ring (need not close, 3.7.1).
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

// The traced member ends of the two patches on one shared side of a propagated chain.
struct SideGap {
  int boundary = -1;       // PatchGraph boundary id
  int chain = -1;          // index into LayoutPropagation::chains
  int patchA = -1, patchB = -1;
  double maxGapM = 0.0;    // largest distance between corresponding inner member ends
  std::string kind;        // "closed" (in tracing order), "both start" (exact), "head-on", "ring cut", "not traced"
};

struct LayoutTracing {
  std::vector<TracedPatch> patches;
  std::vector<SideGap> gaps;
  double c0MaxGapM = 0.0;  // over the sides of the chains, ring cuts not included
  int rounds = 0;          // tracing rounds (patches of one round run in parallel)
  double seconds = 0.0;
};

// `designs[p]` null or infeasible: patch p gets no grid. A family propagation did not cover
// (fallback, or a lone patch) is placed by placeDesignMembers with the design's member options.
// Each patch is traced with its design's grid options.
LayoutTracing traceLayout(const std::vector<const PatchDesign*>& designs, const LayoutPropagation& propagation);

// Largest distance between corresponding inner member ends of two traced patches of a chain on
// the boundary between chain node `node` - 1 and `node` (1 <= node < nodes; node 0 of a ring: the cut).
double traceGap(const PropagatedChain& chain, int node, const EggGrid& before, const EggGrid& after);

}  // namespace egg::propagation
