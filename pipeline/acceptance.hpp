#pragma once
// The verdict of a run (issue 36): the deployed structure held against stated acceptance limits,
// each a criterion with its value, its limit and whether it passed. A run that misses one fails
// (exit 1) with the criterion named in report.json's `failures`. The limits and why they are
// what they are: docs/acceptance.md.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace egg::pipeline {

// Scene section "acceptance". Lengths as fractions of the span: the longer side of the design
// surface's plan bounding box.
struct AcceptanceLimits {
  // Largest distance of the deployed grid's contact points from the design surface.
  double maxErrorOverSpan = 1.0 / 50.0;
  // Their root mean square.
  double rmseOverSpan = 1.0 / 200.0;
  // Largest vertex displacement under self-weight from the weightless equilibrium (patch by
  // patch, where the simulation measures it).
  double maxSagOverSpan = 1.0 / 250.0;
  // Largest bending + torsion stress of a deployed lamella over the material's strength
  // (fabrication's stress check).
  double maxStressRatio = 1.0;
};

struct Criterion {
  std::string name;  // e.g. "joined_max_error"
  std::string what;  // in words, for the terminal and report.html
  bool evaluated = false;
  std::string notEvaluatedReason;  // when !evaluated
  double value = 0.0;              // in `unit`
  double limit = 0.0;              // in `unit`
  std::string unit;                // "m" or "" (a ratio)
  std::string limitRule;           // how the limit follows from the scene, e.g. "span / 50"
  bool passed = true;              // not evaluated counts as passed
};

struct Verdict {
  double spanM = 0.0;
  std::vector<Criterion> criteria;
  bool passed() const;
  // One line per criterion missed, naming the criterion, the value and the limit.
  std::vector<std::string> failures() const;
};

// Reads the finished report's sections (surface, simulation, fabrication). A criterion whose
// figure the run did not compute (no simulation, no gravity, no fabrication) is listed as not
// evaluated, with the reason.
Verdict judgeRun(const nlohmann::json& report, const AcceptanceLimits& limits);

nlohmann::json verdictJson(const Verdict& verdict);

// What `egg run` prints at its end: patches, coverage, each criterion against its limit, the
// warnings (their count and the first few), the failures, where the files are; the last line says
// "passed" only for a run without failures.
std::string runSummary(const nlohmann::json& report, const std::filesystem::path& outDir,
                       double seconds);

}  // namespace egg::pipeline
