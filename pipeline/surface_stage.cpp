#include "pipeline/surface_stage.hpp"
#include "core/timing.hpp"
#include "pipeline/run_state.hpp"

#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"
#include "core/io/mesh_io.hpp"
#include "core/mesh/validate.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>
#include <chrono>
#include <cmath>

namespace egg::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

// A roof in metres is between half a metre (a test piece) and two kilometres across. Outside that
// the mesh was almost certainly modelled in other units (issue 39: a millimetre OBJ read as metres
// is 20 km wide, and patching then fails with a message about patch sizes). The error names the
// size found and the scale_to_m that brings it nearest a typical roof (50 m).
void checkPlausibleSize(const std::filesystem::path& file, const TriMesh& mesh, double scaleToM) {
  constexpr double kSmallestM = 0.5, kLargestM = 2000.0;
  const double size = boundingBox(mesh).size().maxCoeff();
  if (size >= kSmallestM && size <= kLargestM) return;
  struct Unit {
    double toM;
    const char* name;
  };
  static constexpr Unit kUnits[] = {{0.001, "millimetres"}, {0.01, "centimetres"},
                                    {0.0254, "inches"},     {0.3048, "feet"},
                                    {1.0, "metres"},        {1000.0, "kilometres"}};
  const Unit* best = nullptr;
  double bestDistance = 0.0;
  for (const Unit& u : kUnits) {
    const double scaled = size / scaleToM * u.toM;
    if (scaled < kSmallestM || scaled > kLargestM) continue;
    const double distance = std::abs(std::log(scaled / 50.0));
    if (!best || distance < bestDistance) best = &u, bestDistance = distance;
  }
  std::string hint = "no common unit makes it a roof's size: check the model";
  if (best)
    hint = fmt::format(
        "if it was modelled in {}, set \"surface\": {{\"scale_to_m\": {}}} "
        "(it is then {:.4g} m across)",
        best->name, best->toM, size / scaleToM * best->toM);
  throw InvalidInput(fmt::format(
      "{}: the surface is {:.4g} m across (file coordinates times surface.scale_to_m = {}), not "
      "the size of a roof in metres ({} m to {} m); {}",
      file.string(), size, scaleToM, kSmallestM, kLargestM, hint));
}

LoadedSurface fromFile(const std::filesystem::path& file, double scaleToM, bool keepLargest) {
  const auto start = Clock::now();
  MeshImportOptions importOptions;
  importOptions.scaleToM = scaleToM;
  TriangleSoup soup = readMeshFile(file, importOptions);
  MeshCheckOptions checkOptions;
  checkOptions.components = keepLargest ? ComponentPolicy::KeepLargest : ComponentPolicy::Reject;
  MeshRepairDiagnostics diagnostics;
  LoadedSurface out;
  try {
    out.mesh = prepareMesh(std::move(soup), checkOptions, diagnostics);
  } catch (const InvalidInput& e) {
    throw InvalidInput(file.string() + ": " + e.what());
  }
  checkPlausibleSize(file, out.mesh, scaleToM);
  out.description = file.string();
  out.warnings = diagnostics.warnings;
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

LoadedSurface fromSample(const std::string& name, const samples::Params& params,
                         double edgeLengthM) {
  const auto start = Clock::now();
  LoadedSurface out;
  out.mesh = samples::generateSample(name, params, edgeLengthM);
  out.description = fmt::format("sample {}, edge {} m", name, edgeLengthM);
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

LoadedSurface loadSurface(const SurfaceSource& spec) {
  if (!spec.sample.empty()) return fromSample(spec.sample, spec.params, spec.edgeLengthM);
  return fromFile(spec.file, spec.scaleToM, spec.keepLargestComponent);
}

LoadedSurface loadSurfaceArgumentDetailed(const std::string& argument,
                                          std::optional<double> edgeLengthM) {
  if (samples::isSample(argument)) {
    return fromSample(argument, {}, edgeLengthM.value_or(defaultSampleEdgeLength(argument)));
  }
  if (endsWith(argument, ".json")) {
    Scene scene = loadScene(argument);
    if (edgeLengthM) scene.surface.edgeLengthM = *edgeLengthM;
    return loadSurface(scene.surface);
  }
  if (!std::filesystem::exists(argument)) {
    std::string names;
    for (const auto& info : samples::listSamples())
      names += (names.empty() ? "" : ", ") + info.name;
    throw IoError(argument + ": no such file, and not a sample name (samples: " + names + ")");
  }
  return fromFile(argument, 1.0, false);
}

nlohmann::json surfaceSummary(const LoadedSurface& surface) {
  const TriMesh& mesh = surface.mesh;
  const BoundingBox box = boundingBox(mesh);
  const MeshCheckResult check = checkMesh(soupFromMesh(mesh));
  nlohmann::json issues = nlohmann::json::array();
  for (const auto& issue : check.issues) issues.push_back(issue.message);
  const CurvatureField curvature = computeCurvature(mesh);
  const double bound = injectivityRadiusBound(curvature.gaussianMax);
  return {
      {"source", surface.description},
      {"vertices", mesh.n_vertices()},
      {"faces", mesh.n_faces()},
      {"bbox_min_m", {box.min.x(), box.min.y(), box.min.z()}},
      {"bbox_max_m", {box.max.x(), box.max.y(), box.max.z()}},
      {"bbox_m", {box.size().x(), box.size().y(), box.size().z()}},
      {"area_m2", surfaceArea(mesh)},
      {"mean_edge_m", meanEdgeLength(mesh)},
      {"min_angle_rad", check.minAngleRad},
      {"boundary_edges", check.boundaryEdges},
      {"components", check.components},
      {"gaussian_curvature",
       {{"min_per_m2", curvature.gaussianMin},
        {"max_per_m2", curvature.gaussianMax},
        {"injectivity_bound_m",
         std::isfinite(bound) ? nlohmann::json(bound) : nlohmann::json(nullptr)}}},
      {"validation", {{"ok", check.acceptable()}, {"issues", issues}}},
      {"warnings", surface.warnings},
      {"seconds", surface.seconds},
  };
}

TriMesh loadSurfaceArgument(const std::string& argument) {
  return loadSurfaceArgumentDetailed(argument).mesh;
}

void surfaceStage(RunState& state) {
  const Stopwatch watch;
  LoadedSurface surface = [&] {
    try {
      return loadSurface(state.scene.surface);
    } catch (const InvalidInput& e) {
      throw InvalidInput(state.scene.path.string() + ": surface: " + e.what());
    }
  }();
  state.report.section("surface") = surfaceSummary(surface);
  state.report.stageRan("surface", watch.seconds());
  for (const auto& w : surface.warnings) state.report.warn("surface: " + w);
  state.surface = std::move(surface);
}

}  // namespace egg::pipeline
