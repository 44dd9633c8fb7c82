#include "pipeline/scene_template.hpp"

#include "core/curvature/curvature.hpp"
#include "core/errors.hpp"
#include "core/materials/materials.hpp"
#include "pipeline/scene.hpp"
#include "pipeline/scene_fields.hpp"
#include "pipeline/surface_stage.hpp"
#include "samples/generators/samples.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// Plywood thicknesses a merchant stocks [mm] (EN 636 panels: 4-30 mm; thicker ones are glued up
// from these or cut from LVL).
constexpr double kStockThicknessesMm[] = {4,  6,  9,  12, 15, 18, 21, 24, 27,
                                          30, 35, 40, 45, 50, 60, 70, 80, 100};
// Half the characteristic strength: k_mod (0.6, permanent) over gamma_M (1.2) for plywood.
constexpr double kPrestressRatio = 0.5;
// Width over thickness of the thesis' sections (Table 3.3: 5 to 10; the Yas 8).
constexpr double kWidthOverThickness = 8.0;

SurfaceMeasures measure(const TriMesh& mesh) {
  SurfaceMeasures m;
  const Eigen::Vector3d size = boundingBox(mesh).size();
  m.planXM = size.x(), m.planYM = size.y(), m.riseM = size.z();
  m.spanM = std::max(size.x(), size.y());
  m.planDiagonalM = std::hypot(size.x(), size.y());
  const CurvatureField curvature = computeCurvature(mesh);
  std::vector<double> kappa;
  for (int v = 0; v < curvature.kappaMax.size(); ++v)
    if (!curvature.onBoundary[v])
      kappa.push_back(std::max(std::abs(curvature.kappaMax[v]), std::abs(curvature.kappaMin[v])));
  if (kappa.empty())
    for (int v = 0; v < curvature.kappaMax.size(); ++v)
      kappa.push_back(std::max(std::abs(curvature.kappaMax[v]), std::abs(curvature.kappaMin[v])));
  if (!kappa.empty()) {
    const size_t at = std::min(kappa.size() - 1, static_cast<size_t>(0.95 * kappa.size()));
    std::nth_element(kappa.begin(), kappa.begin() + static_cast<long>(at), kappa.end());
    m.bendingCurvaturePerM = kappa[at];
  }
  return m;
}

std::string fixed(double x, int digits) { return fmt::format("{:.{}f}", x, digits); }

}  // namespace

double suggestedThicknessM(double kappa, double youngsModulusPa, double bendingStrengthPa) {
  // sigma = E kappa t / 2 <= ratio f_m  =>  t <= 2 ratio f_m / (E kappa).
  const double limitMm =
      kappa > 0.0 ? 2.0 * kPrestressRatio * bendingStrengthPa / (youngsModulusPa * kappa) * 1000.0
                  : kStockThicknessesMm[std::size(kStockThicknessesMm) - 1];
  double chosen = kStockThicknessesMm[0];
  for (double t : kStockThicknessesMm)
    if (t <= limitMm) chosen = t;
  return chosen / 1000.0;
}

double suggestedMaxPatchSizeM(double planDiagonalM) {
  return std::clamp(5.0 * std::ceil(planDiagonalM * 2.0 / 3.0 / 5.0), 40.0, 100.0);
}

