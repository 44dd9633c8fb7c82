#include "patching/workflow2.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "patching/layout.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace egg::patching {
namespace {

TEST(Workflow2, APlaneGetsOnePatchPerMaxSizeCell) {
  // 12 x 6 m, cells no larger than 5 m across: the 12 m direction needs 3 cells, the 6 m one 2
  // (a 4 x 3 m cell is 5 m across), so 3 x 2 = 6 patches covering the plane exactly.
  const TriMesh plane = samples::generateSample("plane", {{"length", 12}, {"width", 6}}, 0.5);
  Workflow2Options options;
  options.maxPatchSizeM = 5.0;
  const Workflow2Layout layout = proposeLayout(plane, options);
  EXPECT_EQ(layout.blocks, 1);
  EXPECT_EQ(layout.holes, 0);
  ASSERT_EQ(layout.quads.size(), 6u);
  EXPECT_EQ(layout.corners.size(), 12u);  // a 4 x 3 grid of corners
  for (const auto& q : layout.quads) {
    // Counter-clockwise seen from above, and within the size.
    const auto& a = layout.corners[q[0]];
    const auto& b = layout.corners[q[1]];
    const auto& c = layout.corners[q[2]];
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);
    EXPECT_LE((c - a).norm(), 5.0 + 1e-9);
    EXPECT_LE((layout.corners[q[3]] - b).norm(), 5.0 + 1e-9);
  }
  // The outer corners are the plane's corners.
  double minX = 1e9, maxX = -1e9;
  for (const auto& c : layout.corners) minX = std::min(minX, c.x()), maxX = std::max(maxX, c.x());
  EXPECT_NEAR(maxX - minX, 12.0, 1e-9);
}

TEST(Workflow2, AHoleIsNeverInsideAPatch) {
  // The Great Court: a rectangle with the Reading Room cut out. Every patch is cut without error
  // (a hole inside a patch, or a side wrapping round it, would throw) and none holds the hole's
  // centre.
  const TriMesh surface = samples::generateSample("great_court", {}, 2.0);
  Workflow2Options options;
  options.maxPatchSizeM = 80.0;
  const Workflow2Layout proposal = proposeLayout(surface, options);
  EXPECT_EQ(proposal.holes, 1);
  EXPECT_EQ(proposal.blocks, 4);
  EXPECT_EQ(proposal.quads.size(), 4u);
  const geodesic::DistanceSolver solver(surface);
  const PatchLayout layout = makeLayout(surface, solver, proposal.corners, proposal.quads);
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    const LayoutPatch cut = cutLayoutPatch(layout, static_cast<int>(p));
    for (auto vh : cut.patch.mesh.vertices()) {
      const Eigen::Vector3d x = toEigen(cut.patch.mesh.point(vh));
      EXPECT_GT(std::hypot(x.x(), x.y()), 22.245 - 1e-6)
          << "patch " << p;  // outside the Reading Room
    }
  }
}

TEST(Workflow2, ACornerMovesOntoAPeak) {
  // A bump off the centre of a 3 x 3 grid of 2 m cells: the interior grid node nearest to it moves
  // onto p_max (Algorithm 2: a corner at p_max).
  const TriMesh bump = samples::generateSample(
      "bump", {{"length", 6}, {"width", 6}, {"height", 0.8}, {"sigma", 0.8}}, 0.2);
  Workflow2Options options;
  options.maxPatchSizeM =
      3.4;  // 3 x 3 cells of 2 x 2 m (the centre one 3.3 m across over the bump)
  const Workflow2Layout layout = proposeLayout(bump, options);
  EXPECT_EQ(layout.quads.size(), 9u);
  // The bump is centred: no interior node of a 3 x 3 grid is near it, none moves.
  EXPECT_EQ(layout.peaksSnapped, 0);
  options.maxPatchSizeM =
      5.0;  // 2 x 2 cells (4.6 m across over the bump): the centre node is a grid node at the peak
  const Workflow2Layout two = proposeLayout(bump, options);
  EXPECT_EQ(two.quads.size(), 4u);
  EXPECT_EQ(two.peaksSnapped, 1);
  double nearest = 1e9;
  for (const auto& c : two.corners) nearest = std::min(nearest, c.head<2>().norm());
  EXPECT_LT(nearest, 0.25);
}

// z = two Gaussian bumps (height 2 m, sigma 1 m: K = 4 / m^2 at the tops, circles of pi / 2 m) at
// x = -3 and x = +3 over a 14 x 8 m regular grid.
TriMesh twoPeaks() {
  TriangleSoup soup;
  const int nx = 70, ny = 40;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -7.0 + 14.0 * i / nx, y = -4.0 + 8.0 * j / ny;
      soup.vertices.emplace_back(x, y,
                                 2.0 * (std::exp(-((x + 3) * (x + 3) + y * y) / 2) +
                                        std::exp(-((x - 3) * (x - 3) + y * y) / 2)));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      soup.triangles.push_back({a, b, c});
      soup.triangles.push_back({a, c, d});
    }
  return meshFromSoup(soup);
}

TEST(Workflow2, TwoPeaksGetACornerEach) {
  // Cells up to 9 m across over the bumps: the screened grid with the fewest predicted patches puts
  // a corner on each peak (a peak left inside a cell would cost Workflow 1 three more patches).
  const TriMesh surface = twoPeaks();
  Workflow2Options options;
  options.maxPatchSizeM = 9.0;
  const Workflow2Layout layout = proposeLayout(surface, options);
  EXPECT_EQ(layout.peaksSnapped, 2);
  EXPECT_GT(layout.candidatesScreened, 10);
  for (double x : {-3.0, 3.0}) {
    double nearest = 1e9;
    for (const auto& c : layout.corners) nearest = std::min(nearest, std::hypot(c.x() - x, c.y()));
    EXPECT_LT(nearest, 0.2) << "no corner on the peak at x = " << x;
  }
}

