#include "pipeline/report_html.hpp"

#include "pipeline/deviation_plan.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace egg::pipeline {
namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size()))
    ++n;
  return n;
}

// A report as the pipeline writes it (the keys reportHtml reads), with a warning that must be
// escaped and four lamellas of known stress ratios.
nlohmann::json sampleReport() {
  return nlohmann::json::parse(R"({
    "scene": {"name": "court <test>", "path": "/scenes/court.json"},
    "stages": {"surface": {"ran": true, "seconds": 0.5}, "patching": {"ran": true, "seconds": 2.0},
               "design": {"ran": true, "seconds": 1.0}, "propagation": {"ran": false, "seconds": 0.0,
               "skipped_reason": "one patch: no boundary to continue members across"},
               "grid": {"ran": true, "seconds": 0.25}, "simulation": {"ran": true, "seconds": 4.0},
               "fabrication": {"ran": true, "seconds": 0.75}},
    "timings": {"total_s": 8.5},
    "warnings": ["surface: a <b>bold</b> claim & more"],
    "failures": ["fabrication: 1 lamellas cannot be spliced"],
    "patches": [{"id": 0, "feasible": true, "area_m2": 12.5, "members_u": 7, "members_v": 9, "eta_u": 1.0001,
                 "eta_v": 1.0002, "max_notch_m": 0.012,
                 "cladding": {"slope_bounds": [0.1, 10.0], "infinite_slope_factor": 10000.0,
                              "u": {"start_side_m": 4.0, "end_side_m": 5.0, "points_x1": [0, 0.5, 1], "points_x2": [0, 0.3, 1],
                                    "members_x1": [0, 0.5, 1], "members_x2": [0, 0.3, 1], "bijective": true},
                              "v": {"start_side_m": 3.0, "end_side_m": 3.5, "points_x1": [0, 1], "points_x2": [0, 1],
                                    "members_x1": [0, 1], "members_x2": [0, 1], "bijective": true}}},
                {"id": 1, "feasible": false, "reason": "eta"}],
    "simulation": {"ran": true, "converged": true, "rmse_m": 0.021, "max_error_m": 0.093, "nrmse": 0.004,
                   "rmse_no_notches_m": 0.05, "iterations": 321,
                   "patches": [{"patch": 0, "converged": true, "iterations": 321, "rmse_m": 0.021, "max_error_m": 0.093,
                                "seconds": 4.0,
                                "history": [{"seconds": 0.1, "iteration": 0, "load_step": 0, "rmse_m": 0.001, "max_error_m": 0.004},
                                            {"seconds": 3.9, "iteration": 321, "load_step": 2, "rmse_m": 0.021, "max_error_m": 0.093}]}],
                   "joined": {"ran": true, "converged": true,
                              "history": [{"seconds": 0.2, "iteration": 0, "load_step": 0, "rmse_m": 0.02, "max_error_m": 0.09},
                                          {"seconds": 2.0, "iteration": 12, "load_step": 0, "rmse_m": 0.025, "max_error_m": 0.1}]}},
    "fabrication": {"ran": true, "material": "poplar_plywood", "lamellae": 4, "total_length_m": 40.0, "mass_kg": 215.0,
                    "sheets": 3, "yield": 0.61, "bolts": 63, "notches": 40, "splices": 2, "supports": 6,
                    "max_stress_ratio": 1.25, "max_stress_lamella": "P0-V3", "max_bending_stress_pa": 5.0e7,
                    "max_torsion_stress_pa": 2.0e6, "warnings": ["lamella P0-V3 is stressed to 1.25"],
                    "unspliceable_lamellae": ["lamella P0-U2 (45000 mm) cannot be spliced between 0 and 13480 mm"],
                    "lamella_stress": [{"id": "P0-U1", "ratio": 0.05}, {"id": "P0-U2", "ratio": 0.07},
                                       {"id": "P0-V1", "ratio": 0.31}, {"id": "P0-V3", "ratio": 1.25}]}
  })");
}