StartingScene startingScene(const StartingSceneOptions& options) {
  if (options.surface.empty()) throw InvalidInput("egg init: name a mesh file or a sample");
  Scene scene;
  const bool sample =
      samples::isSample(options.surface) && !std::filesystem::exists(options.surface);
  if (sample) {
    if (options.scaleToM)
      throw InvalidInput("--scale-to-m: applies to a mesh file, not to the sample " +
                         options.surface);
    scene.surface.sample = options.surface;
    scene.surface.edgeLengthM = defaultSampleEdgeLength(options.surface);
    scene.name = options.surface;
  } else {
    const std::filesystem::path file(options.surface);
    if (file.extension() == ".json")
      throw InvalidInput(options.surface +
                         ": a scene already; egg init starts one from a mesh file or a sample");
    scene.surface.file = std::filesystem::absolute(file);
    scene.surface.scaleToM = options.scaleToM.value_or(1.0);
    scene.name = file.stem().string();
  }
  if (scene.name.empty() || scene.name.front() == '.') scene.name = "my_surface";

  // The same loader as `egg run`: a missing file, a broken mesh or a millimetre model fails here,
  // with the same message, before anything is written.
  const LoadedSurface loaded = loadSurface(scene.surface);
  StartingScene out;
  out.warnings = loaded.warnings;
  out.measures = measure(loaded.mesh);
  const SurfaceMeasures& m = out.measures;

  const MaterialProperties& material = materialByName(scene.lamella.material);
  out.thicknessM = suggestedThicknessM(m.bendingCurvaturePerM, material.youngsModulusPa,
                                       material.bendingStrengthPa);
  out.widthM =
      std::clamp(std::round(kWidthOverThickness * out.thicknessM * 100.0) / 100.0, 0.04, 0.5);
  scene.lamella.thicknessM = out.thicknessM;
  scene.lamella.widthM = out.widthM;
  out.maxPatchSizeM = suggestedMaxPatchSizeM(m.planDiagonalM);
  scene.patching.workflow2.maxPatchSizeM = out.maxPatchSizeM;

  // The mesh as the scene will find it: relative to the scene's folder where one is named.
  ordered_json& doc = out.scene;
  if (!options.schema.empty()) doc["$schema"] = options.schema;
  doc["$comment"] = {
      fmt::format("Written by egg init from {}: plan {} x {} m, rise {} m, span {} m.",
                  sample ? "the sample " + options.surface : options.surface, fixed(m.planXM, 1),
                  fixed(m.planYM, 1), fixed(m.riseM, 1), fixed(m.spanM, 1)),
      "Every key is at its default; lengths in metres unless the key ends in _mm, angles in "
      "radians (docs/scene-reference.md). Run it with: egg run THIS_FILE",
      fmt::format("lamella: {:.0f} x {:.0f} mm, the thickest stock plywood whose deployment "
                  "bending stress E kappa t / 2 stays at half the {} bending strength at kappa = "
                  "{:.4f} 1/m (radius {:.1f} m, 95th percentile of the surface's curvature); the "
                  "run's acceptance check judges sag and stress.",
                  out.widthM * 1000.0, out.thicknessM * 1000.0, material.name,
                  m.bendingCurvaturePerM,
                  m.bendingCurvaturePerM > 0 ? 1.0 / m.bendingCurvaturePerM : INFINITY),
      fmt::format("patching.max_patch_size_m: {} m, two thirds of the plan diagonal ({} m), so "
                  "that Workflow 2 starts near 2 x 2 patches (the samples use 55 to 100 m); at "
                  "least 40 m, at most 100 m (handling on site, 3.5.3).",
                  field::numberText(out.maxPatchSizeM), fixed(m.planDiagonalM, 1))};

  for (const SceneSection& section : sceneSections()) {
    ordered_json values = ordered_json::object();
    ordered_json comments = ordered_json::array();
    if (!section.key.empty()) comments.push_back(section.doc);
    for (const SceneField& f : section.fields) {
      comments.push_back(f.key + ": " + f.doc + " (" + f.type + ")");
      std::optional<json> value = f.write(scene);
      if (!value) continue;
      if (section.key == "surface" && f.key == "file") {
        const std::filesystem::path folder =
            std::filesystem::absolute(options.sceneFolder.empty() ? "." : options.sceneFolder);
        const std::filesystem::path relative =
            std::filesystem::relative(scene.surface.file, folder);
        value = (relative.empty() ? scene.surface.file : relative).string();
      }
      values[f.key] = ordered_json::parse(value->dump());
    }
    if (section.key.empty()) {
      for (const auto& line : comments) doc["$comment"].push_back(line);
      for (auto& [key, value] : values.items()) doc[key] = value;
    } else {
      ordered_json object = {{"$comment", comments}};
      for (auto& [key, value] : values.items()) object[key] = value;
      doc[section.key] = std::move(object);
    }
  }
  return out;
}

}  // namespace egg::pipeline
