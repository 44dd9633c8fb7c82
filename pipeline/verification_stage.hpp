#pragma once
// The verification stage (issue 37, docs/verification.md): the deployed structure (the joined one
// when it ran, else the one simulated patch) as a CalculiX beam model, its load cases solved by
// ccx, report.json verification{} and the model files under fem/. Skipped, with the reason, when
// ccx is not installed or nothing was deployed; never faked.
#include "pipeline/run_state.hpp"

#include <string>

namespace egg::pipeline {

std::string verificationSkipReason(const RunState& state);
void verificationStage(RunState& state);

}  // namespace egg::pipeline
