#include "patching/injectivity.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

namespace egg::patching {
namespace {

constexpr double kPi = std::numbers::pi;

// A tall narrow bump: K at the top = (height / sigma^2)^2 = 4 / m^2, so r = pi / 2 m, a circle that
// fits on the 8 x 8 m footprint.
TriMesh tallBump(double length = 8.0) {
  return samples::generateSample(
      "bump", {{"length", length}, {"width", 8}, {"height", 2}, {"sigma", 1}}, 0.15);
}

// z = sum of two Gaussian bumps (sigma 1 m) at x = +-separation / 2 over a regular grid.
TriMesh twoBumps(double separation, double height = 2.0) {
  TriangleSoup soup;
  const double hx = 0.5 * separation + 4.0, hy = 4.0, h = 0.15;
  const int nx = static_cast<int>(std::ceil(2 * hx / h)),
            ny = static_cast<int>(std::ceil(2 * hy / h));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -hx + 2 * hx * i / nx, y = -hy + 2 * hy * j / ny;
      double z = 0.0;
      for (double c : {-0.5 * separation, 0.5 * separation})
        z += height * std::exp(-((x - c) * (x - c) + y * y) / 2.0);
      soup.vertices.emplace_back(x, y, z);
    }
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Alternate the diagonals so the grid is symmetric under x -> -x.
      if ((i + j) % 2 == 0) {
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        soup.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return meshFromSoup(soup);
}

SurfacePeakOptions withMinGaussian(double k) {
  SurfacePeakOptions options;
  options.minGaussian = k;
  return options;
}

TEST(Injectivity, BumpPeakIsAtTheTopAndItsCircleIsAtDistanceR) {
  const TriMesh surface = tallBump();
  const std::vector<SurfacePeak> peaks = findSurfacePeaks(surface);
  ASSERT_EQ(peaks.size(), 1u);
  const SurfacePeak& peak = peaks[0];
  EXPECT_LT(peak.position.head<2>().norm(), 0.16);  // within one edge of the apex
  EXPECT_NEAR(peak.position.z(), 2.0, 0.03);
  // K_max is the conservative (largest nearby) K: at least the analytic 4 / m^2 less the fit error.
  EXPECT_GT(peak.gaussianMax, 3.8);
  EXPECT_LT(peak.gaussianMax, 4.4);
  EXPECT_NEAR(peak.radiusM, kPi / std::sqrt(peak.gaussianMax), 1e-12);
  EXPECT_FALSE(peak.onBoundary);

  const geodesic::DistanceSolver solver(surface);
  const InjectivityCircle circle = injectivityCircle(surface, solver, peak);
  EXPECT_EQ(circle.radiusM, peak.radiusM);
  ASSERT_EQ(circle.polylines.size(), 1u);
  EXPECT_TRUE(circle.complete);
  EXPECT_FALSE(circle.coversSurface);
  const CirclePolyline& loop = circle.polylines[0];
  EXPECT_TRUE(loop.closed);
  EXPECT_GT(loop.points.size(), 40u);
  EXPECT_LT(circle.maxDistanceErrorM, 1e-9 * circle.radiusM);
  // An independent check: a directed distance query for a few of the points.
  for (size_t i = 0; i < loop.points.size(); i += loop.points.size() / 7) {
    const double d = solver.distance(geodesic::vertexPoint(surface, peak.vertex), loop.points[i]);
    EXPECT_NEAR(d, circle.radiusM, 1e-6 * circle.radiusM) << i;
  }
  // Positive K inside: a geodesic circle is shorter than 2 pi r (Bertrand-Diguet-Puiseux), and on
  // this bump (K from 4 at the top to negative on the flank) not by more than half.
  EXPECT_LT(circle.lengthM, 2 * kPi * circle.radiusM);
  EXPECT_GT(circle.lengthM, 0.5 * 2 * kPi * circle.radiusM);
  // Counter-clockwise seen from above (the disc on the left): positive signed area in xy.
  double area = 0.0;
  for (size_t i = 0; i < loop.positions.size(); ++i) {
    const auto& a = loop.positions[i];
    const auto& b = loop.positions[(i + 1) % loop.positions.size()];
    area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  EXPECT_GT(area, 0.0);
}

TEST(Injectivity, FlatCircleHasLengthTwoPiR) {
  const TriMesh plane = samples::generateSample("plane", {{"length", 8}, {"width", 8}}, 0.2);
  const geodesic::DistanceSolver solver(plane);
  SurfacePeak peak;
  double best = 1e9;
  for (auto v : plane.vertices())
    if (toEigen(plane.point(v)).norm() < best)
      best = toEigen(plane.point(v)).norm(), peak.vertex = v.idx();
  peak.radiusM = 2.0;
  const InjectivityCircle circle = injectivityCircle(plane, solver, peak);
  ASSERT_EQ(circle.polylines.size(), 1u);
  EXPECT_TRUE(circle.complete);
  for (const auto& p : circle.polylines[0].positions)
    EXPECT_NEAR((p - circle.centre).norm(), 2.0, 1e-9);
  // The inscribed polygon (edges ~0.2 m) is short of 2 pi r by about (h / r)^2 / 24.
  EXPECT_LT(circle.lengthM, 2 * kPi * 2.0);
  EXPECT_GT(circle.lengthM, 2 * kPi * 2.0 * (1 - 2e-3));
}

TEST(Injectivity, CircleLeavingTheSurfaceIsOpenAndOneCoveringItIsAbsent) {
  // The same bump on a footprint only 2 m long: the circle (horizontal radius ~1.3 m) leaves it at
  // x = +-1.
  const TriMesh narrow = tallBump(2.0);
  const geodesic::DistanceSolver solver(narrow);
  const auto peaks = findSurfacePeaks(narrow);
  ASSERT_FALSE(peaks.empty());
  const InjectivityCircle open = injectivityCircle(narrow, solver, peaks[0]);
  EXPECT_FALSE(open.complete);
  EXPECT_FALSE(open.coversSurface);
  ASSERT_EQ(open.polylines.size(), 2u);  // one arc on each side of the peak
  for (const auto& piece : open.polylines) {
    EXPECT_FALSE(piece.closed);
    for (const Eigen::Vector3d* end : {&piece.positions.front(), &piece.positions.back()})
      EXPECT_NEAR(std::abs(end->x()), 1.0, 1e-9);  // on the boundary x = +-1
  }

  // A sphere cap of radius 10 m: r = pi R = 31.4 m, larger than the whole cap; no circle at all.
  const TriMesh cap = samples::generateSample("sphere", {{"radius", 10}, {"extent", 5}}, 0.5);
  const auto capPeaks = findSurfacePeaks(cap, withMinGaussian(1e-3));
  ASSERT_FALSE(capPeaks.empty());
  EXPECT_NEAR(capPeaks[0].gaussianMax, 0.01, 0.001);  // K = 1 / R^2
  EXPECT_NEAR(capPeaks[0].radiusM, kPi * 10, 1.6);
  const geodesic::DistanceSolver capSolver(cap);
  const InjectivityCircle none = injectivityCircle(cap, capSolver, capPeaks[0]);
  EXPECT_TRUE(none.coversSurface);
  EXPECT_FALSE(none.complete);
  EXPECT_TRUE(none.polylines.empty());
  // By default such a peak is not reported: its circle is larger than the cap's diagonal.
  EXPECT_TRUE(findSurfacePeaks(cap).empty());
}

TEST(Injectivity, TwoBumpsFarApartGiveTwoPeaksCloseTogetherOne) {
  const auto far = findSurfacePeaks(twoBumps(6.0));
  ASSERT_EQ(far.size(), 2u);
  for (const auto& p : far) EXPECT_NEAR(std::abs(p.position.x()), 3.0, 0.16);
  EXPECT_LT(far[0].position.x() * far[1].position.x(), 0.0);
  EXPECT_GE(far[0].gaussianAveraged, far[1].gaussianAveraged);

  // Two low bumps (height 0.5 m: K = 0.25 / m^2 at the tops, r = 2 pi m) 3 m apart: the raw search
  // finds a peak on each, but each lies well inside the other's circle.
  const TriMesh close = twoBumps(3.0, 0.5);
  const CurvatureField field = computeCurvature(close);
  const auto raw = findGaussianPeaks(close, field.gaussian, field.mixedArea);
  int strong = 0;
  for (const auto& p : raw)
    strong += p.gaussianMaxNearby > 0.2 && std::abs(std::abs(p.position.x()) - 1.5) < 0.2;
  EXPECT_EQ(strong, 2);
  const auto kept = findSurfacePeaks(close);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].vertex, raw[0].vertex);
}

TEST(Injectivity, SameResultOnOneAndTwoThreads) {
  const TriMesh surface = twoBumps(6.0);
  const geodesic::DistanceSolver solver(surface);
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const auto peaks = findSurfacePeaks(surface);
    return std::make_pair(peaks, injectivityCircles(surface, solver, peaks));
  };
  const auto [peaks1, circles1] = run(1);
  const auto [peaks2, circles2] = run(2);
  ASSERT_EQ(peaks1.size(), peaks2.size());
  ASSERT_EQ(circles1.size(), 2u);
  for (size_t i = 0; i < peaks1.size(); ++i) {
    EXPECT_EQ(peaks1[i].vertex, peaks2[i].vertex);
    EXPECT_EQ(peaks1[i].gaussianMax, peaks2[i].gaussianMax);
    ASSERT_EQ(circles1[i].polylines.size(), circles2[i].polylines.size());
    EXPECT_EQ(circles1[i].lengthM, circles2[i].lengthM);
    for (size_t k = 0; k < circles1[i].polylines.size(); ++k)
      EXPECT_EQ(circles1[i].polylines[k].positions, circles2[i].polylines[k].positions);
  }
}

TEST(Injectivity, BadInputIsNamed) {
  const TriMesh surface = tallBump();
  const geodesic::DistanceSolver solver(surface);
  SurfacePeak peak;
  peak.vertex = static_cast<int>(surface.n_vertices());
  peak.radiusM = 1.0;
  EXPECT_THROW(injectivityCircle(surface, solver, peak), InvalidInput);
  EXPECT_THROW(findSurfacePeaks(surface, withMinGaussian(-1.0)), InvalidInput);
}

}  // namespace
}  // namespace egg::patching
