// deployed.json and report.html's 3D view (issue 39): the data keeps ids, millimetres and the
// colour scale of deployed.svg; the page carries three.js and draws in a real browser.
#include "pipeline/deployed_view.hpp"
#include "pipeline/report_html.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// Two patches of straight lamellas across a 4 x 2 m plane, 1 to 3 cm off it.
std::vector<DeployedRod> twoPatches() {
  std::vector<DeployedRod> rods;
  for (int patch = 0; patch < 2; ++patch)
    for (int r = 0; r < 3; ++r) {
      DeployedRod rod;
      rod.patch = patch + 5, rod.rod = r;
      for (int i = 0; i <= 4; ++i) {
        rod.points.emplace_back(0.5 * i + 2.0 * patch, 0.5 + 0.5 * r, 0.01 * (1 + r) + 1e-5);
        rod.distanceM.push_back(0.01 * (1 + r));
      }
      rods.push_back(rod);
    }
  return rods;
}

TEST(DeployedView, TheDataKeepsIdsMillimetresAndTheColourScale) {
  const TriMesh plane = samples::generateSample("plane", {}, 0.5);
  const json view = deployedViewJson(twoPatches(), plane, "caption");
  ASSERT_EQ(view["rods"].size(), 6u);
  EXPECT_EQ(view["rods"][4]["patch"], 6);
  EXPECT_EQ(view["rods"][4]["rod"], 1);
  EXPECT_EQ(view["rods"][4]["points"].size(), 15u);
  EXPECT_DOUBLE_EQ(view["rods"][4]["points"][2].get<double>(), 0.02);  // 0.02001 to the mm
  EXPECT_DOUBLE_EQ(view["rods"][5]["distance_m"][0].get<double>(), 0.03);
  EXPECT_DOUBLE_EQ(view["scale_m"].get<double>(), 0.05);  // deviationScale(0.03): 5 cm
  EXPECT_EQ(view["surface"]["triangles"].size(), 3u * plane.n_faces());
  EXPECT_EQ(view["surface"]["positions"].size(), 3u * plane.n_vertices());
  // A surface above the bound is left out, and the view says so.
  const json without = deployedViewJson(twoPatches(), plane, "caption", 10);
  EXPECT_FALSE(without.contains("surface"));
  EXPECT_NE(without["surface_left_out"].get<std::string>().find("more than the view carries (10)"),
            std::string::npos);
}

TEST(DeployedView, TheSectionCarriesItsScriptAndCannotBeEndedByTheData) {
  const std::string section = deployedViewSection(R"({"caption": "</script><b>", "rods": []})");
  EXPECT_NE(section.find("<\\/script><b>"), std::string::npos);
  EXPECT_EQ(section.find("</script><b>"), std::string::npos);
  EXPECT_GT(reportViewerScript().size(), 100000u) << "three.js is bundled";
  EXPECT_EQ(reportViewerScript().find("</script"), std::string::npos);
  EXPECT_NE(deployedViewSection("").find("No 3D view"), std::string::npos);
}

// The page's script counts the canvas pixels that are not background after its first frame
// (readPixels) and leaves the count on the view's element; Chromium's DOM dump shows it.
TEST(DeployedView, HeadlessChromiumDrawsTheViewOfAReport) {
  if (!egg::test::haveTool("chromium"))
    GTEST_SKIP() << "chromium is not installed (Debian package chromium, scripts/install-deps.sh)";
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_deployed_view_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const TriMesh plane = samples::generateSample("plane", {}, 0.5);
  std::ofstream(dir / "deployed.json") << deployedViewJson(twoPatches(), plane, "test").dump();
  writeReportHtml(dir, json{{"scene", {{"name", "view"}}}});
  const std::string chromium =
      "chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--no-first-run --disable-extensions --virtual-time-budget=10000 --user-data-dir=" +
      (dir / "profile").string() + " ";
  const auto [status, dom] =
      egg::test::runTool(chromium + "--dump-dom file://" + (dir / "report.html").string());
  ASSERT_EQ(status, 0) << dom;
  const size_t at = dom.find("id=\"egg-view\"");
  ASSERT_NE(at, std::string::npos) << dom.substr(0, 2000);
  const std::string tag = dom.substr(at, dom.find('>', at) - at);
  const auto attribute = [&](const std::string& name) {
    const size_t start = tag.find(name + "=\"");
    return start == std::string::npos ? -1.0 : std::stod(tag.substr(start + name.size() + 2));
  };
  const double ink = attribute("data-ink"), pixels = attribute("data-pixels");
  ASSERT_GT(pixels, 0.0) << tag << " (the script did not run, or WebGL failed)";
  // The surface and its lamellas cover a part of the frame, not none and not all of it.
  EXPECT_GT(ink / pixels, 0.03) << tag;
  EXPECT_LT(ink / pixels, 0.9) << tag;
  EXPECT_NE(dom.find("<input type=\"checkbox\""), std::string::npos) << "patch toggles";
  EXPECT_NE(dom.find("P6"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace egg::pipeline
