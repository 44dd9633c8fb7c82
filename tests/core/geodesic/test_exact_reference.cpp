// The engine against CGAL's exact Surface_mesh_shortest_path (the oracle of the issue): max
// relative error <= 1e-4 and mean <= 1e-5 beyond two mean edge lengths, on plane, bump, sphere,
// saddle and jittered meshes, with sources at vertices, on edges, inside faces and on the boundary.
// (Both are exact algorithms, so in practice they agree to rounding.)
#include "core/geodesic/exact_reference.hpp"

#include "core/geodesic/distance_solver.hpp"
#include "samples/generators/samples.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::geodesic {
namespace {

using testing::facePoint;

struct ErrorStats {
  double maxRelative = 0.0;
  double meanRelative = 0.0;
  int compared = 0;
};

// CGAL mishandles sources exactly on an edge (a boundary edge, or an interior edge given with a
// zero barycentric weight): it is off by up to several percent there, the known failure the issue
// mentions. Its oracle source is therefore moved 1e-10 (barycentric) into the face, which changes
// true distances by at most 1e-10 edge lengths, while our engine takes the exact edge point.
SurfacePoint intoFace(SurfacePoint p) {
  for (int i = 0; i < 3; ++i) p.barycentric[i] = std::max(p.barycentric[i], 1e-10);
  p.barycentric /= p.barycentric.sum();
  return p;
}

ErrorStats compareWithCgal(const TriMesh& mesh, const SurfacePoint& source) {
  const DistanceSolver solver(mesh);
  const auto ours = solver.distances(source).vertexDistances;
  const bool isVertex = (source.barycentric.array() > 0.0).count() == 1;
  const auto exact = referenceDistances(mesh, isVertex ? source : intoFace(source));
  const double nearLimit = 2.0 * solver.meanEdgeLength();
  ErrorStats stats;
  double sum = 0.0;
  for (size_t v = 0; v < exact.size(); ++v) {
    if (!(exact[v] > nearLimit) || !std::isfinite(exact[v])) continue;
    const double e = std::abs(ours[v] - exact[v]) / exact[v];
    stats.maxRelative = std::max(stats.maxRelative, e);
    sum += e;
    ++stats.compared;
  }
  stats.meanRelative = stats.compared > 0 ? sum / stats.compared : 0.0;
  return stats;
}

// A source on a boundary edge of the grid (the lower edge y = 0) and a boundary vertex.
std::vector<SurfacePoint> gridSources(const TriMesh& mesh) {
  const int faces = static_cast<int>(mesh.n_faces());
  std::vector<SurfacePoint> sources = {
      vertexPoint(mesh, static_cast<int>(mesh.n_vertices()) / 2 + 3),  // vertex
      facePoint(faces / 3, 0.5, 0.5, 0.0),                             // edge
      facePoint(2 * faces / 3 + 1, 0.2, 0.3, 0.5),                     // face
      vertexPoint(mesh, 2)};                                           // boundary vertex
  const auto box = boundingBox(mesh);
  sources.push_back(
      snapToSurface(mesh, Eigen::Vector3d(box.min.x() + 0.37 * box.size().x(), box.min.y(), 0.0)));
  return sources;
}

void expectMatchesCgal(const TriMesh& mesh, const std::vector<SurfacePoint>& sources,
                       const char* name) {
  for (size_t i = 0; i < sources.size(); ++i) {
    const ErrorStats stats = compareWithCgal(mesh, sources[i]);
    EXPECT_GT(stats.compared, 50) << name << " source " << i;
    EXPECT_LE(stats.maxRelative, 1e-4) << name << " source " << i;
    EXPECT_LE(stats.meanRelative, 1e-5) << name << " source " << i;
  }
}

TEST(ExactReference, MatchesCgalOnAJitteredPlane) {
  const TriMesh mesh = testing::gridMesh(18, 18, 1.0, 1.0, testing::flat, 0.2);
  expectMatchesCgal(mesh, gridSources(mesh), "jittered plane");
}

TEST(ExactReference, MatchesCgalOnABump) {
  const TriMesh mesh = testing::gridMesh(24, 24, 1.0, 1.0, testing::bump(0.5, 0.5, 0.35, 0.22));
  expectMatchesCgal(mesh, gridSources(mesh), "bump");
}

TEST(ExactReference, MatchesCgalOnAJitteredBump) {
  const TriMesh mesh =
      testing::gridMesh(24, 24, 1.0, 1.0, testing::bump(0.4, 0.6, 0.3, 0.2), 0.3, 11);
  expectMatchesCgal(mesh, gridSources(mesh), "jittered bump");
}

TEST(ExactReference, MatchesCgalOnASaddle) {
  const TriMesh mesh = testing::gridMesh(20, 20, 1.0, 1.0, testing::hypar(0.5, 0.5, 1.2), 0.2, 5);
  expectMatchesCgal(mesh, gridSources(mesh), "hypar");
}

TEST(ExactReference, MatchesCgalOnASphere) {
  const TriMesh mesh = testing::sphereMesh(1.5, 14, 28);
  const int faces = static_cast<int>(mesh.n_faces());
  expectMatchesCgal(mesh,
                    {vertexPoint(mesh, 0), vertexPoint(mesh, 100),
                     facePoint(faces / 2, 0.6, 0.4, 0.0), facePoint(faces / 3, 0.1, 0.2, 0.7)},
                    "sphere");
}

TEST(ExactReference, MatchesCgalOnRemeshedSamples) {
  // The sample generators' isotropic remeshing leaves most vertices as near-flat saddles, the
  // case DistanceSolverOptions::saddleAngleTolerance approximates: the bar must still hold.
  for (const auto& [name, edge] : std::vector<std::pair<std::string, double>>{
           {"bump", 0.35}, {"hypar", 0.4}, {"waves", 0.35}}) {
    const TriMesh mesh = samples::generateSample(name, {}, edge);
    ASSERT_LE(mesh.n_vertices(), 2000u) << name;
    const int n = static_cast<int>(mesh.n_vertices());
    const int faces = static_cast<int>(mesh.n_faces());
    expectMatchesCgal(mesh,
                      {vertexPoint(mesh, n / 3), facePoint(faces / 2, 0.2, 0.3, 0.5),
                       vertexPoint(mesh, 7 * n / 9)},
                      name.c_str());
  }
}

TEST(ExactReference, ExactModeAgreesWithCgalToRounding) {
  // With saddleAngleTolerance = 0 every saddle is a pseudo-source: the exact polyhedral distance.
  const TriMesh mesh =
      testing::gridMesh(20, 20, 1.0, 1.0, testing::bump(0.4, 0.6, 0.3, 0.2), 0.25, 3);
  DistanceSolverOptions exact = DistanceSolverOptions::exact();
  const DistanceSolver solver(mesh, exact);
  for (const SurfacePoint& source : {vertexPoint(mesh, 200), facePoint(300, 0.2, 0.3, 0.5)}) {
    const auto ours = solver.distances(source).vertexDistances;
    const auto cgal = referenceDistances(mesh, source);
    for (size_t v = 0; v < ours.size(); ++v)
      EXPECT_NEAR(ours[v], cgal[v], 1e-12 * (1.0 + cgal[v])) << v;
  }
}

TEST(ExactReference, ExactModeAgreesWithCgalOnRemeshedSamples) {
  // Remeshed samples are full of saddles with a tiny excess, whose pseudo-source windows cover only
  // the narrow cone where shortest paths may leave them (Propagator::fire): exact mode must still
  // find every shortest path.
  DistanceSolverOptions exact = DistanceSolverOptions::exact();
  for (const auto& [name, edge] :
       std::vector<std::pair<std::string, double>>{{"bump", 0.35}, {"hypar", 0.4}}) {
    const TriMesh mesh = samples::generateSample(name, {}, edge);
    const DistanceSolver solver(mesh, exact);
    const int n = static_cast<int>(mesh.n_vertices());
    for (const SurfacePoint& source :
         {vertexPoint(mesh, n / 3),
          facePoint(static_cast<int>(mesh.n_faces()) / 2, 0.2, 0.3, 0.5)}) {
      const auto ours = solver.distances(source).vertexDistances;
      const auto cgal = referenceDistances(mesh, source);
      double worst = 0.0;
      for (size_t v = 0; v < ours.size(); ++v)
        worst = std::max(worst, std::abs(ours[v] - cgal[v]) / (1.0 + cgal[v]));
      EXPECT_LT(worst, 1e-12) << name;
    }
  }
}

TEST(ExactReference, ExactModeAgreesWithCgalAroundAReflexCorner) {
  // A curved L-shaped patch: paths between the arms bend at the reflex boundary corner (either way
  // round, from sources in both arms) and at the saddles of the surface.
  const TriMesh mesh = testing::lShapeMesh(10, testing::hypar(1.0, 1.0, 0.4));
  DistanceSolverOptions exact = DistanceSolverOptions::exact();
  const DistanceSolver solver(mesh, exact);
  for (const Eigen::Vector3d& requested :
       {Eigen::Vector3d(1.7, 0.0, 0.0), Eigen::Vector3d(0.0, 1.7, 0.0),
        Eigen::Vector3d(1.6, 0.4, 0.0), Eigen::Vector3d(0.3, 1.8, 0.0)}) {
    const SurfacePoint source = snapToSurface(mesh, requested);
    const auto ours = solver.distances(source).vertexDistances;
    const bool isVertex = (source.barycentric.array() > 0.0).count() == 1;
    const auto cgal = referenceDistances(mesh, isVertex ? source : intoFace(source));
    for (size_t v = 0; v < ours.size(); ++v) {
      // The CGAL source sits 1e-10 (barycentric) inside the face when ours is on an edge.
      EXPECT_NEAR(ours[v], cgal[v], 1e-9 * (1.0 + cgal[v]))
          << "source near " << requested.transpose() << ", vertex " << v;
    }
  }
}

TEST(ExactReference, CgalIsWrongForSourcesOnEdgesButOursIsNot) {
  // Documents why the comparisons above nudge edge sources for CGAL: on a convex flat square the
  // distance from a boundary point is Euclidean; CGAL misses it by percents, we by rounding.
  const TriMesh mesh = testing::gridMesh(12, 12, 1.0, 1.0, testing::flat, 0.2);
  const SurfacePoint source = snapToSurface(mesh, Eigen::Vector3d(0.37, 0.0, 0.0));
  const Eigen::Vector3d p = position(mesh, source);
  const auto cgal = referenceDistances(mesh, source);
  const auto ours = DistanceSolver(mesh).distances(source).vertexDistances;
  double cgalError = 0.0, ourError = 0.0;
  for (auto vh : mesh.vertices()) {
    const double euclidean = (toEigen(mesh.point(vh)) - p).norm();
    cgalError = std::max(cgalError, std::abs(cgal[vh.idx()] - euclidean));
    ourError = std::max(ourError, std::abs(ours[vh.idx()] - euclidean));
  }
  EXPECT_LT(ourError, 1e-12);
  EXPECT_GT(cgalError, 1e-6);  // if CGAL gets fixed, the nudge above can go
}

TEST(ExactReference, UnreachableVerticesAreInfinite) {
  TriangleSoup soup = soupFromMesh(testing::gridMesh(3, 3, 1.0, 1.0, testing::flat));
  const int offset = static_cast<int>(soup.vertices.size());
  const TriangleSoup other = soupFromMesh(testing::gridMesh(2, 2, 1.0, 1.0, testing::flat));
  for (const auto& v : other.vertices) soup.vertices.push_back(v + Eigen::Vector3d(3, 0, 0));
  for (const auto& t : other.triangles)
    soup.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const auto d = referenceDistances(meshFromSoup(soup), facePoint(0, 0.3, 0.3, 0.4));
  EXPECT_TRUE(std::isfinite(d[0]));
  EXPECT_TRUE(std::isinf(d[offset]));
}

}  // namespace
}  // namespace egg::geodesic
