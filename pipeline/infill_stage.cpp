// Generalised patches in `egg run` (issue 41): see infill_stage.hpp.
#include "pipeline/infill_stage.hpp"

#include "assembly/patch_joins.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "core/timing.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace egg::pipeline {
namespace {

using nlohmann::json;

// The quad grids' member spacing: per traced patch and family, the mean length of the two sides
// its members are spaced along (the other family's direction) over the gaps between them; the
// median over all of them.
double infillMemberSpacing(const std::vector<SolvedPatch>& patches) {
  std::vector<double> spacings;
  for (const auto& p : patches) {
    if (!p.egg) continue;
    const auto& sides = p.egg->patch.sideLengths;
    // The first and last u members are sides 0 and 2 (core/egg/grid.cpp), so the u members are
    // spaced along sides 1 and 3; the v members, whose outer ones are sides 3 and 1, along 0, 2.
    const size_t nu = p.egg->grid.u.size(), nv = p.egg->grid.v.size();
    if (nu >= 2) spacings.push_back(0.5 * (sides[1] + sides[3]) / static_cast<double>(nu - 1));
    if (nv >= 2) spacings.push_back(0.5 * (sides[0] + sides[2]) / static_cast<double>(nv - 1));
  }
  if (spacings.empty()) return 0.0;
  std::sort(spacings.begin(), spacings.end());
  return spacings[spacings.size() / 2];
}

// Generalised patches are numbered after the quad patches, piece i as P<first + i>.
int infillPatchId(const RunState& state, size_t piece) {
  int first = 0;
  for (const auto& p : state.patches) first = std::max(first, p.id + 1);
  return first + static_cast<int>(piece);
}

json infillEntry(const patching::InfillPiece& piece, int index, int patchId) {
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
  entry["patch_id"] = patchId;  // its lamellas are P<patch_id>-U<i>, -V<j> in the shop files
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
  entry["min_crossing_angle_deg"] = d.minCrossingAngleRad * 180.0 / std::numbers::pi;
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

// A notch shorter than this is drilled as a plain hole (mm): the planarisation leaves rounding.
constexpr double kInfillMinSlotMm = 0.05;

bool infillSlotted(const rods::Notch& notch) {
  return 1000.0 * (notch.beforeM + notch.afterM) >= kInfillMinSlotMm;
}

// Lamella ids as fabrication names them, per layout member: P<patch>-U<i> for the family in layer
// 0, P<patch>-V<j> for the other (assembly/generalised_patch.hpp).
std::vector<std::string> infillLamellaIds(const assembly::GeneralisedPatch& patch) {
  std::vector<std::string> ids;
  const int nu = static_cast<int>(patch.grid.u.size());
  for (int r : patch.rodOfMember)
    ids.push_back(fmt::format("P{}-{}{}", patch.patchId, r < nu ? 'U' : 'V', r < nu ? r : r - nu));
  return ids;
}

// The cut list: one row per lamella; its bolts as "s_bar[notch_from..notch_to]" in mm from the
// lamella's start (a plain hole without the brackets), its two end anchors at 0 and the length.
std::string infillCutList(const patching::InfillPiece& piece,
                          const assembly::GeneralisedPatch& patch) {
  const auto& network = piece.design->network;
  const auto ids = infillLamellaIds(patch);
  std::vector<std::vector<std::string>> holes(network.rods.size());
  for (size_t k = 0; k < network.connections.size(); ++k) {
    const auto& c = network.connections[k];
    const auto hole = [&](double s, const rods::Notch& notch, int other) {
      const std::string where = fmt::format("{:.1f}", 1000.0 * s);
      const std::string slot = infillSlotted(notch)
                                   ? fmt::format("[{:.1f}..{:.1f}]", 1000.0 * (s - notch.beforeM),
                                                 1000.0 * (s + notch.afterM))
                                   : "";
      return fmt::format("{}{}@{}", where, slot, ids[other]);
    };
    holes[c.rodA].push_back(hole(c.sAM, c.notchA, c.rodB));
    holes[c.rodB].push_back(hole(c.sBM, c.notchB, c.rodA));
  }
  std::string csv =
      "lamella,family,layer,length_mm,width_mm,thickness_mm,anchors_mm,bolts_mm "
      "(s_bar[slot from..to]@crossing lamella)\n";
  for (size_t r = 0; r < network.rods.size(); ++r) {
    const auto& rod = network.rods[r];
    std::string bolts;
    for (const auto& h : holes[r]) bolts += (bolts.empty() ? "" : " ") + h;
    csv += fmt::format("{},{},{},{:.1f},{:.1f},{:.1f},0.0 {:.1f},{}\n", ids[r],
                       piece.optimisation->layout.members[r].family == 0 ? "g" : "h",
                       patch.network.rods[patch.rodOfMember[r]].layer, 1000.0 * rod.lengthM,
                       1000.0 * rod.section.widthM, 1000.0 * rod.section.thicknessM,
                       1000.0 * rod.lengthM, bolts);
  }
  return csv;
}

// The planar layout in mm (1200 px on its longer side), y up: lamella outlines (u, the family in
// layer 0, blue; v orange), bolts, notch slots.
std::string infillPlanarSvg(const patching::InfillPiece& piece,
                            const assembly::GeneralisedPatch& patch) {
  const int index = patch.piece, patchId = patch.patchId;
  const auto& endpoints = piece.design->planar.endpoints;
  const auto& network = piece.design->network;
  const double width = 1000.0 * piece.design->planarProblem.widthM;
  Eigen::AlignedBox2d box;
  for (const auto& e : endpoints) box.extend(1000.0 * e[0]), box.extend(1000.0 * e[1]);
  const double margin = 2.0 * width + 50.0;
  const Eigen::Vector2d low = box.min() - Eigen::Vector2d::Constant(margin);
  const Eigen::Vector2d size = box.sizes() + Eigen::Vector2d::Constant(2 * margin);
  const auto px = [&](const Eigen::Vector2d& p) {
    return fmt::format("{:.2f},{:.2f}", p.x() - low.x(), size.y() - (p.y() - low.y()));
  };
  const double stroke = std::max(size.maxCoeff() / 1500.0, 0.5);
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
      "width=\"{8:.0f}\" height=\"{9:.0f}\" viewBox=\"0 0 {0:.2f} {1:.2f}\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n"
      "<text x=\"{2:.1f}\" y=\"{3:.1f}\" font-family=\"sans-serif\" font-size=\"{4:.1f}\">"
      "G{5} (P{10}): planar cut layout (mm), {6} lamellas, {7} bolts</text>\n",
      size.x(), size.y(), 0.3 * margin, 0.5 * margin, 0.25 * margin, index, endpoints.size(),
      network.connections.size(), 1200.0 * size.x() / size.maxCoeff(),
      1200.0 * size.y() / size.maxCoeff(), patchId);
  const auto ids = infillLamellaIds(patch);
  for (size_t r = 0; r < endpoints.size(); ++r) {
    const Eigen::Vector2d a = 1000.0 * endpoints[r][0], b = 1000.0 * endpoints[r][1];
    const Eigen::Vector2d d = (b - a).normalized();
    const Eigen::Vector2d n = 0.5 * width * Eigen::Vector2d(-d.y(), d.x());
    const bool g = patch.rodOfMember[r] < static_cast<int>(patch.grid.u.size());  // u: blue
    svg += fmt::format(
        "<path id=\"{}\" d=\"M{}L{}L{}L{}Z\" fill=\"{}\" fill-opacity=\"0.25\" stroke=\"{}\" "
        "stroke-width=\"{:.2f}\"/>\n",
        ids[r], px(a - n), px(b - n), px(b + n), px(a + n), g ? "#1f77b4" : "#ff7f0e",
        g ? "#1f77b4" : "#ff7f0e", stroke);
  }
  for (const auto& c : network.connections) {
    for (int side = 0; side < 2; ++side) {
      const int rod = side == 0 ? c.rodA : c.rodB;
      const double s = side == 0 ? c.sAM : c.sBM;
      const auto& notch = side == 0 ? c.notchA : c.notchB;
      const Eigen::Vector2d a = 1000.0 * endpoints[rod][0];
      const Eigen::Vector2d d = (1000.0 * endpoints[rod][1] - a).normalized();
      if (infillSlotted(notch))
        svg += fmt::format(
            "<path d=\"M{}L{}\" stroke=\"#0000ff\" stroke-width=\"{:.2f}\" "
            "stroke-linecap=\"round\"/>\n",
            px(a + 1000.0 * (s - notch.beforeM) * d), px(a + 1000.0 * (s + notch.afterM) * d),
            0.3 * width);
    }
    const Eigen::Vector2d a = 1000.0 * endpoints[c.rodA][0];
    const Eigen::Vector2d d = (1000.0 * endpoints[c.rodA][1] - a).normalized();
    const Eigen::Vector2d at = a + 1000.0 * c.sAM * d;
    svg += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"#111111\"/>\n",
                       at.x() - low.x(), size.y() - (at.y() - low.y()), 0.2 * width);
  }
  return svg + "</svg>\n";
}

}  // namespace

