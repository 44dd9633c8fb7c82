#include "pipeline/report_html.hpp"

#include "pipeline/deployed_view.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"
#include "pipeline/cladding_plot.hpp"
#include "pipeline/error_time_plot.hpp"
#include "pipeline/report_figure_sections.hpp"
#include "pipeline/stages.hpp"
#include "pipeline/svg_png.hpp"

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// A report value as text: numbers with `digits` significant digits, null as a dash.
std::string text(const json& value, int digits = 4) {
  if (value.is_null()) return "&ndash;";
  if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
  if (value.is_number_integer() || value.is_number_unsigned())
    return fmt::format("{}", value.get<long long>());
  if (value.is_number()) return fmt::format("{:.{}g}", value.get<double>(), digits);
  if (value.is_string()) return escapeXml(value.get<std::string>());
  if (value.is_array() &&
      std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); })) {
    std::string out;  // a list of numbers (buckling factors): "1.891, 2.259"
    for (const auto& v : value) out += (out.empty() ? "" : ", ") + text(v, digits);
    return out.empty() ? "&ndash;" : out;
  }
  return escapeXml(value.dump());
}

json at(const json& j, const std::string& key) {
  return j.is_object() && j.contains(key) ? j[key] : json();
}

double numberOr(const json& j, const std::string& key, double fallback = 0.0) {
  const json v = at(j, key);
  return v.is_number() ? v.get<double>() : fallback;
}

// A table of key figures: (label, value) rows.
std::string figures(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string out = "<table class=\"figures\">\n";
  for (const auto& [label, value] : rows)
    out += "<tr><th>" + escapeXml(label) + "</th><td>" + value + "</td></tr>\n";
  return out + "</table>\n";
}

// Horizontal bars, one per (label, value), scaled to the largest; `marker` > 0 draws a vertical
// line at that value (a stress ratio of 1). Inline SVG.
std::string barChart(const std::string& id, const std::vector<std::pair<std::string, double>>& bars,
                     const std::string& unit, double marker = 0.0) {
  const double rowHeight = 18.0, labelWidth = 170.0, plotWidth = 520.0;
  double largest = marker;
  for (const auto& b : bars) largest = std::max(largest, std::isfinite(b.second) ? b.second : 0.0);
  if (largest <= 0.0) largest = 1.0;
  const double height = rowHeight * static_cast<double>(bars.size()) + 24.0;
  std::string svg = fmt::format(
      "<svg id=\"{}\" class=\"chart\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {:.0f} "
      "{:.0f}\" role=\"img\">\n",
      id, labelWidth + plotWidth + 90.0, height, labelWidth + plotWidth + 90.0, height);
  for (size_t i = 0; i < bars.size(); ++i) {
    const double y = rowHeight * static_cast<double>(i);
    const double value = std::isfinite(bars[i].second) ? std::max(0.0, bars[i].second) : 0.0;
    const double w = plotWidth * value / largest;
    svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\" font-size=\"12\">{}</text>",
        labelWidth - 6.0, y + 13.0, escapeXml(bars[i].first));
    svg += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{:.1f}\" fill=\"#4a7fb5\" "
        "data-value=\"{:.6g}\"/>",
        labelWidth, y + 3.0, w, rowHeight - 5.0, value);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\">{:.3g} {}</text>\n",
                       labelWidth + w + 4.0, y + 13.0, value, escapeXml(unit));
  }
  if (marker > 0.0) {
    const double x = labelWidth + plotWidth * marker / largest;
    svg += fmt::format(
        "<line x1=\"{:.1f}\" y1=\"0\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#c62828\" "
        "stroke-dasharray=\"4 3\"/>",
        x, x, height - 20.0);
    svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"#c62828\" "
        "text-anchor=\"middle\">{:.3g}</text>\n",
        x, height - 6.0, marker);
  }
  return svg + "</svg>\n";
}

