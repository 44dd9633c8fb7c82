#include "pipeline/acceptance.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// The value at `key` when it is a number.
bool number(const json& j, const char* key, double& out) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return false;
  out = j[key].get<double>();
  return true;
}

bool ran(const json& section) {
  return section.is_object() && section.value("ran", true) && !section.contains("skipped_reason");
}

std::string notRunReason(const json& section, const std::string& stage) {
  if (section.is_object() && section.contains("skipped_reason"))
    return stage + " did not run: " + section["skipped_reason"].get<std::string>();
  return stage + " did not run";
}

Criterion lengthCriterion(std::string name, std::string what, double spanM, double fraction) {
  Criterion c;
  c.name = std::move(name);
  c.what = std::move(what);
  c.unit = "m";
  c.limit = fraction * spanM;
  c.limitRule = fmt::format("span {:.4g} m x {:.4g}", spanM, fraction);
  return c;
}

void evaluate(Criterion& c, bool evaluated, double value, const std::string& reason) {
  c.evaluated = evaluated;
  if (!evaluated) {
    c.notEvaluatedReason = reason;
    return;
  }
  c.value = value;
  c.passed = std::isfinite(value) && value <= c.limit;
}

}  // namespace

bool Verdict::passed() const {
  return std::all_of(criteria.begin(), criteria.end(), [](const Criterion& c) { return c.passed; });
}

std::vector<std::string> Verdict::failures() const {
  std::vector<std::string> out;
  for (const Criterion& c : criteria) {
    if (c.passed) continue;
    out.push_back(fmt::format("acceptance: {} ({}) is {:.4g}{} above its limit {:.4g}{} ({})",
                              c.what, c.name, c.value, c.unit.empty() ? "" : " " + c.unit, c.limit,
                              c.unit.empty() ? "" : " " + c.unit, c.limitRule));
  }
  return out;
}

Verdict judgeRun(const json& report, const AcceptanceLimits& limits) {
  Verdict v;
  const json& surface = report.value("surface", json::object());
  if (surface.contains("bbox_m") && surface["bbox_m"].is_array() && surface["bbox_m"].size() >= 2)
    v.spanM = std::max(surface["bbox_m"][0].get<double>(), surface["bbox_m"][1].get<double>());
  const json& simulation = report.value("simulation", json::object());
  // An unconverged run is no equilibrium: its shape is where Newton stopped, not where the grid
  // would stand. Its failure is the simulation's own; the shape criteria wait for an equilibrium.
  const bool simulated = ran(simulation) && simulation.value("converged", true);
  const std::string noSimulation = ran(simulation) ? std::string("the simulation did not converge")
                                                   : notRunReason(simulation, "the simulation");

  // The patch-by-patch deployment (every patch held along its sides, as the thesis simulated
  // them) and the joined structure (the patches bolted to each other, held at the design
  // boundary): the joined one is the structure that is built, so its error decides when it ran.
  double value = 0.0;
  Criterion rmse = lengthCriterion("patch_by_patch_rmse",
                                   "RMS distance of the deployed patches from the design surface",
                                   v.spanM, limits.rmseOverSpan);
  {
    // Measured first: the arguments of one call are evaluated in no fixed order.
    const bool measured = simulated && number(simulation, "rmse_m", value);
    evaluate(rmse, measured, value, noSimulation);
  }
  Criterion max =
      lengthCriterion("patch_by_patch_max_error",
                      "largest distance of the deployed patches from the design surface", v.spanM,
                      limits.maxErrorOverSpan);
  {
    // Measured first: the arguments of one call are evaluated in no fixed order.
    const bool measured = simulated && number(simulation, "max_error_m", value);
    evaluate(max, measured, value, noSimulation);
  }
  v.criteria.push_back(rmse);
  v.criteria.push_back(max);

  const json& joined = simulated ? simulation.value("joined", json::object()) : json::object();
  const bool joinedRan =
      joined.value("ran", false) && !joined.contains("failure") && joined.value("converged", true);
  std::string noJoined = noSimulation;
  if (simulated && joined.contains("skipped_reason"))
    noJoined = "the joined simulation did not run: " + joined["skipped_reason"].get<std::string>();
  else if (simulated && joined.contains("failure"))
    noJoined = "the joined simulation failed: " + joined["failure"].get<std::string>();
  else if (simulated)
    noJoined = "the joined simulation did not converge";
  Criterion joinedRmse =
      lengthCriterion("joined_rmse", "RMS distance of the joined structure from the design surface",
                      v.spanM, limits.rmseOverSpan);
  {
    // Measured first: the arguments of one call are evaluated in no fixed order.
    const bool measured = joinedRan && number(joined, "rmse_m", value);
    evaluate(joinedRmse, measured, value, noJoined);
  }
  Criterion joinedMax = lengthCriterion(
      "joined_max_error", "largest distance of the joined structure from the design surface",
      v.spanM, limits.maxErrorOverSpan);
  {
    // Measured first: the arguments of one call are evaluated in no fixed order.
    const bool measured = joinedRan && number(joined, "max_error_m", value);
    evaluate(joinedMax, measured, value, noJoined);
  }
  v.criteria.push_back(joinedRmse);
  v.criteria.push_back(joinedMax);

  // Sag: measured by each patch's run from its own weightless equilibrium (the joined run starts
  // from the patches' loaded equilibria, so it measures a settling, not the sag).
  Criterion sag = lengthCriterion("max_sag", "largest sag under self-weight (patch by patch)",
                                  v.spanM, limits.maxSagOverSpan);
  double largestSag = 0.0;
  bool sagMeasured = false;
  if (simulated && simulation.value("gravity", false) && simulation.contains("patches")) {
    for (const json& p : simulation["patches"]) {
      double s = 0.0;
      if (number(p, "max_sag_m", s)) {
        largestSag = std::max(largestSag, s);
        sagMeasured = true;
      }
    }
  }
  evaluate(sag, sagMeasured, largestSag,
           simulated ? "the simulation ran without self-weight (simulation.gravity = false)"
                     : noSimulation);
  v.criteria.push_back(sag);

  const json& fabrication = report.value("fabrication", json::object());
  Criterion stress;
  stress.name = "max_stress_ratio";
  stress.what = "largest bending and torsion stress of a deployed lamella over its strength";
  stress.limit = limits.maxStressRatio;
  stress.limitRule = fmt::format("acceptance.max_stress_ratio = {:.4g}", limits.maxStressRatio);
  const bool stressed = ran(fabrication) && number(fabrication, "max_stress_ratio", value);
  evaluate(stress, stressed, value,
           notRunReason(fabrication, "fabrication (which computes the lamella stresses)"));
  v.criteria.push_back(stress);
  return v;
}

