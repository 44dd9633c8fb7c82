#include "core/curvature/curvature.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include "tests/support/analytic_meshes.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <map>
#include <numbers>

namespace egg {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::icosphere;

// Height field z = f(x, y) on a (2n+1)^2 grid over [-h n, h n]^2 (a vertex at the origin). With
// `unionJack` the diagonals alternate (valences 4 and 8, symmetric about the origin); otherwise
// they are all parallel (valence 6 everywhere).
template <class F>
TriMesh heightField(int n, double h, F f, int* originVertex, bool unionJack = false) {
  TriangleSoup soup;
  const int side = 2 * n + 1;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double x = (i - n) * h, y = (j - n) * h;
      soup.vertices.push_back({x, y, f(x, y)});
    }
  auto id = [side](int i, int j) { return j * side + i; };
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      if (!unionJack || (i + j) % 2 == 0) {
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        soup.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  *originVertex = id(n, n);
  return meshFromSoup(soup);
}

// Open cylinder of radius R around the z axis, `around` x `along` quads, outward normals.
TriMesh cylinder(double radius, double length, int around, int along) {
  TriangleSoup soup;
  for (int j = 0; j <= along; ++j)
    for (int i = 0; i < around; ++i) {
      const double phi = 2.0 * kPi * (i + 0.5 * (j % 2)) / around;  // staggered rows
      soup.vertices.push_back({radius * std::cos(phi), radius * std::sin(phi), length * j / along});
    }
  auto id = [around](int i, int j) { return j * around + (i % around); };
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      if (j % 2 == 0) {
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        soup.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      }
    }
  return meshFromSoup(soup);
}

struct ErrorStats {
  double max = 0.0, mean = 0.0;
  int count = 0;
};

TEST(Curvature, MixedAreasTileTheSurfaceAndDefectsObeyGaussBonnet) {
  const TriMesh sphere = icosphere(2.0, 3);
  EXPECT_NEAR(mixedVoronoiAreas(sphere).sum(), surfaceArea(sphere), 1e-10);
  EXPECT_NEAR(angleDefects(sphere).sum(), 4.0 * kPi, 1e-10);  // chi = 2
  int origin = 0;
  const TriMesh disc = heightField(
      4, 0.25, [](double x, double y) { return 0.2 * x * x - 0.1 * y * y; }, &origin);
  EXPECT_NEAR(mixedVoronoiAreas(disc).sum(), surfaceArea(disc), 1e-10);
  EXPECT_NEAR(angleDefects(disc).sum(), 2.0 * kPi,
              1e-10);  // a disc: chi = 1 (boundary turning included)
}

TEST(Curvature, SphereGaussianWithinOnePercent) {
  const double radius = 3.0;
  for (int level : {3, 4}) {
    const TriMesh mesh = icosphere(radius, level);
    const CurvatureField field = computeCurvature(mesh);
    double worstK = 0.0, worstKappa = 0.0, worstH = 0.0;
    for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
      worstK = std::max(worstK, std::abs(field.gaussianAngleDefect(v) * radius * radius - 1.0));
      worstKappa = std::max({worstKappa, std::abs(field.kappaMax(v) * radius - 1.0),
                             std::abs(field.kappaMin(v) * radius - 1.0)});
      worstH = std::max(worstH, std::abs(field.mean(v) * radius - 1.0));
      // Outward normals: the normal is the radial direction.
      EXPECT_GT(field.normals[v].dot(toEigen(mesh.point(TriMesh::VertexHandle(v))).normalized()),
                0.9999);
    }
    std::cout << "icosphere level " << level << " (mean edge " << meanEdgeLength(mesh) / radius
              << " R): max rel. error K " << worstK << ", kappa " << worstKappa << ", H " << worstH
              << "\n";
    EXPECT_LT(worstK, 0.01) << "level " << level;
    EXPECT_LT(worstKappa, 0.01) << "level " << level;
    EXPECT_NEAR(injectivityRadiusBound(field.gaussianMax), kPi * radius, 0.01 * kPi * radius);
  }
}

TEST(Curvature, CylinderIsFlatInKWithPrincipalDirectionsAroundAndAlong) {
  const double radius = 2.0;
  const TriMesh mesh = cylinder(radius, 4.0, 48, 24);
  const CurvatureField field = computeCurvature(mesh);
  int interior = 0;
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
    if (field.onBoundary[v]) continue;
    ++interior;
    const Eigen::Vector3d p = toEigen(mesh.point(TriMesh::VertexHandle(v)));
    const Eigen::Vector3d around = Eigen::Vector3d(-p.y(), p.x(), 0.0).normalized();
    EXPECT_NEAR(field.gaussianAngleDefect(v), 0.0,
                1e-10);  // angle defect of a developable mesh is exactly 0
    EXPECT_NEAR(field.kappaMax(v), 1.0 / radius, 0.01 / radius);
    EXPECT_NEAR(field.kappaMin(v), 0.0, 0.01 / radius);
    EXPECT_GT(std::abs(field.directionMax[v].dot(around)), 0.999);
    EXPECT_GT(std::abs(field.directionMin[v].z()), 0.999);
  }
  EXPECT_GT(interior, 1000);
  // Boundary vertices get K, kappa from a one-sided quadric fit: a few per cent of 1/R (measured
  // 2.5 % of 1/R^2 in K, 3.3 % in kappa here), stable rather than accurate.
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
    if (!field.onBoundary[v]) continue;
    EXPECT_NEAR(field.gaussianAngleDefect(v), 0.0, 0.05 / (radius * radius));
    EXPECT_NEAR(field.kappaMax(v), 1.0 / radius, 0.05 / radius);
  }
}

