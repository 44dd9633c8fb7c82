#pragma once
// A hand-made 3 x 3 grid for the assembly tests: exact connections, sides and anchors.
#include "core/egg/grid.hpp"

namespace egg::testing {

// Three u members crossing three v members on the plane z = 0.1 x; the middle connection (1, 1)
// is the only one not on a side.
inline EggGrid threeByThree() {
  EggGrid grid;
  for (int k = 0; k < 3; ++k) {
    GridMember u;
    u.family = Family::U;
    u.index = k;
    u.boundary = k != 1;
    u.spatial = {{0, double(k), 0}, {2, double(k), 0.2}};
    u.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    u.planarLength = u.spatialLength = (u.spatial[1] - u.spatial[0]).norm();
    grid.u.push_back(u);
    GridMember v = u;
    v.family = Family::V;
    v.spatial = {{double(k), 0, 0.1 * k}, {double(k), 2, 0.1 * k}};
    v.planarLength = v.spatialLength = 2.0;
    grid.v.push_back(v);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      GridConnection c;
      c.memberU = i;
      c.memberV = j;
      c.spatial = Eigen::Vector3d(j, i, 0.1 * j);
      c.normal = Eigen::Vector3d(-0.1, 0, 1) * 3.0;  // not unit on purpose
      c.sBarU = j * grid.u[i].planarLength / 2.0;
      c.sBarV = i * 1.0;
      c.onBoundary = i != 1 || j != 1;
      grid.connections.push_back(c);
    }
  }
  grid.anchors.push_back({0, "corner"});
  grid.anchors.push_back({8, "corner"});
  return grid;
}

}  // namespace egg::testing
