#include "pipeline/elevations.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace egg::pipeline {
namespace {

// A panel of elevations.svg read back into metres through its data-frame and data-px-per-m.
struct PanelReading {
  std::string text;  // the panel's SVG, up to the next panel
  double left = 0, top = 0, h0 = 0, z0 = 0, scale = 1;
  Eigen::Vector2d metres(double x, double y) const {
    return {h0 + (x - left) / scale, z0 - (y - top) / scale};
  }
};

PanelReading panelOf(const std::string& svg, const std::string& id) {
  PanelReading p;
  const size_t rootScale = svg.find("data-px-per-m=\"");
  p.scale = std::stod(svg.substr(rootScale + 15));
  const size_t at = svg.find("<g id=\"" + id + "\" data-frame=\"");
  if (at == std::string::npos) return p;
  std::istringstream frame(svg.substr(at + id.size() + 21, 120));
  frame >> p.left >> p.top >> p.h0 >> p.z0;
  const size_t next = svg.find("<g id=\"", at + 1);
  p.text = svg.substr(at, next == std::string::npos ? std::string::npos : next - at);
  return p;
}

// The points of the first path of `cls` in the panel (M/L/Z commands, absolute).
std::vector<Eigen::Vector2d> pathPoints(const PanelReading& p, const std::string& cls) {
  std::vector<Eigen::Vector2d> out;
  const size_t at = p.text.find("class=\"" + cls + "\"");
  if (at == std::string::npos) return out;
  const size_t d = p.text.find(" d=\"", at) + 4;
  std::string data = p.text.substr(d, p.text.find('"', d) - d);
  for (char& c : data)
    if (c == 'M' || c == 'L' || c == 'Z' || c == ',') c = ' ';
  std::istringstream in(data);
  for (double x, y; in >> x >> y;) out.push_back(p.metres(x, y));
  return out;
}

std::vector<Eigen::Vector2d> cutDots(const PanelReading& p) {
  std::vector<Eigen::Vector2d> out;
  const std::string key = "<circle cx=\"";
  for (size_t at = p.text.find(key); at != std::string::npos; at = p.text.find(key, at + 1)) {
    const double x = std::stod(p.text.substr(at + key.size()));
    const size_t cy = p.text.find("cy=\"", at) + 4;
    out.push_back(p.metres(x, std::stod(p.text.substr(cy))));
  }
  return out;
}

// A cylinder vault y^2 + z^2 = 25, axis x, x in [-5, 5], z >= 0; one lamella along the axis at
// the angle 0.3 from the top and one round the arc at x = 1.
struct Vault {
  TriMesh surface = samples::generateSample(
      "cylinder", {{"radius", 5.0}, {"length", 10.0}, {"angle", M_PI}}, 0.25);
  std::vector<DeployedRod> rods;
  Vault() {
    DeployedRod along, round;
    for (int k = 0; k <= 20; ++k)
      along.points.emplace_back(-5.0 + 0.5 * k, 5.0 * std::sin(0.3), 5.0 * std::cos(0.3));
    for (int k = 0; k <= 40; ++k) {
      const double t = -M_PI / 2 + M_PI * k / 40;
      round.points.emplace_back(1.0, 5.0 * std::sin(t), 5.0 * std::cos(t));
    }
    rods = {along, round};
  }
};

TEST(Elevations, SectionsOfAVaultCutTheDesignCircleAndEachLamellaOnce) {
  const Vault vault;
  const auto planes = sectionPlanes(vault.surface);
  ASSERT_EQ(planes.size(), 2u);
  EXPECT_TRUE(planes[0].alongX);
  EXPECT_NEAR(planes[0].atM, 0.0, 1e-9);  // the middle of y in [-5, 5]
  EXPECT_NEAR(planes[1].atM, 0.0, 1e-9);
  const std::string svg = elevationsSvg(vault.surface, vault.rods, "vault & <rods>");
  // Points are written to 0.1 px; the mesh's chords sag at most h^2 / 8r = 1.6 mm under the arc.
  const PanelReading b = panelOf(svg, "section-b"), a = panelOf(svg, "section-a");
  ASSERT_FALSE(b.text.empty());
  ASSERT_FALSE(a.text.empty());
  const double tolerance = 0.0016 + 0.1 / b.scale;
  const auto arc = pathPoints(b, "design-cut");
  ASSERT_GT(arc.size(), 100u);
  for (const auto& q : arc) EXPECT_NEAR(q.norm(), 5.0, tolerance) << q.transpose();
  const auto crown = pathPoints(a, "design-cut");  // y = 0: the vault's top line, z = 5
  ASSERT_GT(crown.size(), 20u);
  double hMin = 1e9, hMax = -1e9;
  for (const auto& q : crown) {
    EXPECT_NEAR(q.y(), 5.0, tolerance);
    hMin = std::min(hMin, q.x()), hMax = std::max(hMax, q.x());
  }
  EXPECT_LT(hMin, -4.9);
  EXPECT_GT(hMax, 4.9);
  // B-B (x = 0) cuts the lamella along the axis at (y, z) = 5 (sin 0.3, cos 0.3); A-A (y = 0) cuts
  // the one round the arc at its top, (x, z) = (1, 5).
  const auto dotsB = cutDots(b), dotsA = cutDots(a);
  ASSERT_EQ(dotsB.size(), 1u);
  EXPECT_NEAR(dotsB[0].x(), 5.0 * std::sin(0.3), 0.1 / b.scale);
  EXPECT_NEAR(dotsB[0].y(), 5.0 * std::cos(0.3), 0.1 / b.scale);
  ASSERT_EQ(dotsA.size(), 1u);
  EXPECT_NEAR(dotsA[0].x(), 1.0, 0.1 / a.scale);
  EXPECT_NEAR(dotsA[0].y(), 5.0, 0.1 / a.scale);
  EXPECT_NE(b.text.find(">1 lamellas cut<"), std::string::npos);
}

TEST(Elevations, SilhouettesAreTheVaultsRectangleAndArcAtOneScaleWithLevels) {
  const Vault vault;
  const std::string svg = elevationsSvg(vault.surface, vault.rods, "vault");
  const PanelReading south = panelOf(svg, "elevation-south"), east = panelOf(svg, "elevation-east");
  // A column's top is the highest chord over it: the mesher's edges (0.25 m aimed, up to ~0.45 m)
  // sag at most 0.45^2 / 8r = 5 mm under the arc.
  const double tolerance = 0.005 + 0.1 / south.scale;
  // Looking north the vault covers x in [-5, 5] from z = 0 to its top, z = 5.
  const auto front = pathPoints(south, "design");
  ASSERT_GT(front.size(), 100u);
  double zMin = 1e9, zMax = -1e9, hMin = 1e9, hMax = -1e9;
  for (const auto& q : front) {
    zMin = std::min(zMin, q.y()), zMax = std::max(zMax, q.y());
    hMin = std::min(hMin, q.x()), hMax = std::max(hMax, q.x());
  }
  EXPECT_NEAR(zMin, 0.0, tolerance);
  EXPECT_NEAR(zMax, 5.0, tolerance);
  EXPECT_LT(hMin, -4.95);  // column centres: within 1.5 px of the ends
  EXPECT_GT(hMax, 4.95);
  // Looking west it is its end arc: every silhouette point on y^2 + z^2 = 25.
  const auto end = pathPoints(east, "design");
  ASSERT_GT(end.size(), 100u);
  for (const auto& q : end) EXPECT_NEAR(q.norm(), 5.0, tolerance) << q.transpose();
  // Levels: the ground at z = 0, the design's and the lamellas' top at 5 m.
  EXPECT_NE(svg.find(">±0.00 ground<"), std::string::npos);
  EXPECT_NE(svg.find(">+5.00 design<"), std::string::npos);
  EXPECT_NE(svg.find(">+5.00 deployed<"), std::string::npos);
  // One scale for every panel, and a scale bar whose length matches it.
  EXPECT_DOUBLE_EQ(south.scale, east.scale);
  const size_t bar = svg.find("id=\"scale-bar\"");
  ASSERT_NE(bar, std::string::npos);
  const double barPx = std::stod(svg.substr(svg.find("width=\"", bar) + 7));
  const size_t label = svg.find("id=\"scale-label\"");
  const double barM = std::stod(svg.substr(svg.find('>', label) + 1));
  EXPECT_NEAR(barPx, barM * south.scale, 1e-3);
}

TEST(Elevations, RendersAloneAndRefusesAnEmptySurface) {
  const Vault vault;
  const std::string svg = elevationsSvg(vault.surface, vault.rods, "vault & <rods>");
  EXPECT_NE(svg.find("vault &amp; &lt;rods&gt;"), std::string::npos);
  EXPECT_EQ(svg.rfind("<svg id=\"elevations\" xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_elevations_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "e.svg") << svg;
  const auto run = egg::test::runTool("rsvg-convert -o '" + (dir / "e.png").string() + "' '" +
                                      (dir / "e.svg").string() + "'");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_GT(std::filesystem::file_size(dir / "e.png"), 5000u);
  std::filesystem::remove_all(dir);
  // Without lamellas (no simulation drawn) the design alone still draws.
  EXPECT_NE(elevationsSvg(vault.surface, {}, "design only").find("class=\"design\""),
            std::string::npos);
  EXPECT_THROW(elevationsSvg(TriMesh(), vault.rods, "none"), InvalidInput);
}

}  // namespace
}  // namespace egg::pipeline
