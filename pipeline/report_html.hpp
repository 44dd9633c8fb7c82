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
#include <utility>
#include <vector>

namespace egg::pipeline {

// The page from the report document (report.json), the text of plan.svg and of bom.csv (either
// may be empty: that section then says why it is missing). Every text from the report is escaped.
// `planarSvgs` are (patch id, patch_NNN/planar.svg text), inlined as the planar-grids section;
// `deployedSvg` the text of deployed.svg (deviation_plan.hpp), inlined after the simulation
// figures; `verificationSvg` the text of fem/verification.svg (verification_figure.hpp), inlined in
// the structural check's section.
std::string reportHtml(const nlohmann::json& report, const std::string& planSvg,
                       const std::string& bomCsv,
                       const std::vector<std::pair<int, std::string>>& planarSvgs = {},
                       const std::string& deployedSvg = {}, const std::string& verificationSvg = {},
                       const std::string& deployedViewJson = {});

// The figures of the page as stand-alone SVG texts, (id, svg): plan.svg when given, then every
// chart of `html` (the output of reportHtml), each with the SVG namespace so it renders alone.
std::vector<std::pair<std::string, std::string>> reportFigures(const std::string& html,
                                                               const std::string& planSvg);

// Widths of the PNG previews in pixels.
inline constexpr int kPlanPreviewPx = 1200;
inline constexpr int kChartPreviewPx = 800;

// Reads `runDir`/plan.svg, deployed.svg and bom.csv when present, writes `runDir`/report.html
// atomically and a PNG of each figure under `runDir`/preview/ (svg_png.hpp). Returns the PNGs'
// paths relative to `runDir` (report.json's outputs.previews). Throws WriteError naming the file.
std::vector<std::string> writeReportHtml(const std::filesystem::path& runDir,
                                         const nlohmann::json& report);

}  // namespace egg::pipeline
