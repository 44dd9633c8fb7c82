// The FE check's figure (report.html, fem/verification.svg) on a hand-made result: two straight
// lamellas of two elements each, one over-utilised, a known displacement and buckling mode.
#include "pipeline/verification_figure.hpp"

#include "core/errors.hpp"
#include "pipeline/svg_png.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

namespace egg::pipeline {
namespace {

using verification::CheckResult;
using verification::FeMesh;

CheckResult twoLamellas(bool buckling) {
  CheckResult r;
  for (int l = 0; l < 2; ++l)
    for (int k = 0; k < 5; ++k) r.mesh.nodes.emplace_back(0.5 * k, 2.0 * l, 0.0);
  for (int l = 0; l < 2; ++l)
    for (int e = 0; e < 2; ++e) {
      FeMesh::Element element;
      const int first = 5 * l + 2 * e + 1;  // 1-based, as in the decks
      element.nodes = {first, first + 1, first + 2};
      element.owner = l;
      r.mesh.elements.push_back(element);
    }
  FeMesh::Element bolt;
  bolt.part = FeMesh::Part::Bolt;
  bolt.nodes = {1, 6, 6};
  r.mesh.elements.push_back(bolt);
  verification::CaseResult c;
  c.name = "self_weight";
  c.displacements.assign(r.mesh.nodes.size(), Eigen::Vector3d(0.0, 0.0, -0.01));
  c.lamellaUtilisation = {0.0, 1.5};
  c.maxUtilisation = 1.5;
  r.cases.push_back(c);
  if (buckling) {
    r.buckling.loadCase = "self_weight";
    r.buckling.factors = {4.2};
    r.buckling.modes.push_back(
        std::vector<Eigen::Vector3d>(r.mesh.nodes.size(), Eigen::Vector3d(0.0, 0.0, 1.0)));
  }
  return r;
}

int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(VerificationFigure, ColoursEachLamellaByItsUtilisationAndDrawsShapesToAStatedScale) {
  const std::string svg = verificationSvg(twoLamellas(true));
  // Three panels of the four lamella elements: coloured, undeformed + deflected, undeformed +
  // mode; the bolt is left out.
  EXPECT_EQ(occurrences(svg, "<polyline"), 4 + 8 + 8);
  // Utilisation 0 is green, 1.5 (over 1) dark red: two elements each, plus the legend's swatch.
  EXPECT_EQ(occurrences(svg, "stroke=\"#00af20\""), 2);
  EXPECT_EQ(occurrences(svg, "stroke=\"#7f0000\""), 2);
  EXPECT_NE(svg.find("max 1.50"), std::string::npos);
  // The structure is 2 m by 2 m in plan (2.83 m across): the largest displacement, 10 mm, is
  // drawn at a twentieth of that, x14.
  EXPECT_NE(svg.find("max 10.0 mm, drawn x14"), std::string::npos) << svg.substr(0, 2000);
  EXPECT_NE(svg.find("Buckling mode 1, factor 4.2"), std::string::npos);
  // librsvg reads it as a picture once it carries the SVG namespace (as fem/verification.svg).
  std::string file = svg;
  file.insert(4, " xmlns=\"http://www.w3.org/2000/svg\"");
  const auto png = std::filesystem::temp_directory_path() /
                   ("egg_verification_figure_" + std::to_string(::getpid()) + ".png");
  writePngFromSvg(file, png, 900);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
}

TEST(VerificationFigure, WithoutABucklingStepTheThirdPanelSaysSo) {
  const std::string svg = verificationSvg(twoLamellas(false));
  EXPECT_NE(svg.find("no buckling step"), std::string::npos);
  EXPECT_EQ(occurrences(svg, "<polyline"), 4 + 8 + 4);
}

TEST(VerificationFigure, AnUnsolvedCheckHasNoFigure) {
  CheckResult r = twoLamellas(true);
  r.solved = false;
  EXPECT_THROW(verificationSvg(r), InvalidInput);
}

}  // namespace
}  // namespace egg::pipeline
