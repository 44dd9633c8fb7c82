#pragma once
// Designing every patch of a layout, and Workflow 1 (Algorithm 1, Section 3.4.3): split the
// infeasible patches until every patch passes.
//   - eta or the slopes of F (Problem 2.3) fail for one family: a new side through p_max across
//     that family's members (parallel to the other family's): the peak lies on the boundary of
//     both halves, "the most effective way to avoid non-unique shortest geodesics" (3.4.1), and
//     the failing members are halved ("decrease the size of the patch to make the members of the
//     respective family shorter", Algorithm 2). A side along the failing members would not do: a
//     shortest geodesic that long avoids the peak just as the members do;
//   - both families fail: a corner at p_max with four new sides to the nearest points of the four
//     sides (four patches).
// A new side ends on a neighbour's side: the neighbour gets a T-junction there (its own corners
// stay) and is designed again on the new layout mesh. Splitting replaces smoothing, which would
// alter the design (3.1). A patch that cannot be cut (sides crossing, not convex), or that is
// smaller than the minimum size, or is left when the split budget is spent, fails with its reason.
#include "core/egg/patch_design.hpp"
#include "patching/layout.hpp"

#include <optional>
#include <string>
#include <vector>

namespace egg::patching {

struct LayoutDesignOptions {
  EggOptions design;  // per-patch design (eta_max, maps, Problem 2.3); smoothing as set there
  LayoutOptions layout;
  bool split = false;  // Workflow 1: split infeasible patches (else: the layout as given)
  int maxSplits = 64;  // splits before giving up
  double minSideM =
      0.0;  // no split makes a side shorter than this (0 = 2.5 mean edge lengths of the surface)
  void validate() const;
};

struct SplitRecord {
  int parent = -1;  // patch id in the layout (before compaction)
  std::vector<int> children;
  std::string kind;  // "side over p_max (eta, u)", "corner at p_max (slopes, u and v)", ...
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
};

struct DesignedPatch {
  std::optional<LayoutPatch> cut;     // empty if the patch could not be cut
  std::optional<PatchDesign> design;  // empty if not cut or the design threw
  std::string failure;                // why it carries no grid ("" = feasible)
  bool feasible() const { return failure.empty() && design && design->feasible; }
};

struct LayoutDesign {
  PatchLayout layout;                  // final: the split patches removed, ids 0 .. n-1
  std::vector<DesignedPatch> patches;  // per final patch
  std::vector<SplitRecord> splits;     // in the order they were made (ids before compaction)
  int evaluations = 0;                 // patch designs computed (trial and final)
  int rounds = 0;
  double designSeconds = 0.0;  // wall time of the (parallel) patch designs
  double seconds = 0.0;        // all of it
};

// Designs every patch (in parallel; results do not depend on the thread count) and, with
// options.split, runs Workflow 1 on the layout. Input errors propagate (InvalidInput).
LayoutDesign designLayout(PatchLayout layout, const geodesic::DistanceSolver& surfaceSolver,
                          const LayoutDesignOptions& options);

}  // namespace egg::patching
