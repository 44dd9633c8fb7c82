#include "core/generalised/generalised_grid.hpp"

#include "core/egg/solve_patch.hpp"
#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace egg::generalised {
namespace {

double gridTestDistanceToPolyline(const Eigen::Vector3d& p,
                                  const std::vector<Eigen::Vector3d>& line) {
  double best = INFINITY;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const Eigen::Vector3d e = line[i + 1] - line[i];
    const double t = std::clamp((p - line[i]).dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (line[i] + t * e - p).norm());
  }
  return best;
}

// Sphere cap of radius 10 m around the north pole (centre at the origin), 5 m footprint radius.
TriMesh gridTestCap(double edge) {
  return samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 5.0}}, edge);
}

TEST(GeneralisedGrid, CapLayoutCrossesWhereTheLinesCrossInsideTheDiskOnBothGeodesics) {
  const TriMesh mesh = gridTestCap(0.3);
  const GridDomain domain(mesh);
  LayoutParameters parameters;
  parameters.lines = {5, 5};
  parameters.angleRad = 0.3;
  const auto layout = layoutFromLines(domain, parameters);
  EXPECT_EQ(layout.members.size(), 10u);
  EXPECT_EQ(layout.splitMembers, 0);
  EXPECT_EQ(layout.droppedMembers, 0);
  EXPECT_EQ(layoutProblem(domain, layout), "");
  // Lines at -0.8, -0.4, 0, 0.4, 0.8 of the radius: the pairs (+-0.8, +-0.8) meet outside the
  // disk (0.8^2 + 0.8^2 > 1), every other pair inside: 25 - 4 crossings.
  const auto crossings = gridCrossings(domain, layout);
  EXPECT_EQ(crossings.size(), 21u);
  for (const auto& c : crossings) {
    ASSERT_TRUE(c.found);
    const auto& g = layout.members[c.g];
    const auto& h = layout.members[c.h];
    const auto& traceG = domain.member(g.start, g.end);
    const auto& traceH = domain.member(h.start, h.end);
    EXPECT_LT(gridTestDistanceToPolyline(c.position, traceG.positions),
              0.25 * domain.meanEdgeLengthM());
    EXPECT_LT(gridTestDistanceToPolyline(c.position, traceH.positions),
              0.25 * domain.meanEdgeLengthM());
    // The arc lengths read off the fields place the crossing along each traced member.
    // On a sphere the arc length from the start is R times the angle to the crossing.
    const double angle = std::acos(
        std::clamp(traceG.positions.front().normalized().dot(c.position.normalized()), -1.0, 1.0));
    EXPECT_NEAR(c.sGM, 10.0 * angle, 0.25 * domain.meanEdgeLengthM());
  }
  // Members of one family never cross, by construction and by the interleave test.
  for (size_t i = 0; i < layout.members.size(); ++i) {
    for (size_t j = 0; j < layout.members.size(); ++j) {
      if (layout.members[i].family == layout.members[j].family) {
        EXPECT_FALSE(membersCross(domain.sampleCount(), layout.members[i], layout.members[j]));
      }
    }
  }
}

// Where the great circle through p and q meets the cap's rim (z = sqrt(R^2 - extent^2)), the one
// beyond p (away from q) first.
std::array<Eigen::Vector3d, 2> gridTestRimPoints(const Eigen::Vector3d& p,
                                                 const Eigen::Vector3d& q) {
  const double radius = 10.0, rimZ = std::sqrt(100.0 - 25.0);
  const Eigen::Vector3d a = p.normalized();
  const Eigen::Vector3d b = (a.cross(q.normalized())).cross(a).normalized();  // towards q
  // radius (cos phi a_z + sin phi b_z) = rimZ: A cos phi + B sin phi = C.
  const double A = radius * a.z(), B = radius * b.z();
  const double amplitude = std::hypot(A, B), shift = std::atan2(B, A);
  const double delta = std::acos(std::clamp(rimZ / amplitude, -1.0, 1.0));
  std::array<Eigen::Vector3d, 2> rim;
  for (int k = 0; k < 2; ++k) {
    const double phi = shift + (k == 0 ? -delta : delta);
    rim[k] = radius * (std::cos(phi) * a + std::sin(phi) * b);
  }
  // phi grows from p towards q: the smaller phi lies beyond p.
  return rim;
}

int gridTestNearestSample(const GridDomain& domain, const Eigen::Vector3d& point) {
  int best = 0;
  for (int i = 1; i < domain.sampleCount(); ++i)
    if ((domain.position(i) - point).norm() < (domain.position(best) - point).norm()) best = i;
  return best;
}

