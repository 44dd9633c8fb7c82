#include "core/egg/map_proxy.hpp"

#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace egg {
namespace {

Patch bumpPatch(double edge) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 1.0}, {"sigma", 1.5}, {"length", 8.0}, {"width", 8.0}}, edge);
  return makePatch(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}});
}

TEST(MapProxy, KeepsTheCornersAndItsBoundaryIsASubPolylineOfTheFineSides) {
  const Patch fine = bumpPatch(0.15);
  ASSERT_GT(fine.mesh.n_vertices(), 1500u);
  const MapProxy proxy = makeMapProxy(fine, 300);
  const Patch& p = proxy.patch;
  EXPECT_LE(p.mesh.n_vertices(), 300u);
  EXPECT_GE(p.mesh.n_vertices(), 200u);
  ASSERT_EQ(proxy.fineVertex.size(), p.mesh.n_vertices());
  // Every proxy vertex is the fine vertex it came from, at the same position.
  for (auto vh : p.mesh.vertices())
    EXPECT_EQ(toEigen(p.mesh.point(vh)),
              toEigen(fine.mesh.point(TriMesh::VertexHandle(proxy.fineVertex[vh.idx()]))));
  size_t chainVertices = 0;
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(proxy.fineVertex[p.cornerVertices[k]], fine.cornerVertices[k]);
    EXPECT_EQ(p.sides[k].front(), p.cornerVertices[k]);
    EXPECT_EQ(p.sides[k].back(), p.cornerVertices[(k + 1) % 4]);
    ASSERT_EQ(p.sides[k].size(), p.sideArcLength[k].size());
    EXPECT_LT(p.sides[k].size(), fine.sides[k].size());  // the sides were decimated too
    EXPECT_EQ(p.sideArcLength[k].front(), 0.0);
    EXPECT_EQ(p.sideArcLength[k].back(), fine.sideArcLength[k].back());
    EXPECT_EQ(p.sideLengths[k], fine.sideLengths[k]);
    chainVertices += p.sides[k].size() - 1;
    for (size_t i = 0; i < p.sides[k].size(); ++i) {
      // On the fine boundary polyline, at its fine arc length: distance 0 to rounding.
      const Eigen::Vector3d onFine = position(fine.mesh, sidePoint(fine, k, p.sideArcLength[k][i]));
      EXPECT_LT((toEigen(p.mesh.point(TriMesh::VertexHandle(p.sides[k][i]))) - onFine).norm(),
                1e-12)
          << k << " " << i;
      if (i > 0) {
        EXPECT_GT(p.sideArcLength[k][i], p.sideArcLength[k][i - 1]);
      }
    }
    // A boundary sample maps to the point at the same fine arc length on the proxy's chord:
    // at a proxy side vertex exactly, at the corners too.
    const double s = p.sideArcLength[k][p.sides[k].size() / 2];
    EXPECT_LT(
        (position(p.mesh, sidePoint(p, k, s)) - position(fine.mesh, sidePoint(fine, k, s))).norm(),
        1e-12);
  }
  // The side chains are the whole proxy boundary.
  size_t boundary = 0;
  for (auto vh : p.mesh.vertices()) boundary += p.mesh.is_boundary(vh) ? 1 : 0;
  EXPECT_EQ(boundary, chainVertices);
  EXPECT_NEAR(p.area, fine.area, 1e-3 * fine.area);  // a faithful copy of the surface
}

TEST(MapProxy, TooFewVerticesAreInvalidInputNamingTheSceneKey) {
  const Patch fine = bumpPatch(0.5);
  try {
    makeMapProxy(fine, 5);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("grid.map_proxy_vertices"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace egg