const std::string kPlan =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
    "width=\"400\" height=\"300\" "
    "viewBox=\"0 0 400 300\"><rect id=\"patch-0\" x=\"10\" y=\"10\" width=\"380\" height=\"280\" "
    "fill=\"#abd2e4\"/>"
    "<text x=\"200\" y=\"150\">P0</text></svg>\n";

const std::string kBom =
    "item,id,count,length_mm,width_mm,thickness_mm,area_m2,volume_m3,mass_kg,note\n"
    "lamella,P0-U1,1,9000.00,250.00,40.00,,0.09,38.7,poplar_plywood; 2 holes; 7 slots; 1 segments; "
    "stress ratio 0.050\n"
    "splice,,2,,,,,,,butt joints clear of holes by 250.0 mm\n"
    "bolt,,63,,,,,,,diameter 16.0 mm; one per connection, merged on shared lamellas\n";

TEST(ReportHtml, SelfContainedPageWithEverySection) {
  const std::string html = reportHtml(sampleReport(), {.planSvg = kPlan, .bomCsv = kBom});
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  // Nothing fetched from anywhere: no script, link, image, import or external url.
  for (const char* external :
       {"<script", "<link", "<img", "<iframe", "@import", "url(", "src=", "href="}) {
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  }
  // The only "http" is the SVG namespace name of the inlined plan.
  EXPECT_EQ(count(html, "http"), 1u);
  EXPECT_EQ(count(html, "http://www.w3.org/2000/svg"), 1u);
  // The plan inline, without its XML declaration, scaled to the page.
  EXPECT_EQ(html.find("<?xml"), std::string::npos);
  EXPECT_NE(html.find("<svg class=\"plan\" style=\"max-width:100%;height:auto\" xmlns="),
            std::string::npos);
  EXPECT_NE(html.find("id=\"patch-0\""), std::string::npos);
  // The cladding functions of the traced patch only, and both error-against-time charts.
  EXPECT_NE(html.find("<svg id=\"cladding-patch-0\""), std::string::npos);
  EXPECT_EQ(html.find("cladding-patch-1"), std::string::npos);
  EXPECT_LT(html.find("<h2 id=\"cladding\">"), html.find("<h2 id=\"simulation\">"));
  EXPECT_LT(html.find("<h2 id=\"simulation\">"), html.find("<h2 id=\"error-time\">"));
  EXPECT_NE(html.find("<svg id=\"error-time-patches\""), std::string::npos);
  EXPECT_NE(html.find("<svg id=\"error-time-joined\""), std::string::npos);
  // Report text is escaped.
  EXPECT_NE(html.find("<title>court &lt;test&gt; &ndash; eggshell report</title>"),
            std::string::npos);
  EXPECT_NE(html.find("a &lt;b&gt;bold&lt;/b&gt; claim &amp; more"), std::string::npos);
  EXPECT_EQ(html.find("<b>bold"), std::string::npos);
  // Every stage, with the reason of the one that did not run; the failure; the unspliceable
  // lamella.
  for (const char* stage :
       {"surface", "patching", "design", "propagation", "grid", "simulation", "fabrication"}) {
    EXPECT_NE(html.find(std::string("<tr><td>") + stage + "</td>"), std::string::npos) << stage;
  }
  EXPECT_NE(html.find("one patch: no boundary to continue members across"), std::string::npos);
  EXPECT_NE(html.find("fabrication: 1 lamellas cannot be spliced"), std::string::npos);
  EXPECT_NE(html.find("lamella P0-U2 (45000 mm) cannot be spliced"), std::string::npos);
  // Stage-time bars scaled to the largest (simulation, 4 s = 520 px).
  EXPECT_NE(html.find("width=\"520.00\" height=\"13.0\" fill=\"#4a7fb5\" data-value=\"4\""),
            std::string::npos);
  EXPECT_NE(html.find("width=\"260.00\" height=\"13.0\" fill=\"#4a7fb5\" data-value=\"2\""),
            std::string::npos);
  // Stress histogram in bins of 0.1 up to 1.25: 13 bins; 0.05 and 0.07 in the first, 0.31 in the
  // fourth, 1.25 in the last.
  const size_t histogram = html.find("id=\"stress-histogram\"");
  ASSERT_NE(histogram, std::string::npos);
  const std::string bins = html.substr(histogram, html.find("</svg>", histogram) - histogram);
  EXPECT_EQ(count(bins, "<rect"), 13u);
  EXPECT_NE(bins.find(">0.0 - 0.1</text><rect x=\"170.0\" y=\"3.0\" width=\"520.00\" "
                      "height=\"13.0\" fill=\"#4a7fb5\" data-value=\"2\""),
            std::string::npos)
      << bins;
  EXPECT_NE(bins.find(">0.3 - 0.4</text><rect x=\"170.0\" y=\"57.0\" width=\"260.00\""),
            std::string::npos)
      << bins;
  EXPECT_NE(bins.find(">1.2 - 1.3</text><rect x=\"170.0\" y=\"219.0\" width=\"260.00\""),
            std::string::npos)
      << bins;
  EXPECT_EQ(count(bins, "data-value=\"0\""), 10u);
  // The highest lamellas with the strength marked at a ratio of 1.
  const size_t top = html.find("id=\"stress-top\"");
  ASSERT_NE(top, std::string::npos);
  EXPECT_LT(html.find(">P0-V3</text>", top), html.find(">P0-V1</text>", top));
  EXPECT_NE(html.find("stroke=\"#c62828\" stroke-dasharray=\"4 3\"", top), std::string::npos);
  // The BOM: summary rows up front, the note with its comma in one cell, lamella rows in the fold.
  EXPECT_NE(html.find("<td>diameter 16.0 mm; one per connection, merged on shared lamellas</td>"),
            std::string::npos);
  EXPECT_LT(html.find("<td>splice</td>"), html.find("<details><summary>Every lamella"));
  EXPECT_GT(html.find("<td>P0-U1</td>"), html.find("<details><summary>Every lamella"));
  EXPECT_NE(html.find("(3 rows in all)"), std::string::npos);
}

