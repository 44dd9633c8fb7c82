#pragma once
// report.html of `egg run` (issue 18, first bullet): the run's report.json as one page a person
// reads, written next to it when the scene's outputs contain "report". Self-contained: inline CSS
// and inline SVG only, no script, no external font, image or style sheet, so it opens offline and
// can be mailed. Sections: failures and warnings, stage times, the plan of patches (plan.svg and
// curvature.svg inlined when the scene asked for "plan"), the patches, the simulation's errors
// against the design surface, the fabrication figures with a histogram of the lamellas' stress
// ratios, and the BOM.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace egg::pipeline {

// The run folder's files the page inlines; any may be empty (its section then says why it is
// missing).
struct ReportFiles {
  std::string planSvg;       // plan.svg (the architect's plan)
  std::string curvatureSvg;  // curvature.svg (the analytical sheet), shown under the plan
  std::string bomCsv;
  std::vector<std::pair<int, std::string>> planarSvgs;  // (patch id, patch_NNN/planar.svg)
  std::string deployedSvg;       // deployed.svg (deviation_plan.hpp), after the simulation figures
  std::string elevationsSvg;     // elevations.svg (elevations.hpp), after deployed.svg
  std::string verificationSvg;   // fem/verification.svg, in the structural check's section
  std::string deploymentSvg;     // deployment.svg, in the deployment's section
  std::string deployedViewJson;  // deployed.json: the 3D view's data
};

// The page from the report document (report.json) and the files. Every text from the report is
// escaped.
std::string reportHtml(const nlohmann::json& report, const ReportFiles& files);

// The figures of the page as stand-alone SVG texts, (id, svg): plan.svg when given, then every
// chart of `html` (the output of reportHtml), each with the SVG namespace so it renders alone.
std::vector<std::pair<std::string, std::string>> reportFigures(const std::string& html,
                                                               const std::string& planSvg);

// Widths of the PNG previews in pixels.
inline constexpr int kPlanPreviewPx = 1200;
inline constexpr int kChartPreviewPx = 800;

// Reads the files of ReportFiles from `runDir` when present, writes `runDir`/report.html
// atomically and a PNG of each figure under `runDir`/preview/ (svg_png.hpp). Returns the PNGs'
// paths relative to `runDir` (report.json's outputs.previews). A figure that cannot be drawn has no
// PNG and a line in `problems` ("preview/x.png not drawn: why"). Throws WriteError naming the
// file.
std::vector<std::string> writeReportHtml(const std::filesystem::path& runDir,
                                         const nlohmann::json& report,
                                         std::vector<std::string>* problems = nullptr);

}  // namespace egg::pipeline
