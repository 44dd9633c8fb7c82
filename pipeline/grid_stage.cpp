#include "pipeline/grid_stage.hpp"

#include "core/egg/grid_io.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/timing.hpp"
#include "pipeline/cladding_plot.hpp"
#include "pipeline/infill_stage.hpp"
#include "pipeline/propagation_stage.hpp"
#include "pipeline/stages.hpp"

#include <fmt/core.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// The report's EggResult of a traced design.
EggResult eggResult(const patching::DesignedPatch& designed, FamilyMembers u, FamilyMembers v,
                    EggGrid grid, double membersSeconds, double tracingSeconds) {
  const PatchDesign& design = *designed.design;
  EggResult result;
  result.patch = design.patch;
  result.uniqueness = design.uniqueness;
  result.maps = design.maps;
  result.alphaBar = design.alphaBar;
  result.seconds = design.seconds;
  result.membersU = std::move(u);
  result.membersV = std::move(v);
  result.grid = std::move(grid);
  result.seconds.members = membersSeconds;
  result.seconds.tracing = tracingSeconds;
  result.seconds.patch = designed.cut->patch.seconds;
  result.seconds.total = design.seconds.total + membersSeconds + tracingSeconds;
  result.propagations = design.propagations + result.grid.propagations;
  return result;
}

}  // namespace

std::vector<SolvedPatch> layoutPatches(const PatchingRun& run) {
  const auto& layout = run.layout.layout;
  std::vector<SolvedPatch> out(run.layout.patches.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].id = static_cast<int>(i);
    out[i].cornerIds = layout.patches[i];
    for (int k = 0; k < 4; ++k) out[i].corners[k] = layout.corners[out[i].cornerIds[k]];
    if (!run.layout.patches[i].feasible()) out[i].failure = run.layout.patches[i].failure;
  }
  return out;
}

void tracePatches(PatchingRun& run, std::vector<SolvedPatch>& out,
                  const propagation::LayoutPropagation* members,
                  propagation::LayoutTracing* tracing) {
  if (members) {
    // Several patches: the propagated members (Problem 3.3), traced in member order so that
    // neighbours' member ends coincide on their shared sides (propagation/chain_tracing.hpp).
    std::vector<const PatchDesign*> designs;
    for (const auto& designed : run.layout.patches)
      designs.push_back(designed.feasible() ? &*designed.design : nullptr);
    propagation::LayoutTracing traced = propagation::traceLayout(designs, *members);
    for (size_t i = 0; i < out.size(); ++i) {
      auto& t = traced.patches[i];
      if (!run.layout.patches[i].feasible()) continue;
      if (!t.grid) {
        out[i].failure = t.failure;
        continue;
      }
      out[i].egg = eggResult(run.layout.patches[i], std::move(*t.u), std::move(*t.v),
                             std::move(*t.grid), t.membersSeconds, t.tracingSeconds);
      t.grid.reset();
    }
    if (tracing) *tracing = std::move(traced);
    return;
  }
  tbb::parallel_for(size_t(0), out.size(), [&](size_t i) {
    SolvedPatch& patch = out[i];
    patching::DesignedPatch& designed = run.layout.patches[i];
    if (!designed.feasible()) return;
    const PatchDesign& design = *designed.design;
    try {
      // One patch (or no propagation): its own automatic placement (Section 2.4.4).
      Stopwatch watch;
      FamilyMembers u = placeDesignMembers(design, Family::U, design.options.members);
      FamilyMembers v = placeDesignMembers(design, Family::V, design.options.members);
      const double membersSeconds = watch.seconds();
      watch.restart();
      EggGrid grid = traceDesignGrid(design, u, v, design.options.grid);
      const double tracingSeconds = watch.seconds();
      patch.egg = eggResult(designed, std::move(u), std::move(v), std::move(grid), membersSeconds,
                            tracingSeconds);
    } catch (const InfeasiblePatch& e) {
      patch.failure = std::string("infeasible: ") + e.what();
    } catch (const SolverFailure& e) {
      patch.failure = std::string("solver failure: ") + e.what();
    }
  });
}