TEST(ReportHtml, GeneralisedPatchesGetTheirTableOnlyWhenTheRunHasThem) {
  nlohmann::json report = sampleReport();
  EXPECT_EQ(reportHtml(report, {}).find("id=\"generalised\""), std::string::npos);
  report["generalised_patches"] = nlohmann::json::parse(R"([
    {"id": "G0", "patch_id": 4, "kind": "generalised", "area_m2": 127.06, "members": 15,
     "crossings": 15, "e_shape": 1.0, "e_grid": -2.1, "eps_geo_percent": 23.2,
     "min_crossing_angle_deg": 59.04, "planarisation": {"length_residual_m": 1.8e-15},
     "simulation": {"rmse_m": 0.02164}},
    {"id": "G1", "patch_id": 5, "kind": "generalised", "area_m2": 1.8, "feasible": false,
     "reason": "left as a cut-off: <1.8 m^2> is small"}])");
  report["simulation"]["joined"]["generalised_patches"] = {
      {"ring_beam_bolts", 37}, {"patch_side_ends_anchored_same_layer", 41}};
  const std::string html = reportHtml(report, {});
  EXPECT_NE(html.find("<h2 id=\"generalised\">"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>G0</td><td>P4</td><td>127.1</td><td>15</td><td>15</td><td>1.00</td>"
                      "<td>-2.1</td><td>23.2</td><td>59.0</td><td>1.8e-15</td><td>0.0216</td>"
                      "<td></td></tr>"),
            std::string::npos)
      << html.substr(html.find("id=\"generalised\""), 2000);
  // A piece without a grid: dashes and its reason, escaped.
  EXPECT_NE(html.find("<td>&ndash;</td><td>left as a cut-off: &lt;1.8 m^2&gt; is small</td>"),
            std::string::npos);
  EXPECT_NE(html.find("37 member ends bolted to a quad's boundary lamella, 41 in that lamella's "
                      "own layer held by brackets"),
            std::string::npos);
}

