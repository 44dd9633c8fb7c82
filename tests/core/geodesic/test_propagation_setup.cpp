// The per-query setup of the propagation (propagation_setup.cpp) with known answers: the counted
// working memory of a field, the scratch a thread reuses across engines and meshes, and a source
// on an edge seeded from both faces, in both engines.
#include "core/geodesic/window_propagation.hpp"

#include "core/geodesic/distance_solver.hpp"
#include "tests/core/geodesic/geodesic_test_meshes.hpp"

#include <gtest/gtest.h>

namespace egg::geodesic {
namespace {

using Engine = DistanceSolverOptions::Engine;
using testing::facePoint;

DistanceSolverOptions setupWithEngine(Engine engine) {
  DistanceSolverOptions o;
  o.engine = engine;
  return o;
}

TEST(PropagationSetup, PeakBytesCountTheWindowsHeldAndTheMeshArrays) {
  const TriMesh mesh = testing::gridMesh(30, 30, 3.0, 3.0, testing::bump(1.5, 1.5, 0.6, 0.7), 0.2);
  const DistanceSolver stored(mesh, setupWithEngine(Engine::StoredWindows));
  const DistanceSolver front(mesh, setupWithEngine(Engine::FrontOnly));
  const SurfacePoint s = vertexPoint(mesh, 15 * 31 + 4);
  const auto a = stored.distances(s), b = front.distances(s);
  const double nv = static_cast<double>(mesh.n_vertices()),
               nh = 2.0 * static_cast<double>(mesh.n_edges());
  // At least the windows (56 bytes each) and the per-vertex distances and per-halfedge one-split
  // pairs; the stored engine's windows are all it created.
  const double floor = nv * sizeof(double) + nh * 2 * sizeof(double);
  EXPECT_GE(a.peakBytes, floor + static_cast<double>(a.windowsCreated) * sizeof(detail::Window));
  EXPECT_GE(b.peakBytes, floor + static_cast<double>(b.peakWindows) * sizeof(detail::Window));
  EXPECT_LT(b.peakBytes, a.peakBytes);
  // A field's count does not depend on what the thread computed before (a larger field first).
  const TriMesh big = testing::gridMesh(60, 60, 3.0, 3.0, testing::flat);
  DistanceSolver(big, setupWithEngine(Engine::FrontOnly)).distances(vertexPoint(big, 5));
  EXPECT_EQ(front.distances(s).peakBytes, b.peakBytes);
}

TEST(PropagationSetup, ScratchReusedAcrossEnginesAndMeshesGivesTheFreshFields) {
  const TriMesh one = testing::gridMesh(12, 12, 1.0, 1.0, testing::hypar(0.5, 0.5, 0.8), 0.3);
  const TriMesh two = testing::sphereMesh(1.0, 12, 20);
  const SurfacePoint s1 = facePoint(40, 0.2, 0.3, 0.5), s2 = facePoint(100, 0.6, 0.2, 0.2);
  const std::vector<SurfacePoint> targets = {facePoint(7, 0.3, 0.3, 0.4)};
  const DistanceSolver frontOne(one, setupWithEngine(Engine::FrontOnly)),
      storedTwo(two, setupWithEngine(Engine::StoredWindows));
  const DistanceSolver frontTwo(two, setupWithEngine(Engine::FrontOnly));
  const auto first = frontOne.distances(s1, targets);
  const auto second = storedTwo.distances(s2, targets);
  const auto third = frontTwo.distances(s2, targets);
  EXPECT_EQ(frontOne.distances(s1, targets).vertexDistances, first.vertexDistances);
  EXPECT_EQ(frontOne.distances(s1, targets).targetDistances, first.targetDistances);
  EXPECT_EQ(storedTwo.distances(s2, targets).vertexDistances, second.vertexDistances);
  EXPECT_EQ(frontTwo.distances(s2, targets).vertexDistances, third.vertexDistances);
  for (size_t v = 0; v < third.vertexDistances.size(); ++v) {
    EXPECT_NEAR(third.vertexDistances[v], second.vertexDistances[v], 1e-12) << "vertex " << v;
  }
}

TEST(PropagationSetup, AnEdgeSourceIsTheSameGivenInEitherFace) {
  const TriMesh mesh = testing::gridMesh(12, 12, 1.0, 1.0, testing::bump(0.4, 0.6, 0.4, 0.2), 0.25);
  const auto eh = mesh.edge_handle(100);
  ASSERT_FALSE(mesh.is_boundary(eh));
  const auto h0 = mesh.halfedge_handle(eh, 0), h1 = mesh.halfedge_handle(eh, 1);
  auto onEdge = [&](TriMesh::HalfedgeHandle h) {
    const int f = mesh.face_handle(h).idx();
    const auto ids = faceVertices(mesh, f);
    SurfacePoint p;
    p.face = f;
    for (int i = 0; i < 3; ++i) {
      if (ids[i] == mesh.from_vertex_handle(h0).idx()) p.barycentric[i] = 0.3;
      if (ids[i] == mesh.to_vertex_handle(h0).idx()) p.barycentric[i] = 0.7;
    }
    return p;
  };
  for (const Engine engine : {Engine::StoredWindows, Engine::FrontOnly}) {
    const DistanceSolver solver(mesh, setupWithEngine(engine));
    const auto a = solver.distances(onEdge(h0)), b = solver.distances(onEdge(h1));
    for (size_t v = 0; v < a.vertexDistances.size(); ++v) {
      EXPECT_NEAR(a.vertexDistances[v], b.vertexDistances[v], 1e-12) << "vertex " << v;
    }
  }
}

}  // namespace
}  // namespace egg::geodesic
