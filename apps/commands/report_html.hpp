#pragma once
// report.html of `egg run` (issue 18, first bullet): the run's report.json as one page a person
// reads, written next to it when the scene's outputs contain "report". Self-contained: inline CSS
// and inline SVG only, no script, no external font, image or style sheet, so it opens offline and
// can be mailed. Sections: failures and warnings, stage times, the plan of patches (plan.svg
// inlined when the scene asked for "plan"), the patches, the simulation's errors against the design
// surface, the fabrication figures with a histogram of the lamellas' stress ratios, and the BOM.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace egg::app {

// The page from the report document (report.json), the text of plan.svg and of bom.csv (either
// may be empty: that section then says why it is missing). Every text from the report is escaped.
std::string reportHtml(const nlohmann::json& report, const std::string& planSvg, const std::string& bomCsv);

// Reads `runDir`/plan.svg and `runDir`/bom.csv when present and writes `runDir`/report.html
// atomically. Throws WriteError naming the file.
void writeReportHtml(const std::filesystem::path& runDir, const nlohmann::json& report);

}  // namespace egg::app
