// Generalised patches in `egg run` (issue 41): see infill_stage.hpp.
#include "pipeline/infill_stage.hpp"

#include "core/materials/materials.hpp"
#include "core/timing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// The quad grids' member spacing: per traced patch, its mean side length over the gaps between
// its members, and the median over the patches.
double infillMemberSpacing(const std::vector<SolvedPatch>& patches) {
  std::vector<double> spacings;
  for (const auto& p : patches) {
    if (!p.egg || p.egg->grid.u.size() < 2) continue;
    const auto& sides = p.egg->patch.sideLengths;
    const double meanSide = (sides[0] + sides[1] + sides[2] + sides[3]) / 4.0;
    spacings.push_back(meanSide / static_cast<double>(p.egg->grid.u.size() - 1));
  }
  if (spacings.empty()) return 0.0;
  std::sort(spacings.begin(), spacings.end());
  return spacings[spacings.size() / 2];
}

json infillEntry(const patching::InfillPiece& piece, int index) {
  json entry{{"id", fmt::format("G{}", index)},
             {"kind", "generalised"},
             {"cut_off", piece.cutOff},
             {"area_m2", piece.areaM2},
             {"mesh_vertices", piece.mesh.n_vertices()},
             {"feasible", piece.design.has_value()}};
  if (!piece.design) {
    entry["reason"] = piece.failure;  // as a quad patch's entry names it
    return entry;
  }
  const auto& o = *piece.optimisation;
  const auto& d = *piece.design;
  double maxNotch = 0.0;
  for (double l : d.planar.notchLengthsM) maxNotch = std::max(maxNotch, l);
  entry["lines_per_family"] = o.parameters.lines[0];
  entry["members"] = o.layout.members.size();
  entry["split_members"] = o.layout.splitMembers;
  entry["crossings"] = d.fieldCrossings.size();
  entry["e_effort_per_m4"] = o.energy.eEffort;
  entry["e_effort_scaled"] = o.energy.eEffortScaled;
  entry["e_shape"] = o.energy.eShape;
  entry["e_grid"] = o.energy.eGrid;
  entry["eps_geo_percent"] = d.epsGeoPercent;
  entry["max_crossing_deviation_m"] = d.maxCrossingDeviationM;
  entry["planarisation"] = {{"length_residual_m", d.planar.lengthResidualM},
                            {"notch_energy_m2", d.planar.notchEnergyM2},
                            {"max_notch_m", maxNotch},
                            {"overlapping_neighbours", d.planar.overlappingPairs.size()},
                            {"overlapping_lamellas", d.planarOverlaps.size()},
                            {"status", d.planar.status},
                            {"seconds", d.planar.seconds}};
  entry["anchors"] = {{"design_boundary", piece.anchorsOnDesignBoundary},
                      {"patch_sides", piece.anchorsOnPatchSides},
                      {"cuts", piece.anchorsOnCuts}};
  entry["anchor_supports"] =
      "members end at anchors: on the design boundary or a hole's rim a support ring carries them; "
      "on a quad patch's side the neighbour's boundary lamella, taken as a ring beam; on a cut "
      "between two pieces of a ring a ring beam across the neck";
  entry["seconds"] = {
      {"precompute", piece.precomputeSeconds}, {"optimisation", o.seconds}, {"design", d.seconds}};
  entry["evaluations"] = o.evaluations;
  return entry;
}

}  // namespace