void writeInfillFiles(const RunState& state, const std::filesystem::path& folder) {
  if (!state.infill) return;
  for (const auto& patch : state.generalised) {
    const auto& piece = state.infill->pieces[patch.piece];
    const auto dir = folder / fmt::format("generalised_G{}", patch.piece);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      throw WriteError(dir.string() +
                       ": cannot create the generalised patch's folder: " + ec.message());
    writeFileAtomically(dir / "lamellas.csv", infillCutList(piece, patch));
    writeFileAtomically(dir / "planar.svg", infillPlanarSvg(piece, patch));
  }
}

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
  // Each patch's layers as they bolt more of its ends to the quads' boundary lamellas.
  const auto quadGrids = gridsOf(state.patches);
  state.generalised = assembly::generalisedPatches(
      *state.infill, infillPatchId(state, 0), quadGrids,
      assembly::layerSwaps(state.patching->graph, quadGrids), scene.lamella.widthM);
  json entries = json::array();
  std::vector<double> designedPerCutOff(coverage.cutOffs.size(), 0.0);
  for (size_t i = 0; i < state.infill->pieces.size(); ++i) {
    const auto& piece = state.infill->pieces[i];
    entries.push_back(infillEntry(piece, static_cast<int>(i), infillPatchId(state, i)));
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
  for (const auto& patch : state.generalised) {
    const int i = patch.piece;
    const auto& piece = state.infill->pieces[i];
    state.progress(fmt::format("simulation: generalised patch G{}", i), 0.74);
    const auto result = rods::simulateGrid(patch.network, piece.mesh, state.scene.simulation.rods);
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
  for (const auto& patch : state.generalised) {
    const int i = patch.piece;
    const bool deployed = i < static_cast<int>(state.infillSimulations.size()) &&
                          state.infillSimulations[i].has_value();
    const auto& rods = patch.network.rods;
    for (size_t r = 0; r < rods.size(); ++r)
      lines.push_back(
          {i, rods[r].layer,  // layer = family in the generalised patch's own network
           deployed ? state.infillSimulations[i]->deployed.contactPoints[r] : rods[r].guess});
  }
  return lines;
}

}  // namespace egg::pipeline
