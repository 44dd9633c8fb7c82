#include "export/mesh_writers.hpp"

#include "core/errors.hpp"
#include "fabrication/supports.hpp"

#include <fmt/format.h>

#include <map>

namespace egg::exporter {

namespace {

// One OBJ object of triangles; `next` is the 1-based index of the object's first vertex.
void objMesh(std::string& out, const std::string& name, const ModelMesh& mesh, int& next) {
  fmt::format_to(std::back_inserter(out), "o {0}\ng {0}\n", name);
  for (const auto& v : mesh.vertices)
    fmt::format_to(std::back_inserter(out), "v {:.6f} {:.6f} {:.6f}\n", v.x(), v.y(), v.z());
  for (const auto& t : mesh.triangles)
    fmt::format_to(std::back_inserter(out), "f {} {} {}\n", next + t[0], next + t[1], next + t[2]);
  next += static_cast<int>(mesh.vertices.size());
}

}  // namespace

std::string modelObj(const StructureModel& model) {
  model.validate();
  std::string out = fmt::format(
      "# eggshell {}: the whole structure in site coordinates (metres, z up)\n"
      "# lamellas {} x {} m along their deployed centrelines ({}); one object per lamella, per "
      "patch's bolts and per support\n",
      model.name, model.widthM, model.thicknessM, toString(model.source));
  int next = 1;
  if (!model.surface.triangles.empty()) objMesh(out, "surface", model.surface, next);
  for (const auto& l : model.lamellas)
    objMesh(out, l.id, ribbonOf(l, model.widthM, model.thicknessM).mesh, next);
  for (const auto& [patch, mesh] : boltMeshesByPatch(model))
    objMesh(out, fmt::format("P{}-bolts", patch), mesh, next);
  for (const auto& s : model.supports)
    if (!s.solid.triangles.empty()) objMesh(out, s.id, s.solid, next);
  return out;
}

std::string supportsStl(const StructureModel& model) {
  model.validate();
  fabrication::TriangleMesh all;
  for (const auto& s : model.supports) {
    const int base = static_cast<int>(all.vertices.size());
    all.vertices.insert(all.vertices.end(), s.solid.vertices.begin(), s.solid.vertices.end());
    for (const auto& t : s.solid.triangles)
      all.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  }
  if (all.triangles.empty())
    throw InvalidInput("model " + model.name + ": no support block to write");
  return fabrication::toBinaryStl(
      all, fmt::format("eggshell {} supports, site coordinates, metres", model.name));
}

}  // namespace egg::exporter
