#include "export/glb_writer.hpp"

#include "core/errors.hpp"
#include "export/gltf_buffer.hpp"

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <fmt/core.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace egg::exporter {

namespace {

using nlohmann::json;

tinygltf::Value toValue(const json& j) {
  switch (j.type()) {
    case json::value_t::boolean: return tinygltf::Value(j.get<bool>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return tinygltf::Value(j.get<int>());
    case json::value_t::number_float: return tinygltf::Value(j.get<double>());
    case json::value_t::string: return tinygltf::Value(j.get<std::string>());
    case json::value_t::array: {
      tinygltf::Value::Array a;
      for (const auto& e : j) a.push_back(toValue(e));
      return tinygltf::Value(std::move(a));
    }
    case json::value_t::object: {
      tinygltf::Value::Object o;
      for (const auto& [k, v] : j.items()) o[k] = toValue(v);
      return tinygltf::Value(std::move(o));
    }
    default: return tinygltf::Value();
  }
}

// Builds the single buffer, its views and accessors as meshes are added.
class GltfBuilder {
 public:
  GltfBuilder() {
    gltf_.asset.version = "2.0";
    gltf_.asset.generator = "eggshell (TinyGLTF)";
    gltf_.buffers.emplace_back();
  }

  int material(const std::string& name, std::array<double, 4> colour, bool blend,
               bool doubleSided) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {colour[0], colour[1], colour[2], colour[3]};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 0.8;
    m.alphaMode = blend ? "BLEND" : "OPAQUE";
    m.doubleSided = doubleSided;
    gltf_.materials.push_back(m);
    return static_cast<int>(gltf_.materials.size()) - 1;
  }

  // A triangle mesh with optional per-vertex normals and colours; returns the mesh index.
  int mesh(const std::string& name, const ModelMesh& m, int material,
           const std::vector<Eigen::Vector3d>* normals = nullptr,
           const std::vector<Eigen::Vector3d>* colours = nullptr) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] = vec3(m.vertices, true);
    if (normals) prim.attributes["NORMAL"] = vec3(*normals, false);
    if (colours) prim.attributes["COLOR_0"] = vec3(*colours, false);
    prim.indices = indices(m.triangles);
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(prim));
    gltf_.meshes.push_back(std::move(mesh));
    return static_cast<int>(gltf_.meshes.size()) - 1;
  }

  int node(const std::string& name, int meshIndex, const json& extras) {
    tinygltf::Node n;
    n.name = name;
    n.mesh = meshIndex;
    if (!extras.is_null()) n.extras = toValue(extras);
    gltf_.nodes.push_back(std::move(n));
    return static_cast<int>(gltf_.nodes.size()) - 1;
  }
  void child(int parent, int kid) { gltf_.nodes[parent].children.push_back(kid); }
  tinygltf::Node& at(int node) { return gltf_.nodes[node]; }

  std::string glb(int root) {
    tinygltf::Scene scene;
    scene.name = gltf_.nodes[root].name;
    scene.nodes.push_back(root);
    gltf_.scenes.push_back(scene);
    gltf_.defaultScene = 0;
    auto& data = gltf_.buffers[0].data;
    data.resize((data.size() + 3) / 4 * 4, 0);
    if (data.empty()) gltf_.buffers.clear();
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    if (!writer.WriteGltfSceneToStream(&gltf_, out, false, true))
      throw Error("glTF: TinyGLTF could not serialise the model");
    return out.str();
  }

 private:
  int view(const void* bytes, size_t size, int target) {
    return appendBufferView(gltf_, bytes, size, target);
  }

  int vec3(const std::vector<Eigen::Vector3d>& points, bool bounds) {
    std::vector<float> flat;
    flat.reserve(points.size() * 3);
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()),
        hi(3, -std::numeric_limits<double>::infinity());
    for (const auto& p : points)
      for (int i = 0; i < 3; ++i) {
        const float f = static_cast<float>(p[i]);
        flat.push_back(f);
        lo[i] = std::min(lo[i], static_cast<double>(f));
        hi[i] = std::max(hi[i], static_cast<double>(f));
      }
    tinygltf::Accessor a;
    a.bufferView = view(flat.data(), flat.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = points.size();
    if (bounds) a.minValues = lo, a.maxValues = hi;  // required for POSITION
    gltf_.accessors.push_back(a);
    return static_cast<int>(gltf_.accessors.size()) - 1;
  }

  int indices(const std::vector<Eigen::Vector3i>& triangles) {
    std::vector<uint32_t> flat;
    flat.reserve(triangles.size() * 3);
    for (const auto& t : triangles)
      for (int i = 0; i < 3; ++i) flat.push_back(static_cast<uint32_t>(t[i]));
    tinygltf::Accessor a;
    a.bufferView =
        view(flat.data(), flat.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = flat.size();
    gltf_.accessors.push_back(a);
    return static_cast<int>(gltf_.accessors.size()) - 1;
  }

  tinygltf::Model gltf_;
};

ModelMesh merged(const std::vector<ModelMesh>& parts) {
  ModelMesh all;
  for (const auto& p : parts) {
    const int base = static_cast<int>(all.vertices.size());
    all.vertices.insert(all.vertices.end(), p.vertices.begin(), p.vertices.end());
    for (const auto& t : p.triangles) all.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  }
  return all;
}