json patchEntry(const SolvedPatch& patch) {
  json corners = json::array();
  for (const auto& c : patch.corners) corners.push_back({c.x(), c.y(), c.z()});
  json entry{{"id", patch.id},
             {"kind", "quad"},  // generalised patches: report.json generalised_patches[]
             {"corners", corners},
             {"corner_ids", patch.cornerIds},
             {"feasible", patch.egg.has_value()}};
  if (!patch.egg) {
    entry["reason"] = patch.failure;
    return entry;
  }
  const EggResult& r = *patch.egg;
  entry.update({
      {"area_m2", r.patch.area},
      {"vertices", r.patch.mesh.n_vertices()},
      {"side_lengths_m", r.patch.sideLengths},
      {"inner_angles_rad", r.patch.innerAngles},
      {"eta_u", r.uniqueness.etaU},
      {"eta_v", r.uniqueness.etaV},
      {"injectivity_bound_m", std::isfinite(r.uniqueness.injectivityBoundM)
                                  ? json(r.uniqueness.injectivityBoundM)
                                  : json(nullptr)},
      {"smoothing_rounds", r.uniqueness.smoothingRounds},
      {"smoothing_displacement_m", r.uniqueness.smoothingDisplacementM},
      {"alpha_bar_rad", r.alphaBar.alphaBar},
      {"alpha_bar_range_rad", {r.alphaBar.alphaMin, r.alphaBar.alphaMax}},
      {"slope_min", r.alphaBar.slopeMin},
      {"slope_max", r.alphaBar.slopeMax},
      {"members_u", r.grid.u.size()},
      {"members_v", r.grid.v.size()},
      {"connections", r.grid.connections.size()},
      {"anchors", r.grid.anchors.size()},
      {"notches", countNotches(r.grid)},  // slots longer than 0.1 mm (shorter is a plain hole)
      {"max_notch_m", r.grid.maxNotch},
      {"max_length_mismatch_relative", r.grid.maxLengthMismatch},
      {"seconds",
       {{"patch_s", r.seconds.patch},
        {"uniqueness_s", r.seconds.uniqueness},
        {"distance_maps_s", r.seconds.distanceMaps},
        {"sqp_s", r.seconds.sqp},
        {"members_s", r.seconds.members},
        {"tracing_s", r.seconds.tracing},
        {"total_s", r.seconds.total}}},
  });
  return entry;
}

namespace {

// One object and group per polyline, named by `names` (lamella ids).
std::string polylinesObj(const std::vector<std::vector<Eigen::Vector3d>>& lines,
                         const std::vector<std::string>& names, const std::string& comment) {
  std::ostringstream out;
  out.precision(10);
  out << "# " << comment << "\n";
  int next = 1;
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto& line = lines[i];
    if (i < names.size()) out << "o " << names[i] << "\ng " << names[i] << "\n";
    for (const auto& p : line) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    out << "l";
    for (size_t k = 0; k < line.size(); ++k) out << " " << next + static_cast<int>(k);
    out << "\n";
    next += static_cast<int>(line.size());
  }
  return out.str();
}

}  // namespace

void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir,
                     const Scene& scene) {
  if (!patch.egg) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw WriteError(dir.string() + ": cannot create the patch folder: " + ec.message());
  writeGridJson(*patch.egg, (dir / "grid.json").string(), patch.id);
  if (!scene.wants("previews")) return;
  writeGridObj(patch.egg->grid, (dir / "grid.obj").string(), patch.id);
  writePlanarSvg(patch.egg->grid, (dir / "planar.svg").string());
  if (patch.simulation) {
    // Rods are the u members, then the v members (assembly/grid_to_rods.hpp).
    std::vector<std::string> names;
    for (const auto* family : {&patch.egg->grid.u, &patch.egg->grid.v})
      for (const auto& m : *family)
        names.push_back(
            fmt::format("P{}-{}{}", patch.id, m.family == Family::U ? "U" : "V", m.index));
    writeFileAtomically(
        dir / "deployed.obj",
        polylinesObj(patch.simulation->deployed.centrelines, names,
                     fmt::format("eggshell patch {}: deployed lamella centrelines (m)", patch.id)));
  }
}

void addPatchEntries(RunState& state) {
  const PatchingRun& patching = *state.patching;
  const bool gridNeeded = stageNeeded(StageId::Grid, state.scene.outputs);
  for (const auto& p : state.patches) {
    json entry = patchEntry(p);
    const auto& designed = patching.layout.patches[p.id];
    if (!p.egg && designed.design && designed.feasible()) {
      // Designed but not traced (no output needs the grid): the design's own figures.
      entry["feasible"] = true;
      entry["eta_u"] = designed.design->uniqueness.etaU;
      entry["eta_v"] = designed.design->uniqueness.etaV;
      entry["alpha_bar_rad"] = designed.design->alphaBar.alphaBar;
      entry["area_m2"] = designed.design->patch.area;
    }
    if (p.egg && designed.design) {
      // F_u, F_v with their members and the slope band they were kept in (Sections 2.4.3, 2.4.4).
      const EggResult& egg = *p.egg;
      const AlphaBarOptions& bounds = designed.design->options.alphaBar;
      const auto sides = [&](Family f) {
        return std::array<double, 2>{familySideLength(egg.patch, f, false),
                                     familySideLength(egg.patch, f, true)};
      };
      entry["cladding"] =
          claddingEntry(egg.alphaBar.claddingU, egg.alphaBar.claddingV, egg.membersU, egg.membersV,
                        sides(Family::U), sides(Family::V), bounds.slopeMin, bounds.slopeMax,
                        bounds.cladding.infiniteSlopeFactor);
    }
    state.report.section("patches").push_back(entry);
    if (!designed.feasible() || (gridNeeded && !p.egg))
      state.failures.push_back(
          fmt::format("patch {}: {}", p.id, p.failure.empty() ? designed.failure : p.failure));
  }
}

std::string gridSkipReason(const RunState& state) {
  return designedCount(*state.patching) == 0 ? "no feasible patch design" : std::string();
}

void gridStage(RunState& state) {
  tracePatches(*state.patching, state.patches, state.members ? &*state.members : nullptr,
               &state.tracing);
  if (state.members)
    state.report.section("propagation") = propagationSection(*state.members, state.tracing);
  designInfill(state);
}

}  // namespace egg::pipeline