json verdictJson(const Verdict& verdict) {
  json criteria = json::array();
  for (const Criterion& c : verdict.criteria) {
    json j{{"name", c.name}, {"what", c.what}, {"evaluated", c.evaluated}, {"passed", c.passed}};
    if (c.evaluated) {
      j["value"] = c.value;
      j["limit"] = c.limit;
    } else {
      j["not_evaluated_reason"] = c.notEvaluatedReason;
      j["limit"] = c.limit;
    }
    j["unit"] = c.unit;
    j["limit_rule"] = c.limitRule;
    criteria.push_back(j);
  }
  return {{"passed", verdict.passed()}, {"span_m", verdict.spanM}, {"criteria", criteria}};
}

std::string runSummary(const json& report, const std::filesystem::path& outDir, double seconds) {
  const std::string name = report.value("scene", json::object()).value("name", std::string("run"));
  std::string out;
  const json& patches = report.value("patches", json::array());
  const json& coverage = report.value("coverage", json::object());
  double covered = 0.0;
  out +=
      fmt::format("egg run: {}: {} patch{}", name, patches.size(), patches.size() == 1 ? "" : "es");
  if (number(coverage, "fraction", covered)) out += fmt::format(", coverage {:.3f}", covered);
  out += "\n";
  const json& acceptance = report.value("acceptance", json::object());
  for (const json& c : acceptance.value("criteria", json::array())) {
    const std::string unit = c.value("unit", std::string());
    const std::string label = c.value("name", std::string());
    if (!c.value("evaluated", false)) {
      out += fmt::format("  {:<26} not evaluated ({})\n", label,
                         c.value("not_evaluated_reason", std::string()));
      continue;
    }
    const std::string u = unit.empty() ? "" : " " + unit;
    out += fmt::format("  {:<26} {:>10.4g}{:<2} limit {:.4g}{:<2} {}\n", label,
                       c["value"].get<double>(), u, c["limit"].get<double>(), u,
                       c.value("passed", false) ? "ok" : "FAILED");
  }
  std::vector<std::string> warnings;
  for (const json& w : report.value("warnings", json::array()))
    warnings.push_back(w.is_string() ? w.get<std::string>() : w.dump());
  if (!warnings.empty()) {
    out += fmt::format("  {} warning{} (all in report.json and report.html):\n", warnings.size(),
                       warnings.size() == 1 ? "" : "s");
    constexpr size_t kShown = 3;
    for (size_t i = 0; i < std::min(kShown, warnings.size()); ++i)
      out += "    " + warnings[i] + "\n";
    if (warnings.size() > kShown)
      out += fmt::format("    ... and {} more\n", warnings.size() - kShown);
  }
  const json& failures = report.value("failures", json::array());
  for (const json& f : failures) out += "  failure: " + f.get<std::string>() + "\n";
  out += fmt::format("  results in {}\n", outDir.string());
  if (failures.empty())
    out += fmt::format("egg run: {} passed in {:.2f} s\n", name, seconds);
  else
    out += fmt::format("egg run: {} FAILED ({} failure{}) after {:.2f} s\n", name, failures.size(),
                       failures.size() == 1 ? "" : "s", seconds);
  return out;
}

}  // namespace egg::pipeline