TEST(GeneralisedGrid, DiskGridAgreesWithTheQuadSolversGridOnAnInscribedQuad) {
  // The quad solver (Chapter 2) designs a grid on a geodesic quad inscribed in the cap; each of
  // its members, a great-circle arc, continued to the rim is a member of a generalised grid on the
  // whole disk (anchors snapped to the rim's samples). Where the two grids overlap, inside the
  // quad, the generalised grid's crossings (from the distance fields of the rim) must be the quad
  // grid's connections.
  const TriMesh mesh = gridTestCap(0.15);
  EggOptions options;
  options.members.count = 5;
  const std::array<Eigen::Vector3d, 4> corners = {
      Eigen::Vector3d(-2.5, -2.0, 0), {2.5, -2.2, 0}, {2.3, 2.4, 0}, {-2.4, 2.1, 0}};
  std::array<Eigen::Vector3d, 4> onCap;
  for (int k = 0; k < 4; ++k) {
    onCap[k] = corners[k];
    onCap[k].z() = std::sqrt(100.0 - corners[k].head<2>().squaredNorm());
  }
  const auto quad = solveEgg(mesh, onCap, options);
  const GridDomain domain(mesh);
  GeneralisedLayout layout;
  int line = 0;
  for (int family = 0; family < 2; ++family) {
    for (const auto& member : family == 0 ? quad.grid.u : quad.grid.v) {
      const auto rim = gridTestRimPoints(member.spatial.front(), member.spatial.back());
      layout.members.push_back({family, gridTestNearestSample(domain, rim[0]),
                                gridTestNearestSample(domain, rim[1]), line++});
    }
  }
  ASSERT_EQ(layoutProblem(domain, layout), "");
  const auto crossings = gridCrossings(domain, layout);
  const int nu = static_cast<int>(quad.grid.u.size()), nv = static_cast<int>(quad.grid.v.size());
  ASSERT_EQ(static_cast<int>(crossings.size()), nu * nv);  // inside the quad every u meets every v
  double worst = 0.0;
  for (const auto& c : crossings) {
    ASSERT_TRUE(c.found);
    const auto& connection = quad.grid.connections[c.g * nv + (c.h - nu)];
    worst = std::max(worst, (c.position - connection.spatial).norm());
  }
  // Snapping an anchor to the rim's samples moves it by up to half their spacing, and a point of
  // the member between its anchors by less; the field intersection adds a quarter edge.
  double spacing = 0.0;
  for (int i = 0; i < domain.sampleCount(); ++i)
    spacing = std::max(
        spacing, (domain.position((i + 1) % domain.sampleCount()) - domain.position(i)).norm());
  EXPECT_LT(worst, 0.5 * spacing + 0.25 * domain.meanEdgeLengthM());
}

TEST(GeneralisedGrid, BadInputIsNamed) {
  LayoutParameters parameters;
  parameters.lines = {0, 4};
  try {
    parameters.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("lines[0]"), std::string::npos);
  }
  parameters.lines = {4, 4};
  parameters.offsets = {0.5, 1.0};
  EXPECT_THROW(parameters.validate(), InvalidInput);
  // A patch with a hole is not a disk.
  const TriMesh court = samples::generateSample("great_court", {}, 4.0);
  try {
    GridDomain domain(court);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("one boundary loop"), std::string::npos);
  }
}

}  // namespace
}  // namespace egg::generalised

namespace egg::generalised {
namespace {

TEST(GeneralisedGrid, MoonMembersSplitExactlyWhereTheirGeodesicWouldTouchTheBay) {
  // Lines across the mouth of the moon's bay, swept towards it. A line's member is split into two
  // exactly when the shortest connection between its anchors would touch the reflex bay - checked
  // against the traced geodesic, which then bends round a boundary vertex. On the dome the
  // geodesics bulge away from the crown, towards the bay, so members touch it while the straight
  // lines of the layout still pass clear: the member count changes where the member touches, not
  // where the line does.
  const TriMesh mesh = samples::generateSample("ch4_moon", {}, 0.015);
  const GridDomain domain(mesh);
  ASSERT_FALSE(domain.connections().nonConvexSegments.empty());
  const Eigen::Matrix<double, 3, 2> axes = domain.planeAxes();
  const Eigen::Vector2d direction = (axes.transpose() * Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  double low = INFINITY, high = -INFINITY;
  for (int i = 0; i < domain.sampleCount(); ++i) {
    if (!domain.bendsInward()[i]) continue;
    low = std::min(low, normal.dot(domain.projectedBoundary()[i]));
    high = std::max(high, normal.dot(domain.projectedBoundary()[i]));
  }
  int touchingBeforeTheLine = 0, clear = 0, lineThroughBay = 0;
  for (int k = 0; k <= 60; ++k) {
    const double c = (low - 0.08) + (high - low + 0.16) * k / 60.0;
    const auto whole = lineMembers(domain, direction, c, 0, 0, false);
    const auto split = lineMembers(domain, direction, c, 0, 0, true);
    int touching = 0;
    for (const auto& m : whole) {
      const auto path = domain.solver().path(geodesic::vertexPoint(mesh, domain.vertex(m.start)),
                                             geodesic::vertexPoint(mesh, domain.vertex(m.end)));
      bool touches = false;
      for (int v : path.bendVertices) {
        for (int i = 0; i < domain.sampleCount(); ++i)
          touches = touches || (domain.vertex(i) == v && domain.bendsInward()[i] != 0 &&
                                i != m.start && i != m.end);
      }
      touching += touches ? 1 : 0;
    }
    EXPECT_EQ(split.size(), whole.size() + touching) << "line at " << c;
    if (whole.size() == 1 && touching == 1) ++touchingBeforeTheLine;
    if (whole.size() == 1 && touching == 0) ++clear;
    if (whole.size() == 2) ++lineThroughBay;
  }
  EXPECT_GT(touchingBeforeTheLine, 0);
  EXPECT_GT(clear, 0);
  EXPECT_GT(lineThroughBay, 0);
}

}  // namespace
}  // namespace egg::generalised

namespace egg::generalised {
namespace {

TEST(GeneralisedGrid, AMemberNeedsTwoDifferentSamplesInRange) {
  const TriMesh mesh = samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 5.0}}, 0.6);
  const GridDomain domain(mesh);
  EXPECT_THROW(domain.member(3, 3), InvalidInput);
  EXPECT_THROW(domain.member(-1, 3), InvalidInput);
  EXPECT_THROW(domain.member(0, domain.sampleCount()), InvalidInput);
  const auto& forward = domain.member(0, domain.sampleCount() / 2);
  const auto& backward = domain.member(domain.sampleCount() / 2, 0);
  EXPECT_NEAR((forward.positions.front() - backward.positions.back()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(forward.effort, backward.effort, 1e-12);
}

}  // namespace
}  // namespace egg::generalised