TEST(ReportHtml, MissingPartsSayWhy) {
  nlohmann::json report = sampleReport();
  report["simulation"] = {{"ran", false},
                          {"skipped_reason", "the scene disables it (simulation.enabled = false)"}};
  report["fabrication"] = {{"ran", false}, {"skipped_reason", "no requested output needs it"}};
  const std::string html = reportHtml(report, {});
  EXPECT_NE(html.find("No plan: the scene's outputs do not contain \"plan\""), std::string::npos);
  EXPECT_NE(html.find("Not run: the scene disables it (simulation.enabled = false)"),
            std::string::npos);
  EXPECT_NE(html.find("Not run: no requested output needs it"), std::string::npos);
  EXPECT_NE(html.find("No bom.csv"), std::string::npos);
  EXPECT_NE(html.find("No planar grids: the scene's outputs do not contain \"previews\""),
            std::string::npos);
  EXPECT_EQ(html.find("id=\"stress-histogram\""), std::string::npos);
  EXPECT_NE(html.find("No error history: the simulation did not run."), std::string::npos);
  report["patches"] = nlohmann::json::array();
  EXPECT_NE(reportHtml(report, {}).find("No cladding functions: no patch grid was traced."),
            std::string::npos);
}

// Output of a command (stdout) and its exit status.
std::pair<std::string, int> run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {out, -1};
  std::array<char, 4096> buffer{};
  size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  return {out, pclose(pipe)};
}

// Width and height from a PNG's IHDR chunk (bytes 16..23, big endian); zeros when not a PNG.
std::pair<int, int> pngSize(const std::string& png) {
  if (png.size() < 24 || png.compare(1, 3, "PNG") != 0) return {0, 0};
  auto be = [&](size_t at) {
    return (static_cast<unsigned char>(png[at]) << 24) |
           (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  return {static_cast<int>(be(16)), static_cast<int>(be(20))};
}

// writeReportHtml writes a PNG preview of every figure of the page (the plan and each chart), at
// the widths it promises, and names them relative to the run folder for report.json.
TEST(ReportHtml, WritesAPngPreviewOfEveryFigure) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_report_previews_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "plan.svg") << kPlan;
  std::ofstream(dir / "bom.csv") << kBom;
  // Patch 0's flat grid as writePlanarSvg writes it.
  std::filesystem::create_directories(dir / "patch_000");
  std::ofstream(dir / "patch_000" / "planar.svg")
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"200\" viewBox=\"0 0 200 "
         "200\">\n"
         "<line x1=\"10\" y1=\"10\" x2=\"190\" y2=\"190\" stroke=\"#1f77b4\" "
         "stroke-width=\"3\"/>\n</svg>\n";
  // The deployed grid as the pipeline writes it (deviation_plan.hpp): one rod rising off the
  // surface.
  DeployedRod rod;
  for (int i = 0; i < 5; ++i)
    rod.points.emplace_back(i, 0.3 * i, 0.0), rod.distanceM.push_back(0.05 * i);
  std::ofstream(dir / "deployed.svg") << deployedPlanSvg({rod}, "test rod");
  const std::vector<std::string> previews = writeReportHtml(dir, sampleReport());
  const std::vector<std::string> expected = {"preview/plan.png",
                                             "preview/stage_time_chart.png",
                                             "preview/patch_grid_0.png",
                                             "preview/cladding_patch_0.png",
                                             "preview/simulation_error_chart.png",
                                             "preview/error_time_patches.png",
                                             "preview/error_time_joined.png",
                                             "preview/deployed.png",
                                             "preview/stress_histogram.png",
                                             "preview/stress_top.png"};
  std::ifstream page(dir / "report.html");
  std::ostringstream pageText;
  pageText << page.rdbuf();
  EXPECT_NE(pageText.str().find("<h2 id=\"patch-grids\">"), std::string::npos);
  EXPECT_NE(pageText.str().find("<h2 id=\"deployed-grid\">"), std::string::npos);
  EXPECT_NE(pageText.str().find("<h2 id=\"cladding\">"), std::string::npos);
  EXPECT_NE(pageText.str().find("<h2 id=\"error-time\">"), std::string::npos);
  EXPECT_NE(pageText.str().find("<svg id=\"deployed\""), std::string::npos);
  EXPECT_NE(
      pageText.str().find("<svg id=\"patch-grid-0\" style=\"width:280px;height:auto\" xmlns="),
      std::string::npos);
  EXPECT_EQ(previews, expected);
  for (const auto& file : previews) {
    std::ifstream in(dir / file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    const auto [width, height] = pngSize(bytes.str());
    EXPECT_EQ(width, file == "preview/plan.png" ? kPlanPreviewPx : kChartPreviewPx) << file;
    EXPECT_GT(height, 0) << file;
  }
  // The plan is 400 x 300: 1200 px wide keeps its aspect.
  std::ifstream plan(dir / "preview/plan.png", std::ios::binary);
  std::ostringstream planBytes;
  planBytes << plan.rdbuf();
  EXPECT_EQ(pngSize(planBytes.str()), std::make_pair(kPlanPreviewPx, 900));
  std::filesystem::remove_all(dir);
}

// A figure librsvg cannot read loses its preview and says so; the page and the other previews
// are written (the run is not thrown away for a picture).
TEST(ReportHtml, AFigureThatCannotBeDrawnLosesOnlyItsPreview) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_report_badfig_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "plan.svg") << kPlan;
  std::ofstream(dir / "deployed.svg")
      << R"(<svg id="deployed" xmlns="http://www.w3.org/2000/svg" width="10" height="10">)"
      << "<g><rect width=\"5\" height=\"5\"></g></svg>\n";  // </g> closes a <rect>
  std::vector<std::string> problems;
  const auto previews = writeReportHtml(dir, sampleReport(), &problems);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].rfind("preview/deployed.png not drawn: ", 0), 0u) << problems[0];
  EXPECT_EQ(std::count(previews.begin(), previews.end(), "preview/deployed.png"), 0);
  EXPECT_EQ(std::count(previews.begin(), previews.end(), "preview/plan.png"), 1);
  EXPECT_TRUE(std::filesystem::exists(dir / "report.html"));
  EXPECT_FALSE(std::filesystem::exists(dir / "preview" / "deployed.png"));
  std::filesystem::remove_all(dir);
}