TEST(Workflow2, ACapLargerThanItsCircleIsSplitHoweverLargePatchesMayBe) {
  // A tall bump (K = 4 / m^2 at its top: a circle of pi / 2 m) on an 8 x 8 m footprint: one patch
  // would hold the cap in a cell far larger than its circle, which Workflow 1 would split into four
  // anyway; the layout starts with four round a corner on the peak.
  const TriMesh cap = samples::generateSample(
      "bump", {{"length", 8}, {"width", 8}, {"height", 2}, {"sigma", 1}}, 0.2);
  Workflow2Options options;
  options.maxPatchSizeM = 1000.0;
  const Workflow2Layout layout = proposeLayout(cap, options);
  EXPECT_EQ(layout.quads.size(), 4u);
  EXPECT_EQ(layout.peaksSnapped, 1);
}

TEST(Workflow2, EachOfTwoHolesGetsARingOfFourPatches) {
  // The Yas canopy with its two tower holes cut (20 x 12 m ellipses at (-55, -15) and (55, 15)):
  // each hole's box lies in a cell of its own, which becomes four patches round it; no patch
  // holds a hole (its centre is inside no quad's outline in plan).
  const TriMesh surface = samples::generateSample("yas", {{"holes", 1}}, 4.0);
  Workflow2Options options;
  options.maxPatchSizeM = 120.0;
  const Workflow2Layout layout = proposeLayout(surface, options);
  EXPECT_EQ(layout.holes, 2);
  EXPECT_EQ(layout.blocks, 1);
  for (const Eigen::Vector2d& centre : {Eigen::Vector2d(-55, -15), Eigen::Vector2d(55, 15)}) {
    int round = 0;
    for (const auto& q : layout.quads) {
      std::vector<Eigen::Vector2d> outline;
      for (int k : q) outline.push_back(layout.corners[k].head<2>());
      double winding =
          0.0;  // the angle the outline sweeps round the centre: 2 pi inside, 0 outside
      for (size_t k = 0; k < 4; ++k) {
        const Eigen::Vector2d a = outline[k] - centre, b = outline[(k + 1) % 4] - centre;
        winding += std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
      }
      EXPECT_LT(std::abs(winding), 1e-6) << "a patch holds the hole at " << centre.transpose();
      // A patch of the ring has two corners within 15 m of the hole's centre (its box's corners).
      int near = 0;
      for (const auto& c : outline) near += (c - centre).norm() < 15.0;
      round += near == 2;
    }
    EXPECT_EQ(round, 4) << "the ring round the hole at " << centre.transpose();
  }
}

TEST(Workflow2, TheSameLayoutOnAnyThreadCount) {
  const TriMesh surface = samples::generateSample("great_court", {}, 2.0);
  Workflow2Options options;
  options.maxPatchSizeM = 50.0;
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return proposeLayout(surface, options);
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.corners.size(), two.corners.size());
  for (size_t i = 0; i < one.corners.size(); ++i) EXPECT_EQ(one.corners[i], two.corners[i]);
  EXPECT_EQ(one.quads, two.quads);
  EXPECT_GT(one.quads.size(), 4u);  // 50 m cells: the ring's blocks are subdivided
}

TEST(Workflow2, AGivenBlockGridIsLaidOutAsGiven) {
  // The same 12 x 6 m plane: screening picks 3 x 2 (6 patches, above); the architect's 4 x 2 gives
  // 8 patches of 3 x 3 m, each 4.24 m across, and the corners of a 5 x 3 grid.
  const TriMesh plane = samples::generateSample("plane", {{"length", 12}, {"width", 6}}, 0.5);
  Workflow2Options options;
  options.maxPatchSizeM = 5.0;
  options.blockGrid = {4, 2};
  const Workflow2Layout layout = proposeLayout(plane, options);
  ASSERT_EQ(layout.quads.size(), 8u);
  EXPECT_EQ(layout.corners.size(), 15u);
  EXPECT_EQ(layout.candidatesScreened, 1);
  for (const auto& q : layout.quads)
    EXPECT_NEAR((layout.corners[q[2]] - layout.corners[q[0]]).norm(), std::sqrt(18.0), 1e-6);
  // Along the other direction: 2 x 4 cells are 6 x 1.5 m, 6.2 m across: larger than 5 m.
  options.blockGrid = {1, 4};
  try {
    proposeLayout(plane, options);
    ADD_FAILURE() << "a 12 m cell passed a 5 m limit";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("patching.block_grid [1, 4]"), std::string::npos)
        << e.what();
  }
  options.blockGrid = {0, 3};
  EXPECT_THROW(proposeLayout(plane, options), InvalidInput);
  options.blockGrid = {17, 1};
  EXPECT_THROW(proposeLayout(plane, options), InvalidInput);
}

TEST(Workflow2, BadInputIsNamed) {
  const TriMesh plane = samples::generateSample("plane", {{"length", 4}, {"width", 4}}, 0.5);
  Workflow2Options options;
  options.maxPatchSizeM = -1.0;
  EXPECT_THROW(proposeLayout(plane, options), InvalidInput);
}

}  // namespace
}  // namespace egg::patching
