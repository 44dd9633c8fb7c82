#include "pipeline/model_stage.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/rods/surface_distance.hpp"
#include "core/timing.hpp"
#include "export/glb_writer.hpp"
#include "export/mesh_writers.hpp"
#include "export/rhino_writer.hpp"

#include <fmt/core.h>

#include <map>

namespace egg::pipeline {

using exporter::CentrelineSource;
using nlohmann::json;

namespace {

// The point at rest arc length s (0..restLength) of a deployed centreline: its vertices are
// spread along the rod as cut, so the fraction of the deployed arc length is used.
Eigen::Vector3d pointAt(const std::vector<Eigen::Vector3d>& line, double s, double restLength) {
  std::vector<double> arc{0.0};
  for (size_t i = 1; i < line.size(); ++i)
    arc.push_back(arc.back() + (line[i] - line[i - 1]).norm());
  const double target = std::clamp(s / restLength, 0.0, 1.0) * arc.back();
  const size_t k = std::upper_bound(arc.begin(), arc.end(), target) - arc.begin();
  if (k == 0) return line.front();
  if (k >= line.size()) return line.back();
  const double span = arc[k] - arc[k - 1];
  const double f = span > 0.0 ? (target - arc[k - 1]) / span : 0.0;
  return line[k - 1] + f * (line[k] - line[k - 1]);
}

// The deployed run each patch's lamellas come from, with the offsets of its rods and bolts in it.
struct DeployedSource {
  const rods::SimulationRun* run = nullptr;
  int firstRod = 0, firstBolt = 0;
};

// Every patch with a grid: the quads in id order, then the generalised patches (issue 41) in piece
// order, as the joined network holds them (pipeline/joined_simulation.cpp).
struct ModelGrid {
  int id = 0;
  const EggGrid* grid = nullptr;
  const rods::SimulationRun* own = nullptr;  // its own deployment (patch by patch), if any
};

std::vector<ModelGrid> modelGrids(const RunState& state) {
  std::vector<ModelGrid> out;
  for (const auto& p : state.patches)
    if (p.egg)
      out.push_back({p.id, &p.egg->grid, p.simulation ? &p.simulation->deployed : nullptr});
  for (const auto& g : state.generalised) {
    const auto& simulation = state.infillSimulations[g.piece];
    out.push_back({g.patchId, &g.grid, simulation ? &simulation->deployed : nullptr});
  }
  return out;
}

std::map<int, DeployedSource> deployedSources(const RunState& state,
                                              const std::vector<ModelGrid>& grids,
                                              CentrelineSource& source) {
  std::map<int, DeployedSource> out;
  if (state.joined) {
    // The joined network holds every patch with a grid in that order, u then v rods, its bolts
    // first, then the joins (pipeline/joined_simulation.cpp, core/rods/joined_network.cpp).
    int rods = 0, bolts = 0;
    for (const auto& g : grids) {
      out[g.id] = {&*state.joined, rods, bolts};
      rods += static_cast<int>(g.grid->u.size() + g.grid->v.size());
      bolts += static_cast<int>(g.grid->connections.size());
    }
    if (static_cast<int>(state.joined->centrelines.size()) != rods ||
        static_cast<int>(state.joined->boltPositionsM.size()) < bolts)
      throw InvalidInput(fmt::format(
          "model: the joined deployment has {} rods and {} bolts, the grids {} and {}",
          state.joined->centrelines.size(), state.joined->boltPositionsM.size(), rods, bolts));
    source = CentrelineSource::JoinedSimulation;
    return out;
  }
  for (const auto& g : grids)
    if (g.own) out[g.id] = {g.own, 0, 0};
  source = out.empty() ? CentrelineSource::Grid : CentrelineSource::PatchSimulation;
  return out;
}

// Per lamella id, the cut sheet of its first segment (the nesting places the segments of
// fabrication's lamellae in order, fabrication/fabricate.cpp).
std::map<std::string, std::string> sheetsOf(const RunState& state) {
  std::map<std::string, std::string> sheets;
  if (!state.fabricated) return sheets;
  const auto& f = *state.fabricated;
  size_t part = 0;
  for (const auto& plan : f.lamellae)
    for (size_t k = 0; k < plan.segments.size(); ++k, ++part)
      if (k == 0 && part < f.lamellaNesting.placements.size())
        sheets[plan.id] = fmt::format("sheet_{:02d}", f.lamellaNesting.placements[part].sheet + 1);
  return sheets;
}

void addSupports(const RunState& state, exporter::StructureModel& model) {
  if (!state.fabricated) {
    model.supportsNote = "no supports: the fabrication stage did not run";
    return;
  }
  const auto& f = *state.fabricated;
  for (size_t i = 0; i < f.supports.size(); ++i) {
    const auto& s = f.supports[i];
    exporter::ModelSupport m{s.id,       s.patchId, s.connectionId, s.block ? "block" : "bracket",
                             s.position, {}};
    if (s.block && i < f.supportSolids.size()) {
      // supportSolid's frame: millimetres, the point above the origin, z = 0 on the ground.
      const Eigen::Vector3d origin(s.position.x(), s.position.y(), s.position.z() - s.heightM);
      for (const auto& v : f.supportSolids[i].vertices)
        m.solid.vertices.push_back(origin + v / 1000.0);
      m.solid.triangles = f.supportSolids[i].triangles;
    }
    model.supports.push_back(std::move(m));
  }
}

}  // namespace

exporter::StructureModel structureModel(const RunState& state) {
  const Scene& scene = state.scene;
  exporter::StructureModel model;
  model.name = scene.name;
  model.widthM = scene.lamella.widthM;
  model.thicknessM = scene.lamella.thicknessM;
  model.boltDiameterM = scene.fabricationOptions().boltDiameterMm / 1000.0;
  const TriMesh& surface = state.surface->mesh;
  const TriangleSoup soup = soupFromMesh(surface);
  model.surface.vertices = soup.vertices;
  for (const auto& t : soup.triangles) model.surface.triangles.emplace_back(t[0], t[1], t[2]);
  const rods::SurfaceDistance distance(surface);
  const std::vector<ModelGrid> grids = modelGrids(state);
  const std::map<int, DeployedSource> deployed = deployedSources(state, grids, model.source);
  const std::map<std::string, std::string> sheets = sheetsOf(state);
  for (const auto& p : grids) {
    const EggGrid& grid = *p.grid;
    model.patches.push_back(p.id);
    const auto src = deployed.find(p.id);
    const rods::SimulationRun* run = src == deployed.end() ? nullptr : src->second.run;
    const int u = static_cast<int>(grid.u.size());
    int rod = 0;
    for (const auto* family : {&grid.u, &grid.v})
      for (const GridMember& m : *family) {
        exporter::ModelLamella l;
        l.family = m.family == Family::U ? 'U' : 'V';
        l.id = fmt::format("P{}-{}{}", p.id, l.family, m.index);
        l.patch = p.id;
        l.index = m.index;
        l.boundary = m.boundary;
        l.lengthM = m.planarLength;
        l.spatialLengthM = m.spatialLength;
        if (auto it = sheets.find(l.id); it != sheets.end()) l.sheet = it->second;
        if (run) {
          const size_t r = static_cast<size_t>(src->second.firstRod + rod);
          l.centreline = run->centrelines[r];
          l.normals = run->normals[r];
          for (size_t i = 0; i < l.centreline.size(); ++i)
            l.deviationM.push_back(distance.distance(run->contactPoints[r][i]));
          l.layer = (l.centreline[0] - run->contactPoints[r][0]).dot(l.normals[0]) > 0.0 ? 1 : 0;
        } else {
          // The grid: u below the design surface, v above (rod_network.hpp's layers).
          l.layer = m.family == Family::U ? 0 : 1;
          const double side = (l.layer == 1 ? 0.5 : -0.5) * model.thicknessM;
          for (size_t i = 0; i < m.spatial.size(); ++i) {
            l.centreline.push_back(m.spatial[i] + side * m.normals[i]);
            l.normals.push_back(m.normals[i]);
            l.deviationM.push_back(distance.distance(m.spatial[i]));
          }
        }
        model.lamellas.push_back(std::move(l));
        ++rod;
      }
    for (size_t k = 0; k < grid.connections.size(); ++k) {
      const GridConnection& c = grid.connections[k];
      exporter::ModelBolt bolt;
      bolt.patch = p.id;
      bolt.id = fmt::format("P{}-C{}-{}", p.id, c.memberU, c.memberV);
      bolt.position = c.spatial;
      bolt.axis = c.normal;
      if (run) {
        const auto& s = run->boltPositionsM[src->second.firstBolt + k];
        const int ra = src->second.firstRod + c.memberU, rb = src->second.firstRod + u + c.memberV;
        const Eigen::Vector3d a =
            pointAt(run->centrelines[ra], s[0], grid.u[c.memberU].planarLength);
        const Eigen::Vector3d b =
            pointAt(run->centrelines[rb], s[1], grid.v[c.memberV].planarLength);
        bolt.position = 0.5 * (a + b);
        if ((b - a).norm() > 1e-9) bolt.axis = (b - a).normalized();
        if (bolt.axis.dot(c.normal) < 0.0) bolt.axis = -bolt.axis;
      }
      model.bolts.push_back(std::move(bolt));
    }
  }
  addSupports(state, model);
  return model;
}

ModelOutputs::ModelOutputs(RunState& state) : state_(state) {
  model_ = structureModel(state);
  modelS_ = watch_.seconds();  // the deployed state, deviations, supports placed
  if (const std::string why = exporter::rhinoUnavailableReason(); why.empty()) {
    rhinoWatch_.restart();
    // std::async: an exception in the writer comes back through get() in finish().
    rhino_ = std::async(std::launch::async, [this] {
      return exporter::write3dm(model_, state_.staging / "model.3dm");
    });
  } else {
    state.report.section("model")["rhino_skipped"] = why;
    state.report.warn("model.3dm not written: " + why);
  }
}

ModelOutputs::~ModelOutputs() {
  if (rhino_.valid()) rhino_.wait();
}

void ModelOutputs::finish() {
  state_.progress("model", 0.96);
  json& section = state_.report.section("model");
  section["ran"] = true;
  section["model_s"] = modelS_;
  json files = json::array();
  auto write = [&](const std::string& name, const std::string& bytes) {
    writeFileAtomically(state_.staging / name, bytes);
    files.push_back({{"path", name}, {"bytes", bytes.size()}});
  };
  const Stopwatch glb;
  write("model.glb", exporter::glbBytes(model_));
  section["glb_s"] = glb.seconds();
  write("model.obj", exporter::modelObj(model_));
  const bool blocks = std::any_of(model_.supports.begin(), model_.supports.end(),
                                  [](const auto& s) { return !s.solid.triangles.empty(); });
  if (blocks) {
    write("supports.glb", exporter::supportsGlbBytes(model_));
    write("supports.stl", exporter::supportsStl(model_));
  } else {
    section["supports_skipped"] = model_.supportsNote.empty()
                                      ? "no support block (every support is a bracket or none)"
                                      : model_.supportsNote;
  }
  if (rhino_.valid()) {
    try {
      section["rhino_node_s"] = rhino_.get();
      files.push_back({{"path", "model.3dm"},
                       {"bytes", std::filesystem::file_size(state_.staging / "model.3dm")}});
    } catch (const IoError&) {
      throw;  // the run folder cannot be written: the run fails as a whole, as for any file
    } catch (const Error& e) {
      // The writer is a separate program (Node.js with rhino3dm): when it fails, the run still
      // completes with every other file and its report, and fails naming it (exit code 1).
      section["rhino_error"] = e.what();
      state_.failures.push_back(std::string("model.3dm not written: ") + e.what());
    }
    section["rhino_s"] = rhinoWatch_.seconds();  // from its start: it ran beside the rest
  }
  section.update({{"files", files},
                  {"centreline_source", exporter::toString(model_.source)},
                  {"lamellas", model_.lamellas.size()},
                  {"bolts", model_.bolts.size()},
                  {"supports", model_.supports.size()},
                  {"max_deviation_m", model_.maxDeviationM()},
                  {"seconds", watch_.seconds()}});
}

}  // namespace egg::pipeline