TEST(Curvature, HyparAtTheOriginHasKMinusCSquared) {
  const double c = 0.5;
  int origin = 0;
  const TriMesh mesh = heightField(
      6, 0.1, [c](double x, double y) { return c * x * y; }, &origin);
  const CurvatureField field = computeCurvature(mesh);
  std::cout << "hypar origin (valence 6): angle defect K " << field.gaussianAngleDefect(origin)
            << ", fit K " << field.gaussian(origin) << " (exact " << -c * c << ")\n";
  EXPECT_NEAR(field.gaussianAngleDefect(origin), -c * c, 0.01 * c * c);
  EXPECT_NEAR(field.gaussian(origin), -c * c, 1e-3 * c * c);
  EXPECT_NEAR(field.mean(origin), 0.0, 1e-3 * c);
  EXPECT_NEAR(field.kappaMax(origin), c, 1e-3 * c);
  EXPECT_NEAR(field.kappaMin(origin), -c, 1e-3 * c);
  // Principal directions of z = cxy bisect the axes.
  EXPECT_NEAR(std::abs(field.directionMax[origin].x()), std::sqrt(0.5), 1e-3);
  EXPECT_NEAR(std::abs(field.directionMax[origin].y()), std::sqrt(0.5), 1e-3);
  EXPECT_NEAR(field.directionMax[origin].dot(field.directionMin[origin]), 0.0, 1e-3);
}

TEST(Curvature, AngleDefectFailsAtValenceEightButTheFitDoesNot) {
  // Known limitation (Xu 2006): the angle defect is not a pointwise-consistent estimate of K at
  // vertices of valence != 6; on a "union jack" grid the valence-8 origin reports about 2 K. The
  // fit is unaffected, which is why it is offered next to the angle defect.
  const double c = 0.5;
  int origin = 0;
  const TriMesh mesh = heightField(
      6, 0.1, [c](double x, double y) { return c * x * y; }, &origin, true);
  const CurvatureField field = computeCurvature(mesh);
  EXPECT_EQ(mesh.valence(TriMesh::VertexHandle(origin)), 8u);
  EXPECT_NEAR(field.gaussianAngleDefect(origin), -2.0 * c * c, 0.02 * c * c);
  EXPECT_NEAR(field.gaussian(origin), -c * c, 1e-3 * c * c);
}

TEST(Curvature, ParaboloidSignsFollowTheNormal) {
  // z = (x^2 + y^2) / 2: at the origin kappa = 1 with the normal +z bending... towards the
  // normal, so with our convention (positive = bending away) kappa = -1 and K = +1.
  int origin = 0;
  const TriMesh mesh = heightField(
      5, 0.05, [](double x, double y) { return 0.5 * (x * x + y * y); }, &origin);
  const CurvatureField field = computeCurvature(mesh);
  EXPECT_GT(field.normals[origin].z(), 0.9999);
  EXPECT_NEAR(field.kappaMax(origin), -1.0, 1e-3);
  EXPECT_NEAR(field.kappaMin(origin), -1.0, 1e-3);
  EXPECT_NEAR(field.mean(origin), -1.0, 1e-3);
  EXPECT_NEAR(field.gaussianAngleDefect(origin), 1.0, 0.01);
  // K of a paraboloid is largest at its apex: 1 / (1 + r^2)^2.
  EXPECT_EQ(field.vertexGaussianMax, origin);
}

TEST(Curvature, SampleSphereCapAtSeveralEdgeLengths) {
  // The sample generator's remeshed (irregular) sphere cap: K = 1/R^2 everywhere.
  const double radius = 10.0;
  for (double edge : {1.0, 0.5, 0.25}) {
    TriMesh mesh;
    try {
      mesh = samples::generateSample("sphere", {{"radius", radius}, {"extent", 8.0}}, edge);
    } catch (const std::exception& e) {
      GTEST_SKIP() << "sample generator unavailable: " << e.what();
    }
    const CurvatureField field = computeCurvature(mesh);
    double maxDefect = 0.0, sumDefect = 0.0, maxFit = 0.0, sumFit = 0.0;
    int interior = 0;
    for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
      if (field.onBoundary[v]) continue;
      const double e = std::abs(field.gaussianAngleDefect(v) * radius * radius - 1.0);
      const double f = std::abs(field.gaussian(v) * radius * radius - 1.0);
      maxDefect = std::max(maxDefect, e), sumDefect += e;
      maxFit = std::max(maxFit, f), sumFit += f;
      ++interior;
    }
    std::cout << "sample sphere R=10 edge " << edge << " m (" << mesh.n_vertices()
              << " vertices): K angle defect max " << maxDefect << " mean " << sumDefect / interior
              << "; K fit max " << maxFit << " mean " << sumFit / interior << "\n";
    // The angle defect is exact on average but not at every vertex of an irregular mesh (a few
    // per cent at valence-5/7 vertices); the fit is within 1 % everywhere inside.
    EXPECT_LT(sumDefect / interior, 0.01) << edge;
    EXPECT_LT(maxFit, 0.01) << edge;
  }
}

