#pragma once
// The deployment as an animation (issue 42): glTF binary with one frame per step of each patch's
// path, every frame the lamellas' contact lines at that step. Frames are nodes shown one at a time
// by a STEP scale animation (glTF has no visibility channel), 10 s for the whole path (t = 0..1).
// Site coordinates, z up, turned to glTF's y up by the root node, as in model.glb.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace egg::exporter {

struct DeploymentFrame {
  double t = 0.0;                                      // path parameter, 0..1, increasing
  std::vector<std::vector<Eigen::Vector3d>> lamellas;  // polylines (m)
};

struct DeploymentAnimation {
  std::string name;  // e.g. "P3"
  std::vector<DeploymentFrame> frames;
};

// Throws InvalidInput for an empty animation, a frame with no line or decreasing t.
std::string deploymentGlbBytes(const std::vector<DeploymentAnimation>& patches);

}  // namespace egg::exporter
