#include "core/generalised/generalised_design.hpp"

#include "core/errors.hpp"
#include "core/rods/simulation.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

namespace egg::generalised {
namespace {

struct DesignTestCase {
  TriMesh mesh;
  std::unique_ptr<GridDomain> domain;
  GeneralisedLayout layout;
};

// A 6 x 6 line layout on a sphere cap of radius 10 m, 5 m footprint radius.
DesignTestCase designTestCap() {
  DesignTestCase c;
  c.mesh = samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 5.0}}, 0.3);
  c.domain = std::make_unique<GridDomain>(c.mesh);
  LayoutParameters parameters;
  parameters.lines = {6, 6};
  parameters.angleRad = 0.3;
  c.layout = layoutFromLines(*c.domain, parameters);
  return c;
}

TEST(GeneralisedDesign, CapLayoutIsCutPlanarWithEveryLengthKeptAndNoOverlap) {
  const auto c = designTestCap();
  GeneralisedDesignOptions options;
  options.section = {0.08, 0.01};
  const auto design = designGeneralisedGrid(*c.domain, c.layout, options);
  ASSERT_EQ(design.planar.endpoints.size(), c.layout.members.size());
  for (size_t i = 0; i < c.layout.members.size(); ++i) {
    const auto& m = c.layout.members[i];
    const auto& e = design.planar.endpoints[i];
    EXPECT_NEAR((e[1] - e[0]).norm(), c.domain->distance(m.start, m.end), 1e-9);
  }
  EXPECT_TRUE(design.planar.overlappingPairs.empty());
  EXPECT_TRUE(design.planarOverlaps.empty());
  EXPECT_FALSE(design.neighbours.empty());
  // A sphere cannot be laid flat: the crossings keep notches, but far shorter ones than in the
  // grid flattened by projection.
  EXPECT_GT(design.planar.notchEnergyM2, 0.0);
  EXPECT_LT(design.planar.notchEnergyM2, 0.5 * design.planar.initialNotchEnergyM2);
  // The field crossings of Section 4.5.2 lie within a fraction of an edge of the traced ones
  // (Table 4.1's eps_geo is 6-11 %).
  EXPECT_LT(design.epsGeoPercent, 15.0);
  EXPECT_LT(design.maxCrossingDeviationM, c.domain->meanEdgeLengthM());
  // The rods: one per member, two anchors each on the rim, one bolt per crossing.
  EXPECT_EQ(design.network.rods.size(), c.layout.members.size());
  EXPECT_EQ(design.network.anchors.size(), 2 * c.layout.members.size());
  EXPECT_EQ(design.network.connections.size(), design.fieldCrossings.size());
  for (const auto& anchor : design.network.anchors)
    EXPECT_NEAR(anchor.position.head<2>().norm(), 5.0, 1e-6);
}

TEST(GeneralisedDesign, CapDeploysOntoTheSurfaceOnlyWithItsNotches) {
  // Held at the rim, the straight lamellas bend onto the sphere; the notches let the bolts slide
  // to where the surface puts them. With plain holes at the planar crossings the grid cannot
  // reach the sphere's metric and bulges away from it.
  const auto c = designTestCap();
  GeneralisedDesignOptions options;
  options.section = {0.08, 0.01};
  const auto design = designGeneralisedGrid(*c.domain, c.layout, options);
  rods::SimulationOptions simulation;
  simulation.compareWithoutNotches = true;
  const auto result = rods::simulateGrid(design.network, c.mesh, simulation);
  ASSERT_TRUE(result.converged) << result.reason;
  const double withNotches = result.deployed.deviation->rmseM;
  const double plainHoles = result.withoutNotches->deviation->rmseM;
  EXPECT_LT(withNotches, 0.02);  // 2 cm over a 10 m grid
  EXPECT_GT(plainHoles, 5.0 * withNotches);
}

TEST(GeneralisedDesign, LamellasOfOneFamilyOverlapByHowMuchTheirOutlinesShare) {
  // Two parallel 1 m lamellas 2 cm wide: 1 cm apart they share 1 cm, 3 cm apart nothing; a
  // lamella of the other family crossing both lies in the other layer.
  const std::vector<Segment2> near = {Segment2{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)},
                                      Segment2{Eigen::Vector2d(0, 0.01), Eigen::Vector2d(1, 0.01)},
                                      Segment2{Eigen::Vector2d(0.5, -1), Eigen::Vector2d(0.5, 1)}};
  const auto pairs = overlappingLamellas(near, {0, 0, 1}, 0.02);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(0, 1));
  EXPECT_EQ(overlappingLamellas(near, {0, 0, 1}, 0.02, 0.0099).size(), 1u);
  EXPECT_TRUE(overlappingLamellas(near, {0, 0, 1}, 0.02, 0.0101).empty());
  auto apart = near;
  apart[1] = Segment2{Eigen::Vector2d(0, 0.03), Eigen::Vector2d(1, 0.03)};
  EXPECT_TRUE(overlappingLamellas(apart, {0, 0, 1}, 0.02).empty());
  // End to end along one line, 1 cm apart: apart; 1 cm overlapping: overlapping.
  const std::vector<Segment2> inLine = {Segment2{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)},
                                        Segment2{Eigen::Vector2d(1.01, 0), Eigen::Vector2d(2, 0)}};
  EXPECT_TRUE(overlappingLamellas(inLine, {0, 0}, 0.02).empty());
  auto shared = inLine;
  shared[1][0].x() = 0.99;
  EXPECT_EQ(overlappingLamellas(shared, {0, 0}, 0.02).size(), 1u);
}

TEST(GeneralisedDesign, RejectsAnUnbuildableLayoutNamingTheMembers) {
  auto c = designTestCap();
  auto layout = c.layout;
  // Family 0's first member turned round to cross its neighbour.
  std::swap(layout.members[0].end, layout.members[1].end);
  try {
    designGeneralisedGrid(*c.domain, layout);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("of one family cross"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace egg::generalised

namespace egg::generalised {
namespace {

TEST(GeneralisedDesign, CrossingAnglesAreTheLinesAnglesOnAPlane) {
  // On a plane the members are the layout's straight lines between their snapped anchors: the
  // families cross at 90 degrees minus the skew, to within the turn a snap of half a boundary
  // edge gives a member of a few metres.
  const TriMesh mesh = samples::generateSample("plane", {{"length", 6.0}, {"width", 5.0}}, 0.2);
  const GridDomain domain(mesh);
  LayoutParameters parameters;
  parameters.lines = {5, 5};
  parameters.angleRad = 0.3;
  parameters.skewRad = 0.5;
  const auto layout = layoutFromLines(domain, parameters);
  GeneralisedDesignOptions options;
  options.section = {0.05, 0.005};
  const auto design = designGeneralisedGrid(domain, layout, options);
  ASSERT_FALSE(design.crossingAnglesRad.empty());
  for (double angle : design.crossingAnglesRad)
    EXPECT_NEAR(angle, std::numbers::pi / 2 - 0.5, 0.06);
  EXPECT_NEAR(design.minCrossingAngleRad,
              *std::min_element(design.crossingAnglesRad.begin(), design.crossingAnglesRad.end()),
              0.0);
}

}  // namespace
}  // namespace egg::generalised
