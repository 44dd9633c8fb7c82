#pragma once
// The FE check's figure for report.html (issue 37): three axonometric views of the ccx model side
// by side: each lamella coloured by its utilisation in the governing case, the deflected shape of
// that case over the undeformed one, and buckling mode 1. Deformations are drawn to a stated
// scale (the largest one a twentieth of the structure's size), as FE post-processors do.
#include "verification/structural_check.hpp"

#include <string>

namespace egg::pipeline {

// An <svg id="verification"> (no XML declaration: inlined in the page, and written as
// fem/verification.svg with its namespace). `result` must be solved, with at least one case.
std::string verificationSvg(const verification::CheckResult& result);

// The case the figure shows: the buckling step's case, else the highest utilisation.
const verification::CaseResult& governingCase(const verification::CheckResult& result);

}  // namespace egg::pipeline
