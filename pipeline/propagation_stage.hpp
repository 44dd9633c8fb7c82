#pragma once
// The propagation stage (Problem 3.3, Section 3.4.4): the members of every chain of patches, C0 at
// their shared sides. A single patch places its own members (2.4.4) and skips it.
#include "pipeline/patching_stage.hpp"
#include "pipeline/scene.hpp"
#include "propagation/chain_tracing.hpp"
#include "propagation/layout_propagation.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace egg::pipeline {

struct RunState;

// Patches of the layout whose design is feasible.
int designedCount(const PatchingRun& run);

// The propagated members; empty for a single patch.
std::optional<propagation::LayoutPropagation> propagateMembers(const PatchingRun& run,
                                                               const Scene& scene);

// report.json propagation{}: c0_max_gap_m, evenness before/after Problem 3.3, per chain and side
// (the grid stage writes it, once the members are traced).
nlohmann::json propagationSection(const propagation::LayoutPropagation& members,
                                  const propagation::LayoutTracing& tracing);

// Stage table row: one patch or no feasible design leaves nothing to propagate.
std::string propagationSkipReason(const RunState& state);
void propagationStage(RunState& state);

}  // namespace egg::pipeline