TEST(ReportHtml, FiguresStandAloneWithTheSvgNamespace) {
  const std::string html = reportHtml(sampleReport(), {.planSvg = kPlan, .bomCsv = kBom});
  const auto figures = reportFigures(html, kPlan);
  // plan, stage times, the cladding functions of patch 0 (patch 1 has none), simulation error,
  // error against time patch by patch and joined, stress histogram, highest stresses.
  ASSERT_EQ(figures.size(), 8u);
  EXPECT_EQ(figures[0].first, "plan");
  EXPECT_EQ(figures[0].second.rfind("<svg xmlns=", 0), 0u)
      << "plan.svg without its XML declaration";
  for (const auto& [id, svg] : figures) {
    EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos) << id;
    EXPECT_EQ(svg.substr(svg.size() - 6), "</svg>") << id;
  }
  EXPECT_EQ(figures[1].first, "stage-time-chart");
}

// A real browser opens the page offline: headless Chromium parses it (the inline SVG charts become
// SVG elements in its DOM) and renders it to a screenshot with far more ink than an empty page of
// the same size rendered in the same run.
// plan.svg, curvature.svg, deployed.svg and elevations.svg each have a "scale-bar", and the two
// sheets both a "patch-0": inlined on one page, every id stays unique and every url(#...) still
// finds its pattern.
TEST(ReportHtml, InlinedSheetsKeepTheirIdsUniqueAndTheirPatternsResolved) {
  const std::string sheet =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"40\" height=\"30\"><defs><pattern "
      "id=\"hatch\" width=\"4\" height=\"4\"/></defs><rect id=\"patch-0\" "
      "fill=\"url(#hatch)\" width=\"40\" height=\"30\"/><rect id=\"scale-bar\" width=\"8\" "
      "height=\"2\"/></svg>\n";
  const std::string figure =
      "<svg id=\"deployed\" xmlns=\"http://www.w3.org/2000/svg\"><rect id=\"scale-bar\"/></svg>";
  ReportFiles files;
  files.planSvg = sheet;
  files.curvatureSvg = sheet;
  files.deployedSvg = figure;
  files.elevationsSvg =
      "<svg id=\"elevations\" xmlns=\"http://www.w3.org/2000/svg\"><rect id=\"scale-bar\"/></svg>";
  const std::string html = reportHtml(sampleReport(), files);
  std::map<std::string, int> ids;
  for (size_t at = html.find(" id=\""); at != std::string::npos; at = html.find(" id=\"", at + 1)) {
    const size_t start = at + 5;
    ++ids[html.substr(start, html.find('"', start) - start)];
  }
  for (const auto& [id, n] : ids)
    EXPECT_EQ(n, 1) << "id \"" << id << "\" appears " << n << " times";
  for (const char* id :
       {"patch-0", "curvature-patch-0", "scale-bar", "curvature-scale-bar", "deployed-scale-bar",
        "elevations-scale-bar", "deployed", "elevations", "curvature", "hatch", "curvature-hatch"})
    EXPECT_EQ(ids[id], 1) << id;
  EXPECT_NE(html.find("url(#curvature-hatch)"), std::string::npos);
  EXPECT_NE(html.find("url(#hatch)"), std::string::npos);
}

