#include "patching/curvature_sheet.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/bump_layout.hpp"
#include "tests/support/svg_text.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

namespace egg::patching {
namespace {

namespace fs = std::filesystem;

namespace svgtext = egg::test::svg;

using Scene = testing::BumpLayout;

TEST(CurvatureSheet, TwoByTwoOnABumpRendersWithOutlinesCircleCutOffAndScaleBar) {
  const Scene scene;
  ASSERT_EQ(scene.peaks.size(), 1u);
  ASSERT_EQ(scene.coverage.cutOffs.size(), 1u);
  CurvatureDrawing drawing;
  drawing.surface = &scene.surface;
  drawing.layout = &scene.layout;
  drawing.patchProblems = {"", "", "",
                           "eta_u = 1.004 > eta_max = 1.0015"};  // as if its design had failed
  drawing.peaks = scene.peaks;
  drawing.circles = {injectivityCircle(scene.surface, scene.solver, scene.peaks[0])};
  ASSERT_TRUE(drawing.circles[0].complete);
  drawing.coverage = &scene.coverage;
  drawing.title = "bump <2 x 2> & one circle";

  const fs::path dir = fs::temp_directory_path() / ("egg_plan_svg_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path svgPath = dir / "plan.svg", pngPath = dir / "plan.png";
  writeCurvatureSheet(svgPath, drawing);
  const std::string svg = svgtext::readText(svgPath);

  // It renders (a missing rsvg-convert fails the test: scripts/install-deps.sh installs
  // librsvg2-bin).
  ASSERT_EQ(std::system("command -v rsvg-convert > /dev/null"), 0)
      << "rsvg-convert missing: apt-get install librsvg2-bin";
  const std::string command =
      "rsvg-convert -o '" + pngPath.string() + "' '" + svgPath.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  ASSERT_TRUE(fs::exists(pngPath));
  EXPECT_GT(fs::file_size(pngPath), 10000u);

  // One outline per patch, each with its id as text; the infeasible one says its reason index.
  EXPECT_EQ(svgtext::count(svg, "<polygon id=\"patch-"), 4);
  for (int p = 0; p < 4; ++p) {
    EXPECT_EQ(svgtext::element(svg, "patch-" + std::to_string(p)).rfind("<polygon", 0), 0u) << p;
    EXPECT_EQ(svgtext::element(svg, "patch-label-" + std::to_string(p)).rfind("<text", 0), 0u) << p;
    EXPECT_EQ(svgtext::textOf(svg, "patch-label-" + std::to_string(p)),
              p == 3 ? "3 [1]" : std::to_string(p));
  }
  EXPECT_NE(svgtext::attribute(svg, "patch-3", "class").find("infeasible"), std::string::npos);
  EXPECT_NE(svg.find("[1] eta_u = 1.004 &gt; eta_max = 1.0015"), std::string::npos);
  EXPECT_EQ(svgtext::count(svg, " id=\"circle-"), 1);
  EXPECT_EQ(svgtext::count(svg, " id=\"pmax-"), 1);
  EXPECT_EQ(svgtext::count(svg, " id=\"cutoff-"), 1);
  EXPECT_NE(svg.find("bump &lt;2 x 2&gt; &amp; one circle"), std::string::npos);  // text is escaped

  // The scale: the outline's width in px over the surface's width in m is the page scale, and the
  // scale bar's width in px is its label in m times that scale.
  const std::string outline = svgtext::attribute(svg, "outline", "points");
  ASSERT_FALSE(outline.empty());
  double xmin = 1e300, xmax = -1e300;
  std::stringstream points(outline);
  for (std::string pair; points >> pair;) {
    const double x = std::stod(pair.substr(0, pair.find(',')));
    xmin = std::min(xmin, x), xmax = std::max(xmax, x);
  }
  const BoundingBox box = boundingBox(scene.surface);
  const double scale = (xmax - xmin) / box.size().x();
  const size_t rootAt = svg.find("data-px-per-m=\"");
  ASSERT_NE(rootAt, std::string::npos);
  const double declared = std::stod(svg.substr(rootAt + 15));
  EXPECT_NEAR(scale, declared, 0.2 / box.size().x());  // points are written to 0.1 px
  const std::string barLabel = svgtext::textOf(svg, "scale-label");
  ASSERT_EQ(barLabel.substr(barLabel.size() - 2), " m") << barLabel;
  const double barM = std::stod(barLabel);
  const double barPx = std::stod(svgtext::attribute(svg, "scale-bar", "width"));
  EXPECT_NEAR(barPx, barM * declared, 1e-3);
  EXPECT_NEAR(barPx, barM * scale, 0.2 * barM / box.size().x() + 1e-3);
  // A round length: 1, 2 or 5 times a power of ten, between a tenth and a fifth of the width.
  const double mantissa = barM / std::pow(10.0, std::floor(std::log10(barM)));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
              std::abs(mantissa - 5) < 1e-9)
      << barM;
  EXPECT_LE(barM, 0.2 * box.size().x() + 1e-9);
  EXPECT_GE(barM, 0.08 * box.size().x());
  if (std::getenv("EGG_KEEP_PLAN") == nullptr)
    fs::remove_all(dir);  // EGG_KEEP_PLAN=1 keeps it to look at
}

TEST(CurvatureSheet, SurfaceAloneAndBadInput) {
  const TriMesh surface = samples::generateSample("plane", {{"length", 6}, {"width", 3}}, 0.5);
  CurvatureDrawing drawing;
  EXPECT_THROW(curvatureSheetSvg(drawing), InvalidInput);  // no surface
  drawing.surface = &surface;
  const std::string svg = curvatureSheetSvg(drawing);  // K = 0 everywhere: still a plan
  EXPECT_NE(svg.find("id=\"outline\""), std::string::npos);
  EXPECT_EQ(svg.find("id=\"patch-"), std::string::npos);
  drawing.gaussian = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(curvatureSheetSvg(drawing), InvalidInput);  // one value per vertex
  drawing.gaussian.resize(0);
  drawing.options.widthPx = 10;
  EXPECT_THROW(curvatureSheetSvg(drawing), InvalidInput);
}

}  // namespace
}  // namespace egg::patching