// The verdict (acceptance.hpp): every criterion with its value and limit, at the top.
std::string acceptanceSection(const json& report) {
  const json acceptance = at(report, "acceptance");
  if (!acceptance.is_object()) return {};
  const bool passed = acceptance.value("passed", false);
  std::string html = std::string("<div class=\"") + (passed ? "passed" : "failures") +
                     "\" id=\"acceptance\"><p>Acceptance: " +
                     (passed ? "every criterion met" : "criteria missed") +
                     " (limits from the scene's <code>acceptance</code> section; span " +
                     text(at(acceptance, "span_m")) + " m)</p><table class=\"figures\">\n";
  html += "<tr><th>criterion</th><th>value</th><th>limit</th><th>verdict</th></tr>\n";
  for (const json& c : at(acceptance, "criteria")) {
    const std::string unit = c.value("unit", std::string());
    const std::string u = unit.empty() ? "" : " " + unit;
    html += "<tr><td>" + escapeXml(c.value("what", std::string())) + "</td>";
    if (c.value("evaluated", false)) {
      html += "<td>" + text(at(c, "value")) + u + "</td><td>" + text(at(c, "limit")) + u + " (" +
              escapeXml(c.value("limit_rule", std::string())) + ")</td><td>" +
              (c.value("passed", false) ? "ok" : "<b>failed</b>") + "</td></tr>\n";
    } else {
      html += "<td colspan=\"3\">not evaluated: " +
              escapeXml(c.value("not_evaluated_reason", std::string())) + "</td></tr>\n";
    }
  }
  return html + "</table></div>\n";
}

std::string stageTimes(const json& report) {
  std::string out =
      "<h2 id=\"stage-times\">Stage times</h2>\n<table "
      "class=\"list\"><tr><th>stage</th><th>ran</th><th>s</th><th>why not</th></tr>\n";
  std::vector<std::pair<std::string, double>> bars;
  const json stages = at(report, "stages");
  for (StageId id : allStages()) {
    const std::string stage = toString(id);
    const json s = at(stages, stage);
    const bool ran = at(s, "ran").is_boolean() && s["ran"].get<bool>();
    out += "<tr><td>" + escapeXml(stage) + "</td><td>" + (ran ? "yes" : "no") + "</td><td>" +
           text(at(s, "seconds")) + "</td><td>" + text(at(s, "skipped_reason")) + "</td></tr>\n";
    bars.emplace_back(stage, numberOr(s, "seconds"));
  }
  out += "</table>\n";
  out += "<p>Total " + text(at(at(report, "timings"), "total_s")) + " s.</p>\n";
  return out + barChart("stage-time-chart", bars, "s");
}

