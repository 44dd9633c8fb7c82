// The engines without stored windows (DistanceSolverOptions::Engine::FrontOnly and Wavefront,
// issue 19; every test below runs for both) against the stored-window one and against CGAL's exact
// Surface_mesh_shortest_path, on bump, hypar, sphere, prism and L-shaped meshes with vertex, edge
// and face sources; its memory (only the front is held), directed queries, paths and thread-count
// determinism; and how many of the windows either engine keeps a vertex-distance filter could still
// have dropped.
#include "core/geodesic/distance_solver.hpp"

#include "core/errors.hpp"
#include "core/geodesic/exact_reference.hpp"
#include "core/geodesic/window_propagation.hpp"
#include "samples/generators/samples.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace egg::geodesic {
namespace {

using testing::facePoint;
using Engine = DistanceSolverOptions::Engine;

DistanceSolverOptions withEngine(Engine engine,
                                 double tolerance = DistanceSolverOptions{}.saddleAngleTolerance) {
  DistanceSolverOptions o;
  o.engine = engine;
  o.saddleAngleTolerance = tolerance;
  if (tolerance == 0.0) o.imageMergeTolerance = 0.0;  // the exact mode
  return o;
}

struct Case {
  std::string name;
  TriMesh mesh;
};

std::vector<Case> meshes() {
  return {{"jittered bump",
           testing::gridMesh(22, 20, 2.2, 2.0, testing::bump(1.1, 1.0, 0.5, 0.5), 0.25)},
          {"hypar", testing::gridMesh(18, 18, 1.0, 1.0, testing::hypar(0.5, 0.5, 0.8), 0.3)},
          {"sphere", testing::sphereMesh(1.0, 18, 30)},
          {"prism", testing::prismMesh(7, 0.5, 1.5, 12)},
          {"L-shape", testing::lShapeMesh(9, testing::bump(0.6, 0.6, 0.3, 0.4))}};
}

std::vector<SurfacePoint> sourcesOf(const TriMesh& mesh) {
  const int faces = static_cast<int>(mesh.n_faces());
  return {vertexPoint(mesh, static_cast<int>(mesh.n_vertices()) / 3),
          facePoint(faces / 2, 0.5, 0.5, 0.0), facePoint(2 * faces / 3 + 1, 0.2, 0.3, 0.5)};
}

double maxRelativeDifference(const std::vector<double>& a, const std::vector<double>& b,
                             double near) {
  double worst = 0.0;
  for (size_t v = 0; v < b.size(); ++v) {
    if (!std::isfinite(b[v])) {
      EXPECT_EQ(a[v], b[v]) << "vertex " << v;
      continue;
    }
    if (b[v] > near) worst = std::max(worst, std::abs(a[v] - b[v]) / b[v]);
  }
  return worst;
}

// The engines that keep only the front: each FrontEngine test runs for both.
class FrontEngine : public ::testing::TestWithParam<Engine> {};

std::string engineName(const ::testing::TestParamInfo<Engine>& info) {
  return info.param == Engine::FrontOnly ? "FrontOnly" : "Wavefront";
}

TEST_P(FrontEngine, SameDistancesAsStoredWindowsInExactAndDefaultModes) {
  // Both engines discard only strictly dominated window parts, so they agree to rounding (the
  // trimming order differs: measured up to 1.5e-11 on the bench bump). Near images are not merged
  // here (the wavefront's full fields do by default: their error is WavefrontEngine's test).
  for (const auto& c : meshes()) {
    for (const double tolerance : {0.0, DistanceSolverOptions{}.saddleAngleTolerance}) {
      const DistanceSolver stored(c.mesh, withEngine(Engine::StoredWindows, tolerance));
      DistanceSolverOptions frontOptions = withEngine(GetParam(), tolerance);
      frontOptions.imageMergeTolerance = 0.0;
      const DistanceSolver front(c.mesh, frontOptions);
      for (const auto& s : sourcesOf(c.mesh)) {
        const auto a = stored.distances(s), b = front.distances(s);
        EXPECT_LT(maxRelativeDifference(b.vertexDistances, a.vertexDistances, 1e-9), 1e-9)
            << c.name << " tolerance " << tolerance << " source face " << s.face << " "
            << s.barycentric.transpose();
        EXPECT_GT(b.windowsCreated, 0) << c.name;
      }
    }
  }
}

TEST_P(FrontEngine, ExactModeMatchesCgal) {
  // The exact mode of the front engine is the polyhedral distance: CGAL's, to rounding (the issue
  // bar is 1e-6 relative). CGAL misplaces sources on edges, so those are moved 1e-10 into the face.
  for (const auto& c : meshes()) {
    const DistanceSolver front(c.mesh, withEngine(GetParam(), 0.0));
    for (auto s : sourcesOf(c.mesh)) {
      if ((s.barycentric.array() > 0.0).count() != 1) {
        for (int i = 0; i < 3; ++i) s.barycentric[i] = std::max(s.barycentric[i], 1e-10);
        s.barycentric /= s.barycentric.sum();
      }
      const auto exact = referenceDistances(c.mesh, s);
      const auto ours = front.distances(s).vertexDistances;
      EXPECT_LT(maxRelativeDifference(ours, exact, 2.0 * front.meanEdgeLength()), 1e-8) << c.name;
    }
  }
}

TEST_P(FrontEngine, HoldsOnlyTheFront) {
  // 20k vertices: the stored engine holds every window it created; the front engine a small part
  // (the front of a field grows as its perimeter, the windows as its area), so its working memory
  // is a fraction of the stored engine's.
  const TriMesh mesh =
      testing::gridMesh(140, 140, 7.0, 7.0, testing::bump(3.5, 3.5, 1.5, 1.5), 0.2);
  const DistanceSolver stored(mesh, withEngine(Engine::StoredWindows));
  const DistanceSolver front(mesh, withEngine(GetParam()));
  const SurfacePoint s = vertexPoint(mesh, 70 * 141 + 3);
  const auto a = stored.distances(s), b = front.distances(s);
  EXPECT_EQ(a.peakWindows, a.windowsCreated);
  EXPECT_LT(b.peakWindows * 10, b.windowsCreated) << b.peakWindows << " of " << b.windowsCreated;
  EXPECT_LT(b.peakBytes * 5, a.peakBytes) << b.peakBytes << " vs " << a.peakBytes;
  EXPECT_GT(b.peakBytes, 0.0);
  if (GetParam() == Engine::FrontOnly) {
    EXPECT_LT(maxRelativeDifference(b.vertexDistances, a.vertexDistances, 1e-9), 1e-9);
    return;
  }
  // The wavefront engine trims against fewer windows (addWavefrontWindow): other window ends, so
  // other bends at skipped saddles (pathBentAt), by default. Its exact mode equals the stored
  // engine's (SameDistancesAsStoredWindowsInExactAndDefaultModes); here its default mode's error
  // against the exact mode is held to the stored engine's. Measured: both 1.41e-6, wavefront
  // against stored 3.2e-7.
  const auto exact =
      DistanceSolver(mesh, withEngine(Engine::StoredWindows, 0.0)).distances(s).vertexDistances;
  const double waveError = maxRelativeDifference(b.vertexDistances, exact, 1e-9);
  const double storedError = maxRelativeDifference(a.vertexDistances, exact, 1e-9);
  std::printf("20k bump, default mode against exact: wavefront %.2e, stored %.2e, between %.2e\n",
              waveError, storedError,
              maxRelativeDifference(b.vertexDistances, a.vertexDistances, 1e-9));
  EXPECT_LE(waveError, 1.1 * storedError);
  EXPECT_GT(storedError, 0.0);
}

TEST_P(FrontEngine, MergesWindowsOfOneImageOnAPlane) {
  // On a plane every window splits at each vertex its rays pass; the stored engine never joins
  // the pieces again (windows ~ n^1.5: an edge r edges from the source holds ~r of them), the
  // front engine merges queued windows of one source image that touch (addFrontWindow), so its
  // count stays ~n. Known answer: the plane's distances are Euclidean.
  auto windowsOn = [engine = GetParam()](int n, long& storedWindows, long& frontWindows) {
    const TriMesh mesh = testing::gridMesh(n, n, 1.0, 1.0, testing::flat, 0.25);
    const DistanceSolver stored(mesh, withEngine(Engine::StoredWindows));
    const DistanceSolver front(mesh, withEngine(engine));
    const int v = (n / 2) * (n + 1) + n / 3;
    const auto a = stored.distancesFromVertex(v), b = front.distancesFromVertex(v);
    const auto p = mesh.point(mesh.vertex_handle(v));
    for (int u = 0; u < static_cast<int>(mesh.n_vertices()); ++u) {
      const double exact = (mesh.point(mesh.vertex_handle(u)) - p).norm();
      ASSERT_NEAR(b.vertexDistances[u], exact, 1e-9) << "n " << n << " vertex " << u;
      ASSERT_NEAR(a.vertexDistances[u], exact, 1e-9) << "n " << n << " vertex " << u;
    }
    storedWindows = a.windowsCreated;
    frontWindows = b.windowsCreated;
  };
  long s40, f40, s80, f80;
  windowsOn(40, s40, f40);
  windowsOn(80, s80, f80);
  std::printf("plane windows stored %ld -> %ld, front %ld -> %ld\n", s40, s80, f40, f80);
  // Measured: stored 30.7k -> 239k (x7.8, the n^1.5 of 4x the vertices), front 6.2k -> 25.6k
  // (x4.1).
  EXPECT_LT(f80 * 5, s80);
  EXPECT_LT(double(f80) / f40, 5.0);
  EXPECT_GT(double(s80) / s40, 6.5);
}

TEST_P(FrontEngine, TargetsDirectedQueriesAndPaths) {
  const TriMesh mesh = testing::gridMesh(20, 20, 2.0, 2.0, testing::bump(1.0, 1.0, 0.6, 0.5), 0.25);
  const DistanceSolver stored(mesh, withEngine(Engine::StoredWindows));
  const DistanceSolver front(mesh, withEngine(GetParam()));
  const SurfacePoint from = facePoint(17, 0.2, 0.3, 0.5);
  std::vector<SurfacePoint> targets;
  for (int f = 5; f < static_cast<int>(mesh.n_faces()); f += 97)
    targets.push_back(facePoint(f, 0.3, 0.3, 0.4));
  const auto a = stored.distances(from, targets), b = front.distances(from, targets);
  const auto directed = front.directedDistances(from, targets);
  for (size_t i = 0; i < targets.size(); ++i) {
    EXPECT_NEAR(b.targetDistances[i], a.targetDistances[i], 1e-12 * a.targetDistances[i])
        << "target " << i;
    EXPECT_NEAR(directed.targetDistances[i],
                stored.directedDistances(from, targets).targetDistances[i],
                1e-12 * a.targetDistances[i]);
    EXPECT_NEAR(front.distance(from, targets[i]), stored.distance(from, targets[i]),
                1e-12 * a.targetDistances[i]);
    // path() traces back through stored windows whatever the engine: the same polyline.
    const auto p = front.path(from, targets[i]), q = stored.path(from, targets[i]);
    EXPECT_EQ(p.length, q.length);
    EXPECT_EQ(p.points.size(), q.points.size());
    EXPECT_NEAR(p.length, a.targetDistances[i], 2e-5 * a.targetDistances[i]);
  }
}

TEST_P(FrontEngine, BatchIsBitIdenticalForAnyThreadCount) {
  const TriMesh mesh = testing::gridMesh(16, 16, 1.0, 1.0, testing::hypar(0.5, 0.5, 0.8), 0.3);
  std::vector<SurfacePoint> sources;
  for (int f = 0; f < static_cast<int>(mesh.n_faces()); f += 29)
    sources.push_back(facePoint(f, 0.2, 0.3, 0.5));
  const std::vector<SurfacePoint> targets = {facePoint(11, 0.3, 0.3, 0.4),
                                             facePoint(301, 0.0, 0.5, 0.5)};
  auto options = [engine = GetParam()](int threads) {
    DistanceSolverOptions o = withEngine(engine);
    o.threads = threads;
    return o;
  };
  const auto one = DistanceSolver(mesh, options(1)).distances(sources, targets);
  const auto two = DistanceSolver(mesh, options(2)).distances(sources, targets);
  const DistanceSolver single(mesh, options(1));
  // A stored-window query on the same thread first: the scratch it leaves must not leak into the
  // front engine's next field.
  const DistanceSolver stored(mesh, withEngine(Engine::StoredWindows));
  for (size_t i = 0; i < sources.size(); ++i) {
    EXPECT_EQ(one[i].vertexDistances, two[i].vertexDistances);
    EXPECT_EQ(one[i].targetDistances, two[i].targetDistances);
    stored.distances(sources[(i + 1) % sources.size()], targets);
    EXPECT_EQ(one[i].vertexDistances, single.distances(sources[i], targets).vertexDistances);
  }
}

// Of the windows a field keeps, how many are beaten everywhere (at 33 points along them) by a path
// through a vertex of their edge's two faces, with the field's final vertex distances: what the
// best vertex-distance filter (Xin-Wang's three tests against the edge's endpoints, the vertex
// ahead and the one behind; VTP's per-triangle pruning) could still discard. Sampling can only
// overcount.
struct FilterCensus {
  long windows = 0, dominated = 0;
};

FilterCensus vertexFilterCensus(const TriMesh& mesh, int source) {
  const DistanceSolverOptions options;
  const detail::MeshTables t = detail::buildTables(mesh, options);
  detail::Propagation state;
  detail::propagate(t, options, vertexPoint(mesh, source), {}, state, false, /*storeWindows=*/true);
  const auto& d = state.vertexDistance;
  FilterCensus census;
  for (const detail::Window& w : state.windows) {
    const auto& e = t.he[w.halfedge];
    const auto& back = t.he[t.twin(w.halfedge)];
    // The four vertices in the frame of w's edge: its endpoints, the vertex ahead (the face w
    // enters) and the vertex behind (the face across, mirrored from its own frame).
    const int vertex[4] = {e.fromVertex, e.toVertex, e.oppositeVertex, back.oppositeVertex};
    const double vx[4] = {0.0, e.length, e.oppositeX, e.length - back.oppositeX};
    const double vy[4] = {0.0, 0.0, e.oppositeY, -back.oppositeY};
    bool dominated = true;
    for (int i = 0; i <= 32 && dominated; ++i) {
      const double x = w.b0 + (w.b1 - w.b0) * i / 32.0;
      const double own = w.sigma + std::hypot(x - w.sx, w.sy);
      double best = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 4; ++k) {
        if (vertex[k] >= 0) best = std::min(best, d[vertex[k]] + std::hypot(x - vx[k], vy[k]));
      }
      dominated = own > best + 1e-12 * e.length;
    }
    ++census.windows;
    census.dominated += dominated ? 1 : 0;
  }
  return census;
}