namespace egg::patching {
namespace {

// The Great Court roof at its scene edge length (1 m): its K peaks, their circles (open where they
// run into the Reading Room or off the roof), and the plan of the surface alone.
TEST(CurvatureSheet, SlowGreatCourtPeaksCirclesAndPlan) {
  const TriMesh surface = samples::generateSample("great_court", {}, 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  const auto peaks = findSurfacePeaks(surface);
  const auto t1 = std::chrono::steady_clock::now();
  const geodesic::DistanceSolver solver(surface);
  const auto t2 = std::chrono::steady_clock::now();
  const auto circles = injectivityCircles(surface, solver, peaks);
  const auto t3 = std::chrono::steady_clock::now();
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::cout << "great_court 1.0 m: " << surface.n_vertices() << " vertices, " << peaks.size()
            << " peaks in " << seconds(t0, t1) << " s, solver " << seconds(t1, t2) << " s, circles "
            << seconds(t2, t3) << " s\n";
  ASSERT_FALSE(peaks.empty());
  {
    const auto a = std::chrono::steady_clock::now();
    const auto f = solver.distancesFromVertex(peaks[0].vertex);
    std::cout << "  one field " << seconds(a, std::chrono::steady_clock::now()) << " s, "
              << f.windowsCreated << " windows\n";
  }
  for (size_t i = 0; i < circles.size(); ++i) {
    std::cout << "  peak " << i << " at (" << peaks[i].position.transpose() << ") K_max "
              << peaks[i].gaussianMax << " r " << circles[i].radiusM << " m, "
              << circles[i].polylines.size() << " polylines, complete " << circles[i].complete
              << ", covers " << circles[i].coversSurface << ", " << circles[i].propagations
              << " fields, " << circles[i].seconds << " s\n";
    EXPECT_LT(circles[i].maxDistanceErrorM, 1e-9 * circles[i].radiusM) << i;
    EXPECT_LT(peaks[i].radiusM, boundingBox(surface).size().norm()) << i;
  }
  CurvatureDrawing drawing;
  drawing.surface = &surface;
  drawing.peaks = peaks;
  drawing.circles = circles;
  drawing.title = "great_court: K peaks and injectivity circles";
  const std::string svg = curvatureSheetSvg(drawing);
  EXPECT_EQ(svgtext::count(svg, " id=\"hole-"), 1);  // the Reading Room
  EXPECT_EQ(svgtext::count(svg, " id=\"circle-"), static_cast<int>(circles.size()));
  if (std::getenv("EGG_KEEP_PLAN") != nullptr)
    writeCurvatureSheet(fs::temp_directory_path() / "great_court_plan.svg", drawing);
}

}  // namespace
}  // namespace egg::patching
