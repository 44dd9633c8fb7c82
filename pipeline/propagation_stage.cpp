#include "pipeline/propagation_stage.hpp"

#include "pipeline/run_state.hpp"
#include "propagation/patch_sides.hpp"

#include <algorithm>

namespace egg::pipeline {

using nlohmann::json;

int designedCount(const PatchingRun& run) {
  return static_cast<int>(std::count_if(run.layout.patches.begin(), run.layout.patches.end(),
                                        [](const auto& p) { return p.feasible(); }));
}

std::optional<propagation::LayoutPropagation> propagateMembers(const PatchingRun& run,
                                                               const Scene& scene) {
  if (run.layout.patches.size() < 2) return std::nullopt;
  std::vector<propagation::PatchSideData> sides;
  for (const auto& designed : run.layout.patches) {
    if (designed.feasible())
      sides.push_back(propagation::patchSideData(*designed.design, scene.lamella.widthM));
    else
      sides.emplace_back();
  }
  propagation::PropagationOptions options;
  const MemberOptions& members = scene.design().members;
  if (members.count > 0) options.members = members.count;
  options.lamellaWidthM = scene.lamella.widthM;
  options.spacingFactor = members.spacingFactor;
  return propagation::propagateLayout(run.graph, sides, options);
}

json propagationSection(const propagation::LayoutPropagation& members,
                        const propagation::LayoutTracing& tracing) {
  json chains = json::array();
  for (const auto& chain : members.chains) {
    json nodes = json::array();
    for (const auto& n : chain.nodes)
      nodes.push_back({{"patch", n.patch},
                       {"family", n.family == Family::U ? "u" : "v"},
                       {"forward", n.forward}});
    chains.push_back({{"graph_chain", chain.graphChain},
                      {"nodes", nodes},
                      {"ring", chain.ring},
                      {"members", chain.solution.start.size()},
                      {"evenness_before", chain.solution.evennessBefore},
                      {"evenness_after", chain.solution.evennessAfter},
                      {"iterations", chain.solution.iterations},
                      {"status", chain.solution.status}});
  }
  json fallbacks = json::array();
  for (const auto& f : members.fallbacks) {
    json patches = json::array();
    for (const auto& n : f.nodes)
      patches.push_back({{"patch", n.patch}, {"family", n.family == Family::U ? "u" : "v"}});
    fallbacks.push_back({{"graph_chain", f.graphChain}, {"nodes", patches}, {"reason", f.reason}});
  }
  json gaps = json::array();
  for (const auto& g : tracing.gaps)
    gaps.push_back({{"boundary", g.boundary},
                    {"patches", {g.patchA, g.patchB}},
                    {"piece", toString(g.piece)},
                    {"members", {g.membersA, g.membersB}},
                    {"max_gap_m", g.maxGapM},
                    {"kind", toString(g.kind)}});
  return {{"ran", true},
          {"c0_max_gap_m", tracing.c0MaxGapM},
          {"evenness_before", members.evennessBefore},
          {"evenness_after", members.evennessAfter},
          {"iterations", members.iterations},
          {"chains", members.chains.size()},
          {"originals", members.originals},
          {"seconds", members.seconds},
          {"tracing_rounds", tracing.rounds},
          {"matched_runs", tracing.matchedRuns},
          {"held_runs", tracing.heldRuns},
          {"member_traces", tracing.memberTraces},
          {"notes", members.notes},
          {"propagated_chains", chains},
          {"per_patch_chains", fallbacks},
          {"sides", gaps}};
}

std::string propagationSkipReason(const RunState& state) {
  if (state.patching->layout.patches.size() == 1)
    return "one patch: no boundary to continue members across";
  if (designedCount(*state.patching) == 0) return "no feasible patch design";
  return {};
}

void propagationStage(RunState& state) {
  state.members = propagateMembers(*state.patching, state.scene);
  state.report.stageRan("propagation", state.members->seconds);
}

}  // namespace egg::pipeline
