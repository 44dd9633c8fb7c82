#pragma once
// What the assembly drawings (assembly_drawings.hpp) need of each patch, copied from its grid when
// fabricate() runs: members in the plane and deployed, connections with their notch directions.
#include "fabrication/lamella_plan.hpp"
#include "fabrication/options.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace egg::fabrication {

// The patch geometry the drawings need, copied from the grids when fabricate() runs.
struct AssemblyMember {
  std::string id;  // the lamella that carries it ("P0-U3"; a shared side: the other patch's id)
  bool isU = true;
  Eigen::Vector2d planarStart = Eigen::Vector2d::Zero(), planarEnd = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector3d> deployed;  // the simulated centreline, else the traced member (m)
};
struct AssemblyConnection {
  std::string id;  // "P0-C2-3"
  Eigen::Vector2d planar = Eigen::Vector2d::Zero();
  Eigen::Vector3d spatial = Eigen::Vector3d::Zero();
  Eigen::Vector2d slideU = Eigen::Vector2d::Zero(), slideV = Eigen::Vector2d::Zero();  // plane, m
};
struct AssemblyPatch {
  int patchId = 0;
  std::vector<AssemblyMember> members;  // u then v
  std::vector<AssemblyConnection> connections;
  std::vector<int> boltedTo;  // FabricationPatch::boltedTo (a generalised patch's ring beam)
};

// Copies what the drawings need from the patches (lamella ids as `lamellae` name them).
std::vector<AssemblyPatch> assemblyPatches(const std::vector<FabricationPatch>& patches,
                                           const std::vector<LamellaPlan>& lamellae,
                                           const std::vector<SharedBoundary>& shared,
                                           double minNotchM);

}  // namespace egg::fabrication
