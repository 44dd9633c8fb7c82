#pragma once
// The sections of report.html that inline the run's SVG figures (report_html.cpp builds the page):
// the plan and the curvature sheet, the planar grids, deployed.svg and elevations.svg; and the
// generalised patches' table.
#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace egg::pipeline::report_sections {

// `svg` with `prefix` on the ids inside it (not its root's) and on the url(#...) references to
// them, so that the ids of a page inlining several figures stay unique.
std::string prefixIds(std::string svg, const std::string& prefix);
std::string planSection(const std::string& planSvg, const std::string& curvatureSvg);
std::string patchGridsSection(const std::vector<std::pair<int, std::string>>& planarSvgs);
std::string deployedSection(const std::string& deployedSvg);
std::string elevationsSection(const std::string& elevationsSvg);
// report.json generalised_patches[] as a table, and how the joined run held them (issue 41); ""
// when the run has none.
std::string generalisedSection(const nlohmann::json& report);
// deployment.svg inlined (the deployment section's chart; report_html.cpp writes its heading).
std::string deploymentFigure(const std::string& deploymentSvg);

}  // namespace egg::pipeline::report_sections