TEST(ReportHtml, HeadlessChromiumRendersThePage) {
  if (run("command -v chromium >/dev/null 2>&1").second != 0) {
    GTEST_SKIP() << "chromium is not installed (Debian package chromium, scripts/install-deps.sh): "
                    "the page is not checked in a browser";
  }
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_report_html_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "plan.svg") << kPlan;
  std::ofstream(dir / "bom.csv") << kBom;
  writeReportHtml(dir, sampleReport());
  std::ofstream(dir / "empty.html")
      << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"></head><body></body></html>\n";
  // --no-sandbox: tests may run as root in a container; no network is needed or allowed to matter.
  const std::string chromium =
      "chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-extensions "
      "--user-data-dir=" +
      (dir / "profile").string() + " ";
  const auto [dom, domStatus] =
      run(chromium + "--dump-dom file://" + (dir / "report.html").string() + " 2>/dev/null");
  ASSERT_EQ(domStatus, 0) << dom;
  for (const char* section : {"stage-times", "plan", "patches", "patch-grids", "cladding",
                              "simulation", "error-time", "deployed-grid", "fabrication", "bom"}) {
    EXPECT_NE(dom.find(std::string("<h2 id=\"") + section + "\">"), std::string::npos) << section;
  }
  EXPECT_GE(count(dom, "<svg"), 8u) << "plan, stage times, cladding, simulation error, error "
                                       "against time (2), stress histogram, highest stresses";
  EXPECT_NE(dom.find("id=\"patch-0-u-curve\""), std::string::npos);
  EXPECT_NE(dom.find("id=\"error-time-joined-rmse-0\""), std::string::npos);
  EXPECT_NE(dom.find("id=\"patch-0\""), std::string::npos);
  for (const char* page : {"report", "empty"}) {
    const auto png = dir / (std::string(page) + ".png");
    const auto [out, status] =
        run(chromium + "--window-size=1280,2400 --hide-scrollbars --screenshot=" + png.string() +
            " file://" + (dir / (std::string(page) + ".html")).string() + " 2>&1");
    ASSERT_EQ(status, 0) << out;
    ASSERT_TRUE(std::filesystem::exists(png)) << out;
  }
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::string report = slurp(dir / "report.png"), empty = slurp(dir / "empty.png");
  EXPECT_EQ(pngSize(report), std::make_pair(1280, 2400));
  EXPECT_EQ(pngSize(empty), std::make_pair(1280, 2400));
  // A blank page compresses to almost nothing; text, tables and charts do not.
  EXPECT_GT(report.size(), 5 * empty.size()) << report.size() << " vs " << empty.size() << " bytes";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace egg::pipeline