std::string patchesSection(const json& report) {
  std::string out = "<h2 id=\"patches\">Patches</h2>\n";
  const json patches = at(report, "patches");
  if (!patches.is_array() || patches.empty()) return out + "<p class=\"missing\">No patches.</p>\n";
  out +=
      "<table class=\"list\"><tr><th>patch</th><th>feasible</th><th>area m&sup2;</th><th>members u "
      "&times; v</th>"
      "<th>&eta; u</th><th>&eta; v</th><th>max notch m</th><th>why not</th></tr>\n";
  for (const auto& p : patches) {
    out += "<tr><td>" + text(at(p, "id")) + "</td><td>" + text(at(p, "feasible")) + "</td><td>" +
           text(at(p, "area_m2")) + "</td><td>" + text(at(p, "members_u")) + " &times; " +
           text(at(p, "members_v")) + "</td><td>" + text(at(p, "eta_u"), 6) + "</td><td>" +
           text(at(p, "eta_v"), 6) + "</td><td>" + text(at(p, "max_notch_m")) + "</td><td>" +
           text(at(p, "reason")) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

// Each traced patch's F_u and F_v (Sections 2.4.3, 2.4.4) from report.json patches[].cladding.
std::string claddingSection(const json& report) {
  std::string out = "<h2 id=\"cladding\">Cladding functions</h2>\n";
  std::string figures;
  for (const auto& p : at(report, "patches")) {
    const auto plot = claddingFromReport(p);
    if (plot)
      figures += "<div class=\"figure\" style=\"margin:4px\">\n" + claddingSvg(*plot) + "</div>\n";
  }
  if (figures.empty())
    return out + "<p class=\"missing\">No cladding functions: no patch grid was traced.</p>\n";
  return out +
         "<p>F pairs a member's start on one side of the patch with its end on the opposite side "
         "(Section 2.4.3); the dots are the "
         "members. Below each, the slopes of F's segments (dx<sub>2</sub>/dx<sub>1</sub> of the "
         "side parameters, log scale) against "
         "the band (k<sub>min</sub>, k<sub>max</sub>) of patching.slope_bounds that Problem 2.3 "
         "keeps them in; red: outside.</p>\n" +
         figures;
}

// The error of each simulation run against its wall time (simulation.patches[].history,
// joined.history).
std::string errorTimeSection(const json& report) {
  std::string out = "<h2 id=\"error-time\">Simulation: error against run time</h2>\n";
  const json sim = at(report, "simulation");
  std::vector<ErrorTimeSeries> patches;
  for (const auto& p : at(sim, "patches"))
    if (at(p, "history").is_array() && !p["history"].empty())
      patches.push_back({"patch " + at(p, "patch").dump(),
                         historyFromJson(p["history"], "simulation.patches[].history")});
  const json joined = at(sim, "joined");
  const bool joinedHistory = at(joined, "history").is_array() && !joined["history"].empty();
  if (patches.empty() && !joinedHistory)
    return out + "<p class=\"missing\">No error history: the simulation did not run.</p>\n";
  out += fmt::format(
      "<p>RMSE and largest distance of the contact points from the design surface while Newton "
      "runs (every {} "
      "iteration{} and at the end of every load step), against the run's wall time without the "
      "time spent measuring.</p>\n",
      kErrorHistoryEvery, kErrorHistoryEvery == 1 ? "" : "s");
  if (!patches.empty())
    out += errorTimeSvg("error-time-patches",
                        "Patch by patch (each patch's own clock; the patches run in parallel)",
                        patches);
  if (joinedHistory)
    out +=
        errorTimeSvg("error-time-joined",
                     "Joined structure (from the patch-by-patch equilibria when they converged)",
                     {{"joined", historyFromJson(joined["history"], "simulation.joined.history")}});
  return out;
}

std::string simulationSection(const json& report) {
  std::string out = "<h2 id=\"simulation\">Simulation: deviation from the design surface</h2>\n";
  const json sim = at(report, "simulation");
  if (!(at(sim, "ran").is_boolean() && sim["ran"].get<bool>())) {
    return out + "<p class=\"missing\">Not run: " + text(at(sim, "skipped_reason")) + "</p>\n";
  }
  out += figures({{"converged", text(at(sim, "converged"))},
                  {"RMSE (m)", text(at(sim, "rmse_m"))},
                  {"max error (m)", text(at(sim, "max_error_m"))},
                  {"NRMSE (worst patch)", text(at(sim, "nrmse"))},
                  {"RMSE without notches (m)", text(at(sim, "rmse_no_notches_m"))},
                  {"iterations", text(at(sim, "iterations"))}});
  const json patches = at(sim, "patches");
  if (!patches.is_array() || patches.empty()) return out;
  out +=
      "<table class=\"list\"><tr><th>patch</th><th>converged</th><th>iterations</th><th>RMSE "
      "m</th><th>max error m</th>"
      "<th>s</th><th>failure</th></tr>\n";
  std::vector<std::pair<std::string, double>> bars;
  for (const auto& p : patches) {
    out += "<tr><td>" + text(at(p, "patch")) + "</td><td>" + text(at(p, "converged")) +
           "</td><td>" + text(at(p, "iterations")) + "</td><td>" + text(at(p, "rmse_m")) +
           "</td><td>" + text(at(p, "max_error_m")) + "</td><td>" + text(at(p, "seconds")) +
           "</td><td>" + text(at(p, "failure")) + "</td></tr>\n";
    bars.emplace_back("patch " + at(p, "patch").dump(), numberOr(p, "max_error_m"));
  }
  out += "</table>\n<p>Largest deviation per patch:</p>\n";
  return out + barChart("simulation-error-chart", bars, "m");
}

std::string fabricationSection(const json& report) {
  std::string out = "<h2 id=\"fabrication\">Fabrication</h2>\n";
  const json fab = at(report, "fabrication");
  if (!(at(fab, "ran").is_boolean() && fab["ran"].get<bool>())) {
    return out + "<p class=\"missing\">Not run: " + text(at(fab, "skipped_reason")) + "</p>\n";
  }
  out += figures(
      {{"material", text(at(fab, "material"))},
       {"lamellas", text(at(fab, "lamellae"))},
       {"total length (m)", text(at(fab, "total_length_m"))},
       {"mass (kg)", text(at(fab, "mass_kg"))},
       {"sheets (yield)", text(at(fab, "sheets")) + " (" + text(at(fab, "yield")) + ")"},
       {"bolts / notches / splices", text(at(fab, "bolts")) + " / " + text(at(fab, "notches")) +
                                         " / " + text(at(fab, "splices"))},
       {"supports", text(at(fab, "supports"))},
       {"max stress ratio",
        text(at(fab, "max_stress_ratio")) + " (" + text(at(fab, "max_stress_lamella")) + ")"},
       {"max bending stress (Pa)", text(at(fab, "max_bending_stress_pa"))},
       {"max torsion stress (Pa)", text(at(fab, "max_torsion_stress_pa"))}});
  const json unspliced = at(fab, "unspliceable_lamellae");
  if (unspliced.is_array() && !unspliced.empty()) {
    out += "<div class=\"failures\"><p>" + std::to_string(unspliced.size()) +
           " lamellas cannot be spliced and are not in the cut files:</p><ul>\n";
    for (const auto& u : unspliced) out += "<li>" + text(u) + "</li>\n";
    out += "</ul></div>\n";
  }
  // Stress ratios (Section 3.5.2): a histogram in bins of 0.1 up to the largest, and the highest
  // ten.
  const json stress = at(fab, "lamella_stress");
  if (stress.is_array() && !stress.empty()) {
    std::vector<std::pair<std::string, double>> lamellas;
    for (const auto& s : stress)
      lamellas.emplace_back(at(s, "id").is_string() ? s["id"].get<std::string>() : "?",
                            numberOr(s, "ratio"));
    double largest = 0.0;
    for (const auto& l : lamellas) largest = std::max(largest, l.second);
    const int bins = std::max(1, static_cast<int>(std::ceil(largest / 0.1 - 1e-9)));
    std::vector<std::pair<std::string, double>> histogram;
    for (int b = 0; b < std::min(bins, 40); ++b) {
      const bool last = b == std::min(bins, 40) - 1;
      int count = 0;
      for (const auto& l : lamellas) {
        const int bin =
            std::min(static_cast<int>(std::floor(l.second / 0.1)), std::min(bins, 40) - 1);
        count += bin == b ? 1 : 0;
      }
      histogram.emplace_back(
          fmt::format("{:.1f}{}{:.1f}", 0.1 * b, last && bins > 40 ? " and over " : " - ",
                      last && bins > 40 ? largest : 0.1 * (b + 1)),
          count);
    }
    out += "<p>Stress ratio max(&sigma;/f<sub>m</sub>, &tau;/f<sub>v</sub>) of the " +
           std::to_string(lamellas.size()) + " lamellas (count per bin):</p>\n" +
           barChart("stress-histogram", histogram, "lamellas");
    std::sort(lamellas.begin(), lamellas.end(),
              [](const auto& a, const auto& b) { return a.second > b.second; });
    if (lamellas.size() > 10) lamellas.resize(10);
    out += "<p>The highest ten (the dashed line is the strength):</p>\n" +
           barChart("stress-top", lamellas, "", 1.0);
  }
  return out;
}

// bom.csv as a table; the last column (the note) keeps any further commas.
std::string bomSection(const std::string& bom) {
  std::string out = "<h2 id=\"bom\">Bill of materials</h2>\n";
  if (bom.empty())
    return out + "<p class=\"missing\">No bom.csv: the fabrication stage did not run.</p>\n";
  std::istringstream in(bom);
  std::string line;
  std::vector<std::vector<std::string>> rows;
  size_t columns = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    size_t from = 0;
    while (true) {
      const size_t comma = line.find(',', from);
      if (comma == std::string::npos || (columns > 0 && cells.size() + 1 == columns)) {
        cells.push_back(line.substr(from));
        break;
      }
      cells.push_back(line.substr(from, comma - from));
      from = comma + 1;
    }
    if (columns == 0) columns = cells.size();
    rows.push_back(std::move(cells));
  }
  // Everything but the individual lamellas and splice joints up front; those in a fold.
  auto tableOf = [&](bool detail) {
    std::string t = "<table class=\"list bom\"><tr>";
    for (const auto& h : rows.front()) t += "<th>" + escapeXml(h) + "</th>";
    t += "</tr>\n";
    for (size_t r = 1; r < rows.size(); ++r) {
      const bool isDetail = rows[r][0] == "lamella" || rows[r][0] == "splice_joint";
      if (isDetail != detail) continue;
      t += "<tr>";
      for (const auto& c : rows[r]) t += "<td>" + escapeXml(c) + "</td>";
      t += "</tr>\n";
    }
    return t + "</table>\n";
  };
  out += tableOf(false);
  return out + "<details><summary>Every lamella and splice joint (" +
         std::to_string(rows.size() - 1) + " rows in all)</summary>\n" + tableOf(true) +
         "</details>\n";
}

const char* kStyle =
    R"(body{font-family:"DejaVu Sans",Helvetica,Arial,sans-serif;margin:24px;color:#222;max-width:1400px}
h1{font-size:24px}h2{font-size:19px;margin-top:32px;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:8px 0}th,td{padding:2px 8px;text-align:left;font-size:13px;vertical-align:top}
table.list tr:nth-child(even){background:#f3f5f8}table.list th{background:#dde4ee}
table.figures th{font-weight:normal;color:#555}.failures{background:#fdecea;border:1px solid #c62828;padding:4px 12px}.passed{background:#e8f5e9;border:1px solid #2e7d32;padding:4px 12px}
.warnings{background:#fff8e1;border:1px solid #f9a825;padding:4px 12px}.missing{color:#777;font-style:italic}
svg.chart{display:block;margin:8px 0}.figure{border:1px solid #ddd;display:inline-block;max-width:100%})";

// The FE check (output "fem"): what ccx found per load case, buckling, the cross-check against
// the rods, and the figure; or why it was not solved.
// The deployment (docs/deployment.md): per patch the path chosen and why, the peak stress ratio on
// the way beside the end state's, snaps, jams, the largest support force; then the chart.
std::string deploymentSection(const json& report, const std::string& figureSvg) {
  const json d = at(report, "deployment");
  if (!d.is_object() || !d.value("ran", false)) return "";
  std::string html =
      "<h2 id=\"deployment\">Deployment: from the flat grid to the supports</h2>\n<p>" +
      text(at(d, "paths")) +
      ". Self-weight is not included on the patches' paths; the joining (row \"joined\") carries "
      "it when the simulation does.</p>\n<table>\n<tr><th>patch</th>"
      "<th>path</th><th>why</th><th>steps</th><th>peak stress ratio</th><th>at t</th>"
      "<th>end state</th><th>snaps</th><th>jammed steps</th><th>largest support force "
      "(kN)</th><th>end vs simulation (mm)</th></tr>\n";
  for (const auto& p : at(d, "patches")) {
    if (p.contains("failure")) {
      html += "<tr><td>P" + text(at(p, "patch")) +
              "</td><td colspan=\"10\">failed: " + text(at(p, "failure")) + "</td></tr>\n";
      continue;
    }
    const json end = at(p, "end_vs_simulation_rms_m");
    html += "<tr><td>P" + text(at(p, "patch")) + "</td><td>" + text(at(p, "path_kind")) +
            "</td><td>" + text(at(p, "path_choice")) + "</td><td>" + text(at(p, "steps")) +
            "</td><td>" + text(at(p, "peak_stress_ratio"), 3) + "</td><td>" +
            text(at(p, "peak_t"), 3) + "</td><td>" + text(at(p, "end_stress_ratio"), 3) +
            "</td><td>" + text(at(p, "snaps")) + "</td><td>" + text(at(p, "jammed_steps")) +
            "</td><td>" + text(json(1e-3 * at(p, "max_support_force_n").get<double>()), 4) +
            "</td><td>" + (end.is_number() ? text(json(1e3 * end.get<double>()), 3) : "-") +
            "</td></tr>\n";
  }
  const json joined = at(d, "joined");
  if (joined.is_object() && joined.value("ran", false)) {
    if (joined.contains("failure")) {
      html += "<tr><td>joined</td><td colspan=\"10\">failed: " + text(at(joined, "failure")) +
              "</td></tr>\n";
    } else {
      const json end = at(joined, "end_vs_joined_simulation_rms_m");
      html += "<tr><td>joined</td><td>joining</td><td>" + text(at(joined, "phases")) + "</td><td>" +
              text(at(joined, "steps")) + "</td><td>" + text(at(joined, "peak_stress_ratio"), 3) +
              "</td><td>" + text(at(joined, "peak_t"), 3) + "</td><td>" +
              text(at(joined, "end_stress_ratio"), 3) + "</td><td>" + text(at(joined, "snaps")) +
              "</td><td>" + text(at(joined, "jammed_steps")) + "</td><td>" +
              text(json(1e-3 * at(joined, "max_support_force_n").get<double>()), 4) + "</td><td>" +
              (end.is_number() ? text(json(1e3 * end.get<double>()), 3) : "-") +
              " (joined)</td></tr>\n";
    }
  }
  return html + "</table>\n" + report_sections::deploymentFigure(figureSvg);
}

std::string verificationSection(const json& report, const std::string& figureSvg) {
  const json stage = at(at(report, "stages"), "verification");
  const json v = at(report, "verification");
  if (!v.is_object() && !(at(stage, "ran").is_boolean() && !stage["ran"].get<bool>())) return "";
  std::string out = "<h2 id=\"verification\">Structural check (CalculiX)</h2>\n";
  if (!v.is_object() || v.empty())
    return out + "<p class=\"missing\">Not run: " + text(at(stage, "skipped_reason")) + "</p>\n";
  if (v.contains("failure"))
    return out + "<p class=\"failures\">Failed: " + text(at(v, "failure")) + "</p>\n";
  const json model = at(v, "model");
  out += figures({{"structure", text(at(v, "structure"))},
                  {"ccx version", text(at(v, "ccx_version"))},
                  {"model", text(at(v, "model_file")) + ": " + text(at(model, "nodes")) +
                                " nodes, " + text(at(model, "elements")) + " beam elements"}});
  if (at(v, "solved").is_boolean() && !v["solved"].get<bool>())
    return out + "<p class=\"missing\">Not solved: " + text(at(v, "not_solved_reason")) + "</p>\n";
  out +=
      "<table class=\"list\"><tr><th>load case</th><th>analysis</th><th>max displacement "
      "m</th><th>reactions / load</th><th>equilibrium residual</th><th>max "
      "utilisation</th><th>worst lamella</th></tr>\n";
  for (const auto& c : at(v, "cases")) {
    const json top = at(c, "top");
    const std::string worst =
        top.is_array() && !top.empty() ? text(at(top[0], "lamella")) : std::string("-");
    const std::string analysis = at(c, "analysis") == "first_order" ? "first order" : "nonlinear";
    out += "<tr><td>" + text(at(c, "name")) + "</td><td>" + analysis + "</td><td>" +
           text(at(c, "max_displacement_m")) + "</td><td>" + text(at(c, "reaction_ratio"), 8) +
           "</td><td>" + text(at(c, "equilibrium_residual")) + "</td><td>" +
           text(at(c, "max_utilisation")) + "</td><td>" + worst + "</td></tr>\n";
  }
  out += "</table>\n";
  const json sag = at(v, "der_vs_fem");
  out += figures(
      {{"buckling factors (case " + text(at(v, "buckling_case")) + ")",
        text(at(v, "buckling_factors"))},
       {"buckling verdict", text(at(v, "buckling_verdict"))},
       {"rods vs FE sag under self-weight: RMS / max difference (m)",
        text(at(sag, "rms_m")) + " / " + text(at(sag, "max_m"))},
       {"where the two models differ by construction", text(at(sag, "differs_by_construction"))}});
  const size_t start = figureSvg.find("<svg");
  if (start == std::string::npos) return out;
  // Inlined without the namespace the file carries (the page's charts have none).
  std::string svg = figureSvg.substr(start);
  if (const size_t ns = svg.find(" xmlns=\"http://www.w3.org/2000/svg\"");
      ns != std::string::npos && ns < svg.find('>'))
    svg.erase(ns, 35);
  return out + "<div class=\"figure\">\n" + svg + "</div>\n";
}

}  // namespace

std::string reportHtml(const json& report, const ReportFiles& files) {
  const json scene = at(report, "scene");
  const std::string name =
      at(scene, "name").is_string() ? scene["name"].get<std::string>() : "eggshell run";
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
      escapeXml(name) + " &ndash; eggshell report</title>\n<style>\n" + kStyle +
      "\n</style>\n</head>\n<body>\n";
  html += "<h1>" + escapeXml(name) + "</h1>\n<p>Scene " + text(at(scene, "path")) +
          "; everything below is report.json of this run (metres, radians and seconds; cut files "
          "in millimetres).</p>\n";
  const json failures = at(report, "failures");
  if (failures.is_array() && !failures.empty()) {
    html += "<div class=\"failures\" id=\"failures\"><p>The run failed:</p><ul>\n";
    for (const auto& f : failures) html += "<li>" + text(f) + "</li>\n";
    html += "</ul></div>\n";
  }
  html += acceptanceSection(report);
  // Every stage's warnings are in the top-level list (fabrication's included), shown open.
  std::vector<std::string> warnings;
  for (const auto& w : at(report, "warnings"))
    warnings.push_back(w.is_string() ? w.get<std::string>() : w.dump());
  if (!warnings.empty()) {
    html += "<div class=\"warnings\" id=\"warnings\"><details open><summary>" +
            std::to_string(warnings.size()) + " warnings</summary><ul>\n";
    for (const auto& w : warnings) html += "<li>" + escapeXml(w) + "</li>\n";
    html += "</ul></details></div>\n";
  }
  html += stageTimes(report) + report_sections::planSection(files.planSvg, files.curvatureSvg) +
          patchesSection(report) + report_sections::generalisedSection(report) +
          report_sections::patchGridsSection(files.planarSvgs) + claddingSection(report) +
          simulationSection(report) + errorTimeSection(report) +
          deployedViewSection(files.deployedViewJson) +
          report_sections::deployedSection(files.deployedSvg) +
          report_sections::elevationsSection(files.elevationsSvg) +
          verificationSection(report, files.verificationSvg) +
          deploymentSection(report, files.deploymentSvg) + fabricationSection(report) +
          bomSection(files.bomCsv);
  return html + "</body>\n</html>\n";
}

std::vector<std::pair<std::string, std::string>> reportFigures(const std::string& html,
                                                               const std::string& planSvg) {
  std::vector<std::pair<std::string, std::string>> out;
  const size_t planStart = planSvg.find("<svg");
  const size_t planEnd = planSvg.rfind("</svg>");
  if (planStart != std::string::npos && planEnd != std::string::npos && planEnd > planStart)
    out.emplace_back("plan", planSvg.substr(planStart, planEnd + 6 - planStart));
  // The page's own charts: each an <svg id="..."> without nesting. The inline copy needs no
  // namespace inside HTML; a stand-alone SVG does, so librsvg reads it as SVG.
  for (size_t at = html.find("<svg id=\""); at != std::string::npos;
       at = html.find("<svg id=\"", at + 1)) {
    const size_t idStart = at + 9, idEnd = html.find('"', idStart), end = html.find("</svg>", at);
    if (idEnd == std::string::npos || end == std::string::npos) break;
    std::string svg = html.substr(at, end + 6 - at);
    if (svg.find("xmlns=") == std::string::npos)
      svg.insert(4, " xmlns=\"http://www.w3.org/2000/svg\"");
    out.emplace_back(html.substr(idStart, idEnd - idStart), std::move(svg));
  }
  return out;
}

std::vector<std::string> writeReportHtml(const std::filesystem::path& runDir, const json& report,
                                         std::vector<std::string>* problems) {
  auto readIfThere = [&](const char* file) -> std::string {
    const auto path = runDir / file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return "";
    return readRegularFile(path, std::size_t{1} << 30, file);
  };
  ReportFiles files;
  files.planSvg = readIfThere("plan.svg");
  files.curvatureSvg = readIfThere("curvature.svg");
  for (const auto& p : at(report, "patches")) {
    if (!at(p, "id").is_number_integer()) continue;
    const int id = p["id"].get<int>();
    const std::string file = fmt::format("patch_{:03d}/planar.svg", id);
    const std::string text = readIfThere(file.c_str());
    if (!text.empty()) files.planarSvgs.emplace_back(id, text);
  }
  files.bomCsv = readIfThere("bom.csv");
  files.deployedSvg = readIfThere("deployed.svg");
  files.elevationsSvg = readIfThere("elevations.svg");
  files.verificationSvg = readIfThere("fem/verification.svg");
  files.deploymentSvg = readIfThere("deployment.svg");
  files.deployedViewJson = readIfThere("deployed.json");
  const std::string html = reportHtml(report, files);
  writeFileAtomically(runDir / "report.html", html);
  // PNG previews of the same figures (issue 18): the plan wide enough to read, the charts at their
  // size.
  std::vector<std::string> previews;
  const auto dir = runDir / "preview";
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw WriteError("cannot create " + dir.string() + ": " + error.message());
  const auto figures = reportFigures(html, files.planSvg);
  for (const auto& [id, svg] : figures) {
    std::string file = id;
    std::replace(file.begin(), file.end(), '-', '_');
    previews.push_back("preview/" + file + ".png");
  }
  // Rasterised side by side (each with its own librsvg handle and cairo surface): 16 figures of
  // the Great Court took ~0.6 s one after the other. An exception in any is rethrown here.
  // A figure librsvg cannot draw loses its preview, not the run: the run's own files are all
  // there, and the problem goes to the report's warnings.
  std::vector<std::string> failed(figures.size());
  tbb::parallel_for(size_t{0}, figures.size(), [&](size_t k) {
    try {
      writePngFromSvg(figures[k].second, runDir / previews[k],
                      figures[k].first == "plan" || figures[k].first == "curvature"
                          ? kPlanPreviewPx
                          : kChartPreviewPx);
    } catch (const WriteError&) {
      throw;  // the run folder cannot be written: the run fails as for any file
    } catch (const Error& e) {
      failed[k] = e.what();
    }
  });
  std::vector<std::string> drawn;
  for (size_t k = 0; k < figures.size(); ++k) {
    if (failed[k].empty())
      drawn.push_back(previews[k]);
    else if (problems != nullptr)
      problems->push_back(previews[k] + " not drawn: " + failed[k]);
  }
  return drawn;
}

}  // namespace egg::pipeline