TEST(Curvature, SampleCylinderAndHyparMatchAnalyticCurvature) {
  // Irregular (remeshed) sample meshes at edge 0.5 m.
  const double radius = 5.0;
  const TriMesh cyl = samples::generateSample("cylinder", {{"radius", radius}}, 0.5);
  const CurvatureField c = computeCurvature(cyl);
  double worstKappa = 0.0, worstFitK = 0.0, worstDirection = 0.0;
  for (int v = 0; v < static_cast<int>(cyl.n_vertices()); ++v) {
    if (c.onBoundary[v]) continue;
    // Axis x; the sign of kappa depends on the sample's orientation, so compare magnitudes.
    const bool maxIsBent = std::abs(c.kappaMax(v)) > std::abs(c.kappaMin(v));
    const double bent = maxIsBent ? c.kappaMax(v) : c.kappaMin(v);
    const Eigen::Vector3d& around = maxIsBent ? c.directionMax[v] : c.directionMin[v];
    worstKappa = std::max(worstKappa, std::abs(std::abs(bent) * radius - 1.0));
    worstFitK = std::max(worstFitK, std::abs(c.gaussian(v)) * radius * radius);
    worstDirection = std::max(worstDirection, std::abs(around.x()));
  }
  std::cout << "sample cylinder R=5 edge 0.5: max |kappa R - 1| " << worstKappa
            << ", max |K_fit| R^2 " << worstFitK << ", max |cos(around, axis)| " << worstDirection
            << "\n";
  EXPECT_LT(worstKappa, 0.01);
  EXPECT_LT(worstFitK, 0.01);
  EXPECT_LT(worstDirection, 0.05);

  const double twist = 0.1;
  const TriMesh hypar = samples::generateSample("hypar", {{"c", twist}}, 0.5);
  const CurvatureField h = computeCurvature(hypar);
  double worstFit = 0.0, meanDefect = 0.0, integralDefect = 0.0, integralExact = 0.0;
  int interior = 0;
  for (int v = 0; v < static_cast<int>(hypar.n_vertices()); ++v) {
    if (h.onBoundary[v]) continue;
    const Eigen::Vector3d p = toEigen(hypar.point(TriMesh::VertexHandle(v)));
    const double exact =
        -twist * twist / std::pow(1.0 + twist * twist * (p.x() * p.x() + p.y() * p.y()), 2);
    worstFit = std::max(worstFit, std::abs(h.gaussian(v) / exact - 1.0));
    meanDefect += std::abs(h.gaussianAngleDefect(v) / exact - 1.0);
    integralDefect += h.gaussianAngleDefect(v) * h.mixedArea(v);
    integralExact += exact * h.mixedArea(v);
    ++interior;
  }
  std::cout << "sample hypar c=0.1 edge 0.5: K fit max rel. error " << worstFit
            << ", angle defect mean rel. error " << meanDefect / interior << ", integrated "
            << integralDefect / integralExact - 1.0 << "\n";
  EXPECT_LT(worstFit, 0.01);
  // The angle defect is right in the integral (Gauss-Bonnet) though not vertex by vertex.
  EXPECT_NEAR(integralDefect / integralExact, 1.0, 0.01);
  EXPECT_GT(meanDefect / interior, worstFit);
}

TEST(Curvature, TheResultDoesNotDependOnTheThreadCount) {
  // The fits run in parallel with a stamp array per thread: one thread and two must agree bit
  // for bit (a shared stamp array would mix neighbourhoods across threads).
  const TriMesh mesh = samples::generateSample("hypar", {}, 0.3);
  CurvatureField one, two;
  tbb::task_arena(1).execute([&] { one = computeCurvature(mesh); });
  tbb::task_arena(2).execute([&] { two = computeCurvature(mesh); });
  ASSERT_GT(mesh.n_vertices(), 200u);
  EXPECT_EQ(one.gaussian, two.gaussian);
  EXPECT_EQ(one.mean, two.mean);
  EXPECT_EQ(one.kappaMax, two.kappaMax);
  EXPECT_EQ(one.onBoundary, two.onBoundary);
}

TEST(Curvature, OptionsAreValidated) {
  CurvatureOptions options;
  options.fitRings = 0;
  EXPECT_THROW(computeCurvature(icosphere(1.0, 1), options), InvalidInput);
  EXPECT_THROW(computeCurvature(TriMesh{}), InvalidInput);
  EXPECT_EQ(injectivityRadiusBound(-1.0), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(injectivityRadiusBound(4.0), kPi / 2.0);
}

}  // namespace
}  // namespace egg