void designInfill(RunState& state) {
  const Scene& scene = state.scene;
  const auto& coverage = state.patching->coverage;
  if (!scene.patching.generalisedInfill.value_or(!layoutIsGiven(scene)) || coverage.cutOffs.empty())
    return;
  const double spacing = infillMemberSpacing(state.patches);
  if (!(spacing > 0.0)) return;  // no quad grid to match: nothing traced
  patching::InfillOptions options;
  options.memberSpacingM = spacing;
  // A cut-off smaller than a square of the quad grids' member spacing holds no crossing members.
  options.minAreaM2 = spacing * spacing;
  options.optimisation.globalEvaluations = 200;
  options.optimisation.maxRefinementSweeps = 2;
  options.design.section = {scene.lamella.widthM, scene.lamella.thicknessM};
  const auto& material = materialByName(scene.lamella.material);
  options.design.material = {material.youngsModulusPa, material.shearModulusPa,
                             material.densityKgM3};
  state.progress("grid: generalised patches", 0.55);
  state.infill = patching::infillCutOffs(state.patching->layout.layout, coverage, options);
  state.infillSimulations.assign(state.infill->pieces.size(), std::nullopt);
  json entries = json::array();
  std::vector<double> designedPerCutOff(coverage.cutOffs.size(), 0.0);
  for (size_t i = 0; i < state.infill->pieces.size(); ++i) {
    const auto& piece = state.infill->pieces[i];
    entries.push_back(infillEntry(piece, static_cast<int>(i)));
    if (piece.design) designedPerCutOff[piece.cutOff] += piece.areaM2;
  }
  state.report.section("generalised_patches") = entries;
  // Coverage with the generalised patches: what is left of each cut-off is still cut off.
  json& section = state.report.section("coverage");
  const double quadCovered = coverage.coveredAreaM2;
  section["covered_area_quad_patches_m2"] = quadCovered;
  section["fraction_quad_patches"] = coverage.fraction;
  section["covered_area_generalised_patches_m2"] = state.infill->designedAreaM2;
  section["covered_area_m2"] = quadCovered + state.infill->designedAreaM2;
  section["fraction"] = coverage.surfaceAreaM2 > 0.0
                            ? (quadCovered + state.infill->designedAreaM2) / coverage.surfaceAreaM2
                            : 0.0;
  json left = json::array();
  for (size_t c = 0; c < coverage.cutOffs.size(); ++c) {
    const double remaining = coverage.cutOffs[c].areaM2 - designedPerCutOff[c];
    if (remaining > 1e-6 * std::max(1.0, coverage.cutOffs[c].areaM2))
      left.push_back({{"area_m2", remaining},
                      {"centroid_m",
                       {coverage.cutOffs[c].centroid.x(), coverage.cutOffs[c].centroid.y(),
                        coverage.cutOffs[c].centroid.z()}}});
  }
  section["cut_offs"] = left;
  section["generalised_infill_seconds"] = state.infill->seconds;
}

void simulateInfill(RunState& state) {
  if (!state.infill) return;
  json& entries = state.report.section("generalised_patches");
  for (size_t i = 0; i < state.infill->pieces.size(); ++i) {
    const auto& piece = state.infill->pieces[i];
    if (!piece.design) continue;
    state.progress(fmt::format("simulation: generalised patch {}", i), 0.74);
    const auto result =
        rods::simulateGrid(piece.design->network, piece.mesh, state.scene.simulation.rods);
    json deviation{{"converged", result.converged},
                   {"iterations", result.deployed.solver.iterations},
                   {"seconds", result.seconds}};
    if (result.deployed.deviation) {
      deviation["rmse_m"] = result.deployed.deviation->rmseM;
      deviation["max_m"] = result.deployed.deviation->maxM;
    }
    if (!result.converged) {
      deviation["reason"] = result.reason;
      state.failures.push_back(
          fmt::format("simulation: generalised patch G{} did not converge: {}", i, result.reason));
    }
    entries[i]["simulation"] = deviation;
    state.infillSimulations[i] = result;
  }
}

std::vector<InfillMemberLine> infillMemberLines(const RunState& state) {
  std::vector<InfillMemberLine> lines;
  if (!state.infill) return lines;
  for (size_t i = 0; i < state.infill->pieces.size(); ++i) {
    const auto& piece = state.infill->pieces[i];
    if (!piece.design) continue;
    const auto& rods = piece.design->network.rods;
    for (size_t m = 0; m < rods.size(); ++m) {
      const bool deployed = i < state.infillSimulations.size() && state.infillSimulations[i];
      lines.push_back(
          {static_cast<int>(i), piece.optimisation->layout.members[m].family,
           deployed ? state.infillSimulations[i]->deployed.contactPoints[m] : rods[m].guess});
    }
  }
  return lines;
}

}  // namespace egg::pipeline
