#include "export/deployment_glb.hpp"

#include "core/errors.hpp"
#include "export/gltf_buffer.hpp"

#include <tiny_gltf.h>

#include <limits>
#include <sstream>

namespace egg::exporter {

namespace {

constexpr double kSecondsPerPath = 10.0;

class AnimationBuilder {
 public:
  AnimationBuilder() {
    gltf_.asset.version = "2.0";
    gltf_.asset.generator = "eggshell (TinyGLTF)";
    gltf_.buffers.emplace_back();
    tinygltf::Material m;
    m.name = "lamella";
    m.pbrMetallicRoughness.baseColorFactor = {0.55, 0.35, 0.15, 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    gltf_.materials.push_back(m);
  }

  int lines(const std::vector<std::vector<Eigen::Vector3d>>& polylines) {
    std::vector<float> points;
    std::vector<uint32_t> indices;
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()),
        hi(3, -std::numeric_limits<double>::infinity());
    for (const auto& line : polylines) {
      for (size_t i = 0; i < line.size(); ++i) {
        const uint32_t index = static_cast<uint32_t>(points.size() / 3);
        for (int c = 0; c < 3; ++c) {
          const float f = static_cast<float>(line[i][c]);
          points.push_back(f);
          lo[c] = std::min(lo[c], static_cast<double>(f));
          hi[c] = std::max(hi[c], static_cast<double>(f));
        }
        if (i > 0) indices.insert(indices.end(), {index - 1, index});
      }
    }
    if (indices.empty()) throw InvalidInput("deployment.glb: a frame has no lamella segment");
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_LINE;
    prim.material = 0;
    prim.attributes["POSITION"] =
        accessor(points.data(), points.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT,
                 TINYGLTF_TYPE_VEC3, points.size() / 3, TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
    prim.indices = accessor(indices.data(), indices.size() * sizeof(uint32_t),
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                            indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, {}, {});
    tinygltf::Mesh mesh;
    mesh.primitives.push_back(std::move(prim));
    gltf_.meshes.push_back(std::move(mesh));
    return static_cast<int>(gltf_.meshes.size()) - 1;
  }

  // Animation data (no buffer-view target: glTF forbids one for animation samplers).
  int floats(const std::vector<float>& values, int type, size_t count, bool bounds) {
    std::vector<double> lo, hi;
    if (bounds) {
      lo = {values.front()};
      hi = {values.back()};
    }
    return accessor(values.data(), values.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT,
                    type, count, 0, lo, hi);
  }

  tinygltf::Model gltf_;

 private:
  int accessor(const void* bytes, size_t size, int component, int type, size_t count, int target,
               const std::vector<double>& lo, const std::vector<double>& hi) {
    tinygltf::Accessor a;
    a.bufferView = appendBufferView(gltf_, bytes, size, target);
    a.componentType = component;
    a.type = type;
    a.count = count;
    a.minValues = lo;
    a.maxValues = hi;
    gltf_.accessors.push_back(a);
    return static_cast<int>(gltf_.accessors.size()) - 1;
  }
};

}  // namespace

std::string deploymentGlbBytes(const std::vector<DeploymentAnimation>& patches) {
  if (patches.empty()) throw InvalidInput("deployment.glb: no patch to animate");
  AnimationBuilder b;
  tinygltf::Node root;
  root.name = "eggshell deployment";
  root.rotation = {-0.7071067811865476, 0.0, 0.0, 0.7071067811865476};  // z up -> y up
  b.gltf_.nodes.push_back(root);
  tinygltf::Animation animation;
  animation.name = "deployment";
  for (const DeploymentAnimation& patch : patches) {
    if (patch.frames.empty())
      throw InvalidInput("deployment.glb: patch " + patch.name + " has no frame");
    std::vector<float> times;
    for (const DeploymentFrame& f : patch.frames) {
      if (!times.empty() && !(kSecondsPerPath * f.t > times.back()))
        throw InvalidInput("deployment.glb: patch " + patch.name + ": t must increase");
      times.push_back(static_cast<float>(kSecondsPerPath * f.t));
    }
    const int input = b.floats(times, TINYGLTF_TYPE_SCALAR, times.size(), true);
    for (size_t k = 0; k < patch.frames.size(); ++k) {
      tinygltf::Node node;
      node.name = patch.name + " t=" + std::to_string(patch.frames[k].t);
      node.mesh = b.lines(patch.frames[k].lamellas);
      if (k > 0) node.scale = {0.0, 0.0, 0.0};  // the first frame shows without animation
      b.gltf_.nodes.push_back(node);
      const int nodeIndex = static_cast<int>(b.gltf_.nodes.size()) - 1;
      b.gltf_.nodes[0].children.push_back(nodeIndex);
      std::vector<float> scales;
      for (size_t j = 0; j < patch.frames.size(); ++j) {
        const float s = j == k ? 1.0f : 0.0f;
        scales.insert(scales.end(), {s, s, s});
      }
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.output = b.floats(scales, TINYGLTF_TYPE_VEC3, patch.frames.size(), false);
      sampler.interpolation = "STEP";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel channel;
      channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
      channel.target_node = nodeIndex;
      channel.target_path = "scale";
      animation.channels.push_back(channel);
    }
  }
  b.gltf_.animations.push_back(animation);
  tinygltf::Scene scene;
  scene.name = "deployment";
  scene.nodes.push_back(0);
  b.gltf_.scenes.push_back(scene);
  b.gltf_.defaultScene = 0;
  auto& data = b.gltf_.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&b.gltf_, out, false, true))
    throw Error("glTF: TinyGLTF could not serialise the deployment");
  return out.str();
}

}  // namespace egg::exporter