// The root: site coordinates (z up) turned into glTF's y-up frame.
int rootNode(GltfBuilder& b, const StructureModel& model, const std::string& title) {
  const int root = b.node(title + " " + model.name, -1,
                          {{"units", "m"},
                           {"site_up_axis", "z"},
                           {"note",
                            "meshes are in site coordinates (z up); this node turns them "
                            "to glTF's y up"},
                           {"centreline_source", toString(model.source)},
                           {"lamella_width_m", model.widthM},
                           {"lamella_thickness_m", model.thicknessM},
                           {"deviation_colour_scale_m", json::array({0.0, model.maxDeviationM()})},
                           {"lamellas", model.lamellas.size()},
                           {"bolts", model.bolts.size()},
                           {"supports", model.supports.size()}});
  const double h = std::sqrt(0.5);
  b.at(root).rotation = {-h, 0.0, 0.0, h};
  return root;
}

void addSupports(GltfBuilder& b, int root, const StructureModel& model) {
  const int material = b.material("support", {0.62, 0.60, 0.56, 1.0}, false, false);
  json extras{{"supports", model.supports.size()}};
  if (!model.supportsNote.empty()) extras["note"] = model.supportsNote;
  const int group = b.node("supports", -1, extras);
  b.child(root, group);
  for (const auto& s : model.supports) {
    json info{{"id", s.id},
              {"patch", s.patch},
              {"connection", s.connection},
              {"kind", s.kind},
              {"position_m", {s.position.x(), s.position.y(), s.position.z()}}};
    const int mesh = s.solid.triangles.empty() ? -1 : b.mesh(s.id, s.solid, material);
    b.child(group, b.node(s.id, mesh, info));
  }
}

}  // namespace

std::string glbBytes(const StructureModel& model, const GlbContents& contents) {
  model.validate();
  GltfBuilder b;
  const int root = rootNode(b, model, "eggshell");
  if (contents.surface && !model.surface.triangles.empty()) {
    const int material = b.material("design surface", {0.80, 0.80, 0.82, 0.35}, true, true);
    b.child(root,
            b.node("surface", b.mesh("surface", model.surface, material), {{"role", "design"}}));
  }
  const int lamellaMaterial = b.material("lamella", {1.0, 1.0, 1.0, 1.0}, false, false);
  const int boltMaterial = b.material("bolt", {0.25, 0.25, 0.27, 1.0}, false, false);
  const double maxDeviation = model.maxDeviationM();
  std::map<int, int> patchNode;
  std::map<std::pair<int, char>, int> familyNode;
  for (int p : model.patches) {
    patchNode[p] = b.node(fmt::format("P{}", p), -1, {{"patch", p}});
    b.child(root, patchNode[p]);
  }
  if (contents.lamellas)
    for (const auto& l : model.lamellas) {
      const auto key = std::make_pair(l.patch, l.family);
      if (!familyNode.count(key)) {
        familyNode[key] = b.node(fmt::format("P{}-{}", l.patch, l.family), -1,
                                 {{"patch", l.patch}, {"family", std::string(1, l.family)}});
        b.child(patchNode.at(l.patch), familyNode[key]);
      }
      const Ribbon r = ribbonOf(l, model.widthM, model.thicknessM);
      std::vector<Eigen::Vector3d> colours;
      colours.reserve(r.station.size());
      for (int s : r.station) colours.push_back(deviationColour(l.deviationM[s], maxDeviation));
      double worst = 0.0;
      for (double d : l.deviationM) worst = std::max(worst, d);
      json extras{{"id", l.id},
                  {"patch", l.patch},
                  {"family", std::string(1, l.family)},
                  {"index", l.index},
                  {"boundary", l.boundary},
                  {"layer", l.layer},
                  {"length_m", l.lengthM},
                  {"spatial_length_m", l.spatialLengthM},
                  {"max_deviation_m", worst},
                  {"sheet", l.sheet}};
      const int mesh = b.mesh(l.id, r.mesh, lamellaMaterial, &r.normals, &colours);
      b.child(familyNode[key], b.node(l.id, mesh, extras));
    }
  if (contents.bolts) {
    std::map<int, std::vector<const ModelBolt*>> byPatch;
    for (const auto& bolt : model.bolts) byPatch[bolt.patch].push_back(&bolt);
    for (const auto& [patch, bolts] : byPatch) {
      std::vector<ModelMesh> solids;
      json ids = json::array();
      for (const ModelBolt* bolt : bolts) {
        solids.push_back(boltSolid(*bolt, model.boltDiameterM, 2.0 * model.thicknessM));
        ids.push_back(bolt->id);
      }
      const std::string name = fmt::format("P{}-bolts", patch);
      const int node = b.node(name, b.mesh(name, merged(solids), boltMaterial),
                              {{"patch", patch}, {"count", bolts.size()}, {"ids", ids}});
      if (!patchNode.count(patch))
        throw InvalidInput(fmt::format("bolt of unknown patch {}", patch));
      b.child(patchNode[patch], node);
    }
  }
  if (contents.supports) addSupports(b, root, model);
  return b.glb(root);
}

std::string supportsGlbBytes(const StructureModel& model) {
  model.validate();
  GltfBuilder b;
  const int root = rootNode(b, model, "eggshell supports");
  addSupports(b, root, model);
  return b.glb(root);
}

}  // namespace egg::exporter