TEST(WindowPruning, VertexDistanceFiltersWouldFindAlmostNothingLeftToDrop) {
  // Issue 19 asked for VTP-style constant-time vertex filters. With the trimming against the
  // edge's other windows (window_propagation.cpp) they have nothing left to do: even with the
  // final distances, which no filter has while the front runs, almost no kept window is beaten
  // everywhere by a vertex path. Measured (stored engine, middle vertex source): sphere cap R 10 /
  // extent 8 at 4.6k vertices 0 of 191k; bench bump 4.4k vertices 16 of 159k (and, instrumented,
  // the front engine on the 18k-vertex cap: 0 of 1.02M). The cap's ~55 windows per vertex (most
  // 1-10 % of their edge wide, ~19 per edge) are its exact field's: a faster engine has to make
  // each window cheaper, not fewer. Fails if trimming regresses: switched off, the cap keeps 118
  // dominated windows of 227k and the bump 371 of 180k.
  const TriMesh cap = samples::generateSample("sphere", {}, 0.2567);
  const FilterCensus c = vertexFilterCensus(cap, static_cast<int>(cap.n_vertices()) / 2);
  const TriMesh bump = samples::generateSample("bump", {}, 0.1699);
  const FilterCensus b = vertexFilterCensus(bump, static_cast<int>(bump.n_vertices()) / 2);
  std::printf("vertex-filter census: cap %ld of %ld windows dominated, bump %ld of %ld\n",
              c.dominated, c.windows, b.dominated, b.windows);
  EXPECT_GT(c.windows, 100000);
  EXPECT_GT(b.windows, 100000);
  EXPECT_LE(c.dominated * 10000, c.windows);
  EXPECT_LE(b.dominated * 2000, b.windows);
}

INSTANTIATE_TEST_SUITE_P(Engines, FrontEngine,
                         ::testing::Values(Engine::FrontOnly, Engine::Wavefront), engineName);

TEST(Engines, AnUnknownEngineIsRefusedByName) {
  DistanceSolverOptions o;
  o.engine = static_cast<Engine>(7);
  try {
    DistanceSolver(testing::gridMesh(2, 2, 1.0, 1.0, testing::flat), o);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("DistanceSolverOptions.engine"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace egg::geodesic
