#include "pipeline/report_figure_sections.hpp"

#include "core/io/xml_text.hpp"

#include <fmt/core.h>

namespace egg::pipeline::report_sections {

// A figure inlined beside others: the ids inside it (not its root's) and the url(#...) references
// to them get `prefix`, so that the page's ids stay unique (plan.svg and curvature.svg both have a
// "patch-0", every sheet a "scale-bar").
std::string prefixIds(std::string svg, const std::string& prefix) {
  const size_t rootEnd = svg.find('>');
  if (rootEnd == std::string::npos) return svg;
  std::string out = svg.substr(0, rootEnd + 1);
  for (size_t at = rootEnd + 1; at < svg.size();) {
    const size_t id = svg.find(" id=\"", at), url = svg.find("url(#", at);
    const size_t next = std::min(id, url);
    if (next == std::string::npos) {
      out.append(svg, at, std::string::npos);
      break;
    }
    const size_t keep = next + 5;  // past ` id="` or `url(#`
    out.append(svg, at, keep - at).append(prefix);
    at = keep;
  }
  return out;
}

std::string planSection(const std::string& planSvg, const std::string& curvatureSvg) {
  std::string out = "<h2 id=\"plan\">Plan of patches</h2>\n";
  const size_t start = planSvg.find("<svg");
  if (start == std::string::npos) {
    return out +
           "<p class=\"missing\">No plan: the scene's outputs do not contain \"plan\" "
           "(plan.svg).</p>\n";
  }
  // plan.svg inlined: without its XML declaration, scaled to the page.
  std::string svg = planSvg.substr(start);
  svg.insert(4, " class=\"plan\" style=\"max-width:100%;height:auto\"");
  out += "<div class=\"figure\">\n" + svg + "\n</div>\n";
  // The analytical sheet (curvature.svg) as a chart of its own: <svg id="curvature"> gets its
  // PNG preview.
  const size_t k = curvatureSvg.find("<svg");
  if (k == std::string::npos) return out;
  std::string sheet = prefixIds(curvatureSvg.substr(k), "curvature-");
  sheet.insert(4, " id=\"curvature\" style=\"max-width:100%;height:auto\"");
  return out + "<h3>Curvature and injectivity (curvature.svg)</h3>\n<div class=\"figure\">\n" +
         sheet + "\n</div>\n";
}

// Each patch's flat scissor grid (Section 2.4, writePlanarSvg: U members blue, V orange, boundary
// members thick): the patch_NNN/planar.svg files of the run, inlined small side by side.
std::string patchGridsSection(const std::vector<std::pair<int, std::string>>& planarSvgs) {
  std::string out = "<h2 id=\"patch-grids\">Planar grids of the patches</h2>\n";
  if (planarSvgs.empty())
    return out +
           "<p class=\"missing\">No planar grids: the scene's outputs do not contain \"previews\" "
           "(patch_NNN/planar.svg).</p>\n";
  out +=
      "<p>The flat grid of each patch before deployment: U members blue, V members orange, "
      "boundary members thick.</p>\n";
  for (const auto& [id, text] : planarSvgs) {
    const size_t start = text.find("<svg");
    const size_t end = text.rfind("</svg>");
    if (start == std::string::npos || end == std::string::npos) continue;
    std::string svg = text.substr(start, end + 6 - start);
    svg.insert(4, fmt::format(" id=\"patch-grid-{}\" style=\"width:280px;height:auto\"", id));
    out += fmt::format(
        "<figure class=\"figure\" style=\"display:inline-block;margin:4px\">{}<figcaption>patch "
        "{}</figcaption></figure>\n",
        svg, id);
  }
  return out;
}

namespace {

// A figure of the run inlined under its heading, its ids prefixed (it is an <svg id="...">, so it
// also gets its PNG preview); `missing` when the file holds no <svg>.
std::string inlinedFigure(const std::string& heading, const std::string& svg,
                          const std::string& missing, const std::string& prefix) {
  const size_t start = svg.find("<svg");
  if (start == std::string::npos) return heading + "<p class=\"missing\">" + missing + "</p>\n";
  return heading + "<div class=\"figure\">\n" + prefixIds(svg.substr(start), prefix) + "</div>\n";
}

}  // namespace

std::string deployedSection(const std::string& deployedSvg) {
  return inlinedFigure(
      "<h2 id=\"deployed-grid\">Deployed grid: deviation from the design surface</h2>\n",
      deployedSvg, "No deployed grid: the simulation did not run (deployed.svg).", "deployed-");
}

std::string elevationsSection(const std::string& elevationsSvg) {
  return inlinedFigure("<h2 id=\"elevations-and-sections\">Elevations and sections</h2>\n",
                       elevationsSvg, "No elevations: the simulation did not run (elevations.svg).",
                       "elevations-");
}

std::string deploymentFigure(const std::string& deploymentSvg) {
  return inlinedFigure("", deploymentSvg, "No deployment chart (deployment.svg).", "deployment-");
}

std::string generalisedSection(const nlohmann::json& report) {
  const auto entries = report.find("generalised_patches");
  if (entries == report.end() || !entries->is_array() || entries->empty()) return "";
  const auto number = [](const nlohmann::json& j, const char* key, const char* format) {
    const auto v = j.find(key);
    return v != j.end() && v->is_number() ? fmt::format(fmt::runtime(format), v->get<double>())
                                          : std::string("&ndash;");
  };
  std::string out =
      "<h2 id=\"generalised\">Generalised patches (Chapter 4)</h2>\n<p>Patches on the cut-offs "
      "the quads leave, numbered after them in the cut files (P). E_grid = E_effort (scaled) "
      "&minus; &lambda; E_shape; &epsilon;_geo: distance-field crossings against the traced ones, "
      "in % of an edge; RMSE: each patch deployed alone on its anchors.</p>\n<table "
      "class=\"list\"><tr><th>patch</th><th>P</th><th>area m&sup2;</th><th>members</th>"
      "<th>crossings</th><th>E_shape</th><th>E_grid</th><th>&epsilon;_geo %</th><th>min angle "
      "&deg;</th><th>planar residual m</th><th>RMSE m</th><th>why not</th></tr>\n";
  for (const auto& g : *entries) {
    const auto simulation = g.value("simulation", nlohmann::json::object());
    out +=
        "<tr><td>" + escapeXml(g.value("id", "")) + "</td><td>" +
        (g.contains("patch_id") ? fmt::format("P{}", g["patch_id"].get<int>()) : "") + "</td><td>" +
        number(g, "area_m2", "{:.1f}") + "</td><td>" + number(g, "members", "{:.0f}") +
        "</td><td>" + number(g, "crossings", "{:.0f}") + "</td><td>" +
        number(g, "e_shape", "{:.2f}") + "</td><td>" + number(g, "e_grid", "{:.3g}") + "</td><td>" +
        number(g, "eps_geo_percent", "{:.1f}") + "</td><td>" +
        number(g, "min_crossing_angle_deg", "{:.1f}") + "</td><td>" +
        number(g.value("planarisation", nlohmann::json::object()), "length_residual_m", "{:.1e}") +
        "</td><td>" + number(simulation, "rmse_m", "{:.4f}") + "</td><td>" +
        escapeXml(g.value("reason", "")) + "</td></tr>\n";
  }
  out += "</table>\n";
  const auto joined = report.value("simulation", nlohmann::json::object())
                          .value("joined", nlohmann::json::object())
                          .value("generalised_patches", nlohmann::json::object());
  if (!joined.empty())
    out += fmt::format(
        "<p>In the joined structure: {} member ends bolted to a quad's boundary lamella, {} in "
        "that lamella's own layer held by brackets (anchored in the simulation).</p>\n",
        joined.value("ring_beam_bolts", 0), joined.value("patch_side_ends_anchored_same_layer", 0));
  return out;
}

}  // namespace egg::pipeline::report_sections
