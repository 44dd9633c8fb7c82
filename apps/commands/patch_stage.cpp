#include "apps/commands/patch_stage.hpp"

#include "apps/commands/error_time_plot.hpp"
#include "apps/commands/grid_to_rods.hpp"
#include "apps/commands/report.hpp"
#include "core/egg/grid_io.hpp"
#include "core/errors.hpp"
#include "core/materials/materials.hpp"
#include "propagation/patch_sides.hpp"

#include <fmt/core.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>

namespace egg::app {

using nlohmann::json;

namespace {

// The report's EggResult of a traced design.
EggResult eggResult(const patching::DesignedPatch& designed, FamilyMembers u, FamilyMembers v, EggGrid grid, double membersSeconds,
                    double tracingSeconds) {
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

std::optional<propagation::LayoutPropagation> propagateMembers(const PatchingRun& run, const Scene& scene) {
  if (run.layout.patches.size() < 2) return std::nullopt;
  std::vector<propagation::PatchSideData> sides;
  for (const auto& designed : run.layout.patches) {
    if (designed.feasible()) sides.push_back(propagation::patchSideData(*designed.design, scene.lamella.width_m));
    else sides.emplace_back();
  }
  propagation::PropagationOptions options;
  options.members = scene.grid.members_per_family;
  options.lamellaWidthM = scene.lamella.width_m;
  options.spacingFactor = scene.grid.member_spacing_factor;
  return propagation::propagateLayout(run.graph, sides, options);
}

std::vector<SolvedPatch> tracePatches(PatchingRun& run, const Scene& /*scene*/, const propagation::LayoutPropagation* members,
                                      propagation::LayoutTracing* tracing) {
  const auto& layout = run.layout.layout;
  std::vector<SolvedPatch> out(run.layout.patches.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].id = static_cast<int>(i);
    out[i].cornerIds = layout.patches[i];
    for (int k = 0; k < 4; ++k) out[i].corners[k] = layout.corners[out[i].cornerIds[k]];
    if (!run.layout.patches[i].feasible()) out[i].failure = run.layout.patches[i].failure;
  }
  if (members) {
    // Several patches: the propagated members (Problem 3.3), traced in member order so that
    // neighbours' member ends coincide on their shared sides (propagation/chain_tracing.hpp).
    std::vector<const PatchDesign*> designs;
    for (const auto& designed : run.layout.patches) designs.push_back(designed.feasible() ? &*designed.design : nullptr);
    propagation::LayoutTracing traced = propagation::traceLayout(designs, *members);
    for (size_t i = 0; i < out.size(); ++i) {
      auto& t = traced.patches[i];
      if (!run.layout.patches[i].feasible()) continue;
      if (!t.grid) {
        out[i].failure = t.failure;
        continue;
      }
      out[i].egg = eggResult(run.layout.patches[i], std::move(*t.u), std::move(*t.v), std::move(*t.grid), t.membersSeconds, t.tracingSeconds);
      t.grid.reset();
    }
    if (tracing) *tracing = std::move(traced);
    return out;
  }
  tbb::parallel_for(size_t(0), out.size(), [&](size_t i) {
    SolvedPatch& patch = out[i];
    patching::DesignedPatch& designed = run.layout.patches[i];
    if (!designed.feasible()) return;
    const PatchDesign& design = *designed.design;
    try {
      // One patch (or no propagation): its own automatic placement (Section 2.4.4).
      auto t = std::chrono::steady_clock::now();
      FamilyMembers u = placeDesignMembers(design, Family::U, design.options.members);
      FamilyMembers v = placeDesignMembers(design, Family::V, design.options.members);
      const double membersSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
      t = std::chrono::steady_clock::now();
      EggGrid grid = traceDesignGrid(design, u, v, design.options.grid);
      const double tracingSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
      patch.egg = eggResult(designed, std::move(u), std::move(v), std::move(grid), membersSeconds, tracingSeconds);
    } catch (const InfeasiblePatch& e) {
      patch.failure = std::string("infeasible: ") + e.what();
    } catch (const SolverFailure& e) {
      patch.failure = std::string("solver failure: ") + e.what();
    }
  });
  return out;
}

json propagationSection(const propagation::LayoutPropagation& members, const propagation::LayoutTracing& tracing) {
  json chains = json::array();
  for (const auto& chain : members.chains) {
    json nodes = json::array();
    for (const auto& n : chain.nodes)
      nodes.push_back({{"patch", n.patch}, {"family", n.family == Family::U ? "u" : "v"}, {"forward", n.forward}});
    chains.push_back({{"graph_chain", chain.graphChain},
                      {"nodes", nodes},
                      {"ring", chain.ring},
                      {"members", chain.solution.start.size()},
                      {"evenness_before", chain.solution.evennessBefore},
                      {"evenness_after", chain.solution.evennessAfter},
                      {"iterations", chain.solution.iterations},
                      {"status", chain.solution.status}});
  }
  json fallbacks = json::array();
  for (const auto& f : members.fallbacks) {
    json patches = json::array();
    for (const auto& n : f.nodes) patches.push_back({{"patch", n.patch}, {"family", n.family == Family::U ? "u" : "v"}});
    fallbacks.push_back({{"graph_chain", f.graphChain}, {"nodes", patches}, {"reason", f.reason}});
  }
  json gaps = json::array();
  for (const auto& g : tracing.gaps)
    gaps.push_back({{"boundary", g.boundary},
                    {"patches", {g.patchA, g.patchB}},
                    {"piece", g.piece},
                    {"members", {g.membersA, g.membersB}},
                    {"max_gap_m", g.maxGapM},
                    {"kind", g.kind}});
  return {{"ran", true},
          {"c0_max_gap_m", tracing.c0MaxGapM},
          {"evenness_before", members.evennessBefore},
          {"evenness_after", members.evennessAfter},
          {"iterations", members.iterations},
          {"chains", members.chains.size()},
          {"originals", members.originals},
          {"seconds", members.seconds},
          {"tracing_rounds", tracing.rounds},
          {"matched_runs", tracing.matchedRuns},
          {"held_runs", tracing.heldRuns},
          {"member_traces", tracing.memberTraces},
          {"notes", members.notes},
          {"propagated_chains", chains},
          {"per_patch_chains", fallbacks},
          {"sides", gaps}};
}

namespace {

double patchDiagonal(const EggResult& egg) { return boundingBox(egg.patch.mesh).size().norm(); }

rods::SimulationOptions simulationOptions(const Scene& scene, const EggResult& egg) {
  rods::SimulationOptions options;
  options.model.notches = scene.simulation.notches;
  options.model.gravity = scene.simulation.gravity;
  options.fastenBoltsUnderLoad = scene.simulation.fasten_bolts;
  options.model.frictionMu = scene.simulation.friction_mu;
  options.solver.tolerance = scene.simulation.newton_tolerance;
  options.solver.timeLimit_s = scene.simulation.time_limit_s;
  // RMS1 (plain holes) beside RMS2 (notches), Section 2.6.2: a second full run per patch, only
  // when the scene asks for the comparison (and only meaningful with notches).
  options.compareWithoutNotches = scene.simulation.notches && scene.simulation.compare_without_notches;
  // NRMSE of Section 3.5.2 divides by a scale; we use the patch's bounding-box diagonal so that
  // the figure compares patches and scenes of any size.
  options.scaleFactor = patchDiagonal(egg);
  options.historyEvery = kErrorHistoryEvery;
  return options;
}

}  // namespace

rods::RodNetwork holdEverySide(rods::RodNetwork network, const EggGrid& grid) {
  std::vector<char> anchored(grid.connections.size(), 0);
  for (const auto& a : grid.anchors) anchored.at(a.connection) = 1;
  for (size_t c = 0; c < grid.connections.size(); ++c) {
    const GridConnection& connection = grid.connections[c];
    if (!connection.onBoundary || anchored[c]) continue;
    rods::Anchor anchor;
    anchor.rod = connection.memberU;
    anchor.s_m = std::clamp(connection.sBarU, 0.0, network.rods[anchor.rod].length_m);
    anchor.position = connection.spatial;
    anchor.normal = connection.normal.normalized();
    network.anchors.push_back(anchor);
  }
  return network;
}

void simulatePatches(std::vector<SolvedPatch>& patches, const TriMesh& surface, const Scene& scene, bool holdSharedSides,
                     const std::function<void(int, int)>& patchDone) {
  GridToRodsOptions convert;
  convert.section.width_m = scene.lamella.width_m;
  convert.section.thickness_m = scene.lamella.thickness_m;
  convert.material = materialByName(scene.lamella.material);
  convert.notches = true;  // the simulation switches notches off itself for the comparison run
  // Patches in parallel, each simulation on one thread when there are several (the rods code's
  // own threads would only compete with TBB's); the simulation is bit-identical for any count.
  const int solved = static_cast<int>(std::count_if(patches.begin(), patches.end(), [](const auto& p) { return p.egg.has_value(); }));
  std::atomic<int> done{0};
  tbb::parallel_for(size_t(0), patches.size(), [&](size_t i) {
    auto& patch = patches[i];
    if (!patch.egg) return;
    // One patch's failure must not discard the others' results: record it and go on.
    try {
      rods::RodNetwork network = rodNetworkFromGrid(patch.egg->grid, convert);
      if (holdSharedSides) network = holdEverySide(std::move(network), patch.egg->grid);
      rods::SimulationOptions options = simulationOptions(scene, *patch.egg);
      if (solved > 1) options.solver.threads = 1;
      patch.simulation = rods::simulateGrid(network, surface, options);
    } catch (const Error& e) {
      patch.simulationFailure = e.what();
    }
    if (patchDone) patchDone(++done, solved);
  });
}

int supportDesignBoundary(std::vector<SolvedPatch>& patches, const patching::PatchGraph& graph) {
  int added = 0;
  for (const auto& b : graph.boundaries) {
    if (b.kind != "free") continue;
    const auto& use = b.uses.front();
    auto& patch = patches[use.patch];
    if (!patch.egg) continue;
    EggGrid& grid = patch.egg->grid;
    const int nu = static_cast<int>(grid.u.size()), nv = static_cast<int>(grid.v.size());
    // Side 0 is u member 0, side 2 the last u member, side 3 v member 0, side 1 the last v member.
    std::vector<int> connections;
    if (use.side == 0 || use.side == 2) {
      const int i = use.side == 0 ? 0 : nu - 1;
      for (int j = 0; j < nv; ++j) connections.push_back(i * nv + j);
    } else {
      const int j = use.side == 3 ? 0 : nv - 1;
      for (int i = 0; i < nu; ++i) connections.push_back(i * nv + j);
    }
    for (int c : connections) {
      const bool known = std::any_of(grid.anchors.begin(), grid.anchors.end(), [&](const GridAnchor& a) { return a.connection == c; });
      if (known) continue;
      grid.anchors.push_back({c, "design boundary support"});
      ++added;
    }
  }
  return added;
}

json patchEntry(const SolvedPatch& patch) {
  json corners = json::array();
  for (const auto& c : patch.corners) corners.push_back({c.x(), c.y(), c.z()});
  json entry{{"id", patch.id}, {"corners", corners}, {"corner_ids", patch.cornerIds}, {"feasible", patch.egg.has_value()}};
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
      {"injectivity_bound_m", std::isfinite(r.uniqueness.injectivityBoundM) ? json(r.uniqueness.injectivityBoundM) : json(nullptr)},
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

json simulationSection(const std::vector<SolvedPatch>& patches, const Scene& scene) {
  // Errors over all patches pooled by point count, so a big patch weighs as much as its points.
  double sumSquares = 0.0, sumSquaresPlain = 0.0, maxError = 0.0, nrmseWorst = 0.0;
  long points = 0, pointsPlain = 0;
  int iterations = 0;
  bool converged = true;
  std::string reason;
  json perPatch = json::array();
  for (const auto& patch : patches) {
    if (!patch.simulationFailure.empty()) {
      converged = false;
      if (reason.empty()) reason = fmt::format("patch {}: {}", patch.id, patch.simulationFailure);
      perPatch.push_back({{"patch", patch.id}, {"converged", false}, {"failure", patch.simulationFailure}});
      continue;
    }
    if (!patch.simulation) continue;
    const auto& sim = *patch.simulation;
    converged = converged && sim.converged;
    if (!sim.converged && reason.empty()) reason = fmt::format("patch {}: {}", patch.id, sim.reason);
    iterations += sim.deployed.solver.iterations;
    json entry{{"patch", patch.id},
               {"converged", sim.converged},
               {"iterations", sim.deployed.solver.iterations},
               {"status", rods::toString(sim.deployed.solver.status)},
               {"energy_j", sim.deployed.solver.energy},
               {"gradient_norm_n_nm", sim.deployed.solver.gradientNorm},  // over positions (N) and twists (N m)
               {"decrement_j", sim.deployed.solver.decrement},            // last Newton decrement g^T H^-1 g
               {"unknowns", sim.deployed.unknowns},
               {"factorisations", sim.deployed.solver.factorisations},      // Cholesky, shift trials included
               {"energy_evaluations", sim.deployed.solver.energyEvaluations},  // line-search trials
               {"seconds", sim.seconds}};
    // Under self-weight, how far the grid sagged from its weightless equilibrium (a "collapsed"
    // status means it fell through: Section 3.5.2, Fig. 3.11).
    if (scene.simulation.gravity) entry["max_sag_m"] = sim.deployed.maxSag_m;
    if (sim.deployed.deviation) {
      const auto& d = *sim.deployed.deviation;
      sumSquares += d.rmse_m * d.rmse_m * d.points;
      points += d.points;
      maxError = std::max(maxError, d.max_m);
      nrmseWorst = std::max(nrmseWorst, d.nrmse);
      entry.update({{"rmse_m", d.rmse_m}, {"max_error_m", d.max_m}, {"nrmse", d.nrmse}});
    }
    // Error against run time (issue 18): the deployed run's deviation every few iterations.
    entry["history"] = historyJson(sim.deployed.history);
    entry["history_measuring_s"] = sim.deployed.historySeconds;
    if (sim.withoutNotches && sim.withoutNotches->deviation) {
      const auto& d = *sim.withoutNotches->deviation;
      sumSquaresPlain += d.rmse_m * d.rmse_m * d.points;
      pointsPlain += d.points;
      entry["rmse_no_notches_m"] = d.rmse_m;
    }
    perPatch.push_back(entry);
  }
  json section{{"ran", true},
               {"converged", converged},
               {"rmse_m", points ? json(std::sqrt(sumSquares / points)) : json(nullptr)},
               {"max_error_m", points ? json(maxError) : json(nullptr)},
               {"nrmse", points ? json(nrmseWorst) : json(nullptr)},
               {"nrmse_normalised_by", "patch bounding-box diagonal (worst patch)"},
               {"rmse_no_notches_m", pointsPlain ? json(std::sqrt(sumSquaresPlain / pointsPlain)) : json(nullptr)},
               {"gravity", scene.simulation.gravity},
               {"bolts_fastened_under_load", scene.simulation.gravity && scene.simulation.fasten_bolts},
               {"notches", scene.simulation.notches},
               {"friction_mu", scene.simulation.friction_mu},
               {"iterations", iterations},
               {"patches", perPatch}};
  if (!converged) section["reason"] = reason;
  return section;
}

namespace {

std::string polylinesObj(const std::vector<std::vector<Eigen::Vector3d>>& lines, const std::string& comment) {
  std::ostringstream out;
  out.precision(10);
  out << "# " << comment << "\n";
  int next = 1;
  for (const auto& line : lines) {
    for (const auto& p : line) out << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    out << "l";
    for (size_t k = 0; k < line.size(); ++k) out << " " << next + static_cast<int>(k);
    out << "\n";
    next += static_cast<int>(line.size());
  }
  return out.str();
}

}  // namespace

void writePatchFiles(const SolvedPatch& patch, const std::filesystem::path& dir, const Scene& scene) {
  if (!patch.egg) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw WriteError(dir.string() + ": cannot create the patch folder: " + ec.message());
  writeGridJson(*patch.egg, (dir / "grid.json").string(), patch.id);
  if (!scene.wants("previews")) return;
  writeGridObj(patch.egg->grid, (dir / "grid.obj").string());
  writePlanarSvg(patch.egg->grid, (dir / "planar.svg").string());
  if (patch.simulation) {
    writeFileAtomically(dir / "deployed.obj",
                        polylinesObj(patch.simulation->deployed.centrelines,
                                     fmt::format("eggshell patch {}: deployed lamella centrelines (m)", patch.id)));
  }
}

}  // namespace egg::app
