#include "patching/site_plan.hpp"

#include "core/errors.hpp"
#include "tests/support/bump_layout.hpp"
#include "tests/support/svg_text.hpp"
#include "tests/support/tool_run.hpp"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <sstream>

namespace egg::patching {
namespace {

namespace fs = std::filesystem;
namespace svgtext = egg::test::svg;

// Every data-box="x0 y0 x1 y1" of the sheet.
struct LabelBox {
  double x0, y0, x1, y1;
};
std::vector<LabelBox> labelBoxes(const std::string& svg) {
  std::vector<LabelBox> boxes;
  const std::string key = "data-box=\"";
  for (size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1)) {
    std::istringstream in(svg.substr(at + key.size(), 80));
    LabelBox b{};
    in >> b.x0 >> b.y0 >> b.x1 >> b.y1;
    boxes.push_back(b);
  }
  return boxes;
}

double rootNumber(const std::string& svg, const std::string& name) {
  const size_t at = svg.find(name + "=\"");
  return at == std::string::npos ? std::nan("") : std::stod(svg.substr(at + name.size() + 2));
}

// The bump's 2 x 2 layout with one infeasible patch, areas, members along the patches' diagonals
// and a ring of `supports` supports round the layout (many: they crowd each other's labels).
SitePlanDrawing bumpPlan(const testing::BumpLayout& scene, int supports) {
  SitePlanDrawing d;
  d.surface = &scene.surface;
  d.layout = &scene.layout;
  d.patchProblems = {"", "", "", "eta_u = 1.004 > eta_max = 1.0015"};
  d.patchAreasM2 = {6.5, 6.5, 34170.4, 0.0};  // 34170.4: a plain number, never 3.417e+04
  d.coverage = &scene.coverage;
  for (int k = 0; k < 5; ++k) {
    const double t = -2.5 + 1.25 * k;
    d.members.push_back({0, true, k == 0, {{-2.5, t, 0.1}, {0.0, t, 0.5}, {2.5, t, 0.1}}});
    d.members.push_back({0, false, false, {{t, -2.5, 0.1}, {t, 2.5, 0.1}}});
  }
  for (int k = 0; k < supports; ++k) {
    const double a = 2 * M_PI * k / supports;
    d.supports.push_back(
        {fmt::format("S{:03d}", k + 1), {2.5 * std::cos(a), 2.5 * std::sin(a), 0.0}, k % 7 == 3});
  }
  d.sections = {{"A", true, 0.0}, {"B", false, 0.0}};
  d.title = "bump <2 x 2> & plan";
  return d;
}

TEST(SitePlan, TwoByTwoOnABumpShowsIdsAreasHatchesDimensionsAndSections) {
  const testing::BumpLayout scene;
  const std::string svg = sitePlanSvg(bumpPlan(scene, 8));
  // Patch ids with their surface areas in plain numbers; the infeasible one names its reason.
  EXPECT_EQ(svgtext::count(svg, "<polygon id=\"patch-"), 4);
  EXPECT_NE(svg.find(">P0</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">6.5 m²<"), std::string::npos) << "areas under 10 m² keep a decimal";
  EXPECT_NE(svg.find(">34\u202f170 m²<"), std::string::npos);
  EXPECT_EQ(svg.find("e+04"), std::string::npos);
  EXPECT_NE(svg.find(">P3 [1]</tspan>"), std::string::npos);
  EXPECT_NE(svg.find("[1] eta_u = 1.004 &gt; eta_max = 1.0015"), std::string::npos);
  // Infeasible and cut-off: different patterns, different colours.
  EXPECT_NE(svgtext::attribute(svg, "infeasible-3", "fill").find("sp-hatch-infeasible"),
            std::string::npos);
  EXPECT_NE(svg.find("fill=\"url(#sp-hatch-cutoff)\""), std::string::npos);
  EXPECT_EQ(svgtext::attribute(svg, "patch-3", "stroke"), "#c62828");
  EXPECT_EQ(svgtext::attribute(svg, "patch-0", "stroke"), "#000");
  EXPECT_EQ(svgtext::count(svg, "<g id=\"cutoff-"), 1);
  // Members in two families, a heavier layer for patch sides; supports as blocks and brackets.
  EXPECT_EQ(svgtext::count(svg, "class=\"members-u\""), 1);
  EXPECT_EQ(svgtext::count(svg, "class=\"members-u boundary\""), 1);
  EXPECT_EQ(svgtext::count(svg, "class=\"members-v\""), 1);
  EXPECT_EQ(svgtext::count(svg, "class=\"block\""), 7);
  EXPECT_EQ(svgtext::count(svg, "class=\"bracket\""), 1);
  // The overall dimensions are the surface's 8 x 8 m;
  EXPECT_EQ(svgtext::textOf(svg, "dim-x-label"), "8.00 m");
  EXPECT_EQ(svgtext::textOf(svg, "dim-y-label"), "8.00 m");
  const size_t crown = svg.find("id=\"crown-label\"");
  ASSERT_NE(crown, std::string::npos);
  // The crown is the mesh's highest vertex: the bump's 2 m top, less the meshing's sampling.
  const double top = boundingBox(scene.surface).max.z();
  EXPECT_NEAR(top, 2.0, 0.02);
  EXPECT_EQ(svg.substr(svg.find("<tspan", crown), 41),
            fmt::format("<tspan font-weight=\"bold\">+{:.2f} m</tspan>", top));
  EXPECT_FALSE(svgtext::element(svg, "section-A").empty());
  EXPECT_FALSE(svgtext::element(svg, "section-B").empty());
  EXPECT_NE(svg.find("bump &lt;2 x 2&gt; &amp; plan"), std::string::npos);

  // It renders (rsvg-convert: install-deps.sh installs librsvg2-bin).
  const fs::path dir = fs::temp_directory_path() / ("egg_site_plan_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "plan.svg") << svg;
  const auto run = egg::test::runTool("rsvg-convert -o '" + (dir / "plan.png").string() + "' '" +
                                      (dir / "plan.svg").string() + "'");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_GT(fs::file_size(dir / "plan.png"), 10000u);
  fs::remove_all(dir);
}

TEST(SitePlan, LabelsNeverOverlapOrLeaveThePageAndTheLeftOutAreCounted) {
  const testing::BumpLayout scene;
  for (int supports : {8, 60, 400}) {
    const std::string svg = sitePlanSvg(bumpPlan(scene, supports));
    const double width = rootNumber(svg, "width"), height = rootNumber(svg, "height");
    const auto boxes = labelBoxes(svg);
    for (size_t i = 0; i < boxes.size(); ++i) {
      EXPECT_GE(boxes[i].x0, 0.0) << supports << " supports, label " << i;
      EXPECT_GE(boxes[i].y0, 0.0) << supports << " supports, label " << i;
      EXPECT_LE(boxes[i].x1, width) << supports << " supports, label " << i;
      EXPECT_LE(boxes[i].y1, height) << supports << " supports, label " << i;
      for (size_t j = 0; j < i; ++j)
        EXPECT_FALSE(boxes[i].x0 < boxes[j].x1 && boxes[j].x0 < boxes[i].x1 &&
                     boxes[i].y0 < boxes[j].y1 && boxes[j].y0 < boxes[i].y1)
            << supports << " supports: labels " << j << " and " << i << " overlap";
    }
    // Every label is drawn or counted: 4 patches, 1 cut-off, the crown, the supports, and the
    // dimension texts (the chains have none: the bump has no holes).
    const int leftOut = static_cast<int>(rootNumber(svg, "data-labels-left-out"));
    EXPECT_EQ(static_cast<int>(boxes.size()) + leftOut, 4 + 1 + 1 + supports + 2) << supports;
    if (supports == 400) {
      EXPECT_GT(leftOut, 100) << "400 supports on a 5 m ring cannot all carry their ids";
      EXPECT_NE(svg.find("labels left out where they would overlap"), std::string::npos);
    }
    // Patch ids go first: they are always placed.
    for (int p = 0; p < 4; ++p)
      EXPECT_FALSE(svgtext::element(svg, "patch-label-" + std::to_string(p)).empty())
          << supports << " supports, patch " << p;
  }
}

TEST(SitePlan, BadInputNamesWhatDoesNotFit) {
  const testing::BumpLayout scene;
  SitePlanDrawing d = bumpPlan(scene, 4);
  d.patchAreasM2.pop_back();
  EXPECT_THROW(sitePlanSvg(d), InvalidInput);
  d = bumpPlan(scene, 4);
  d.members[2].points[1].x() = std::nan("");
  try {
    sitePlanSvg(d);
    FAIL() << "a NaN member point was drawn";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("member 2"), std::string::npos) << e.what();
  }
  d = bumpPlan(scene, 4);
  d.surface = nullptr;
  EXPECT_THROW(sitePlanSvg(d), InvalidInput);
  d = bumpPlan(scene, 4);
  d.widthPx = 50;
  EXPECT_THROW(sitePlanSvg(d), InvalidInput);
  // The surface alone is a plan too.
  SitePlanDrawing alone;
  alone.surface = &scene.surface;
  const std::string svg = sitePlanSvg(alone);
  EXPECT_FALSE(svgtext::element(svg, "outline").empty());
  EXPECT_EQ(svg.find("id=\"patch-"), std::string::npos);
  EXPECT_EQ(svg.find("id=\"generalised-"), std::string::npos);
  // A generalised patch is drawn from the layout mesh's faces: without a layout it is bad input,
  // and a face the mesh does not have is named.
  alone.generalised.push_back({"G0", 4, {0, 1}, 2.0});
  try {
    sitePlanSvg(alone);
    FAIL() << "a generalised patch was drawn without its layout";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("generalised patches need the layout"), std::string::npos)
        << e.what();
  }
  d = bumpPlan(scene, 4);
  d.generalised.push_back({"G7", -1, {0, 1 << 30}, 2.0});
  try {
    sitePlanSvg(d);
    FAIL() << "a face outside the layout mesh was drawn";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("generalised patch G7 lists face"), std::string::npos)
        << e.what();
  }
  d.generalised.back().faces = {0, 1, 2};
  const std::string tinted = sitePlanSvg(d);
  EXPECT_FALSE(svgtext::element(tinted, "generalised-G7").empty());
}

}  // namespace
}  // namespace egg::patching
