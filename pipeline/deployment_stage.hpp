#pragma once
// The deployment stage (issue 42, docs/deployment.md): every simulated patch driven from its
// bolted flat grid to its deployed supports in synchronised steps (core/rods/deployment.hpp),
// with report.json deployment{}, deployment.csv (what the crew does and meets at each step),
// deployment.svg (stress ratio and support force against the path) and deployment.glb (the
// animation). Requested by the output "deployment".
#include "pipeline/run_state.hpp"

#include <string>

namespace egg::pipeline {

std::string deploymentSkipReason(const RunState& state);
void deploymentStage(RunState& state);

}  // namespace egg::pipeline
