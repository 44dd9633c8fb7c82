#include "pipeline/patching_stage.hpp"

#include "core/timing.hpp"
#include "pipeline/grid_stage.hpp"
#include "pipeline/infill_stage.hpp"
#include "pipeline/run_state.hpp"

#include "core/errors.hpp"
#include "core/geodesic/distance_solver.hpp"
#include "core/io/atomic_file.hpp"
#include "patching/curvature_sheet.hpp"
#include "patching/injectivity.hpp"
#include "patching/site_plan.hpp"
#include "pipeline/elevations.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <set>

namespace egg::pipeline {

using nlohmann::json;

namespace {

json point(const Eigen::Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); }

const char* familyName(Family f) { return f == Family::U ? "u" : "v"; }

}  // namespace

PatchingRun runPatching(const TriMesh& surface, const geodesic::DistanceSolver& surfaceSolver,
                        const Scene& scene) {
  const std::string origin = scene.path.string();
  PatchingRun run;
  const bool given = layoutIsGiven(scene);
  const bool workflow2 = !given && scene.patching.workflow == 2;
  run.workflow = given ? "given" : workflow2 ? "2" : "1";
  patching::LayoutDesignOptions options;
  options.design = scene.eggOptions();
  options.split = !given;
  options.maxSplits = scene.patching.layout.maxSplits;
  options.minSideM = scene.patching.layout.minSideM;
  try {
    options.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(origin + ": " + e.what());
  }
  const auto started = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3d> corners = scene.patching.corners;
  std::vector<std::array<int, 4>> quads = scene.patching.quads;
  if (workflow2) {
    try {
      run.initial = patching::proposeLayout(surface, scene.patching.workflow2, &surfaceSolver);
    } catch (const InvalidInput& e) {
      throw InvalidInput(origin + ": patching: " + e.what());
    }
    corners = run.initial->corners;
    quads = run.initial->quads;
  }
  patching::PatchLayout layout = [&] {
    try {
      return patching::makeLayout(surface, surfaceSolver, corners, quads, options.layout);
    } catch (const InvalidInput& e) {
      // Workflow 2's corners are its own: the message says what the user can change (issue 40: a
      // one-triangle mesh talked of "patch 0: corner 1").
      if (workflow2)
        throw InvalidInput(fmt::format(
            "{}: patching: Workflow 2 cannot lay out patches on this surface ({} faces): its "
            "proposed layout is degenerate ({}); mesh it finer (surface.edge_length_m) or give "
            "patching.patches",
            origin, surface.n_faces(), e.what()));
      throw InvalidInput(origin + ": patching.patches: " + e.what());
    }
  }();
  // Patches the user gave that overlap are bad input (a roof covered twice: double lamellas,
  // double mass), found before the designs where their sides cross, after them where one lies
  // inside the other. Workflows 1 and 2 never make such layouts.
  const auto refuseOverlaps = [&](const std::vector<patching::PatchOverlap>& overlaps) {
    if (given && !overlaps.empty())
      throw InvalidInput(fmt::format("{}: patching.patches[{}] and patches[{}] overlap: {}", origin,
                                     overlaps[0].a, overlaps[0].b, overlaps[0].what));
  };
  refuseOverlaps(patching::crossingPatches(layout));
  run.layout = patching::designLayout(std::move(layout), surfaceSolver, options);
  std::vector<bool> usable;
  std::vector<std::vector<int>> faces;
  for (const auto& p : run.layout.patches) {
    usable.push_back(p.cut.has_value());
    faces.push_back(p.cut ? p.cut->layoutFace : std::vector<int>{});
  }
  refuseOverlaps(patching::overlapFaces(run.layout.layout, faces));
  run.graph = patching::buildPatchGraph(run.layout.layout, usable);
  run.coverage = patching::computeCoverage(run.layout.layout, faces);
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  run.designSeconds = run.layout.designSeconds;
  run.layoutSeconds =
      total - run.designSeconds;  // corners, traces, splits, layout mesh, graph, coverage
  return run;
}

void addPatchingReport(const PatchingRun& run, json& report) {
  const auto& L = run.layout;
  json splits = json::array();
  for (const auto& s : L.splits)
    splits.push_back({{"parent", s.parent},
                      {"children", s.children},
                      {"kind", s.kind},
                      {"p_max_m", point(s.peak)}});
  report["patching"] = {{"workflow", run.workflow},
                        {"patches", L.patches.size()},
                        {"splits", L.splits.size()},
                        {"merges", 0},
                        {"candidates_screened", run.initial ? run.initial->candidatesScreened : 0},
                        {"candidates_evaluated", L.evaluations},
                        {"rounds", L.rounds},
                        {"corners", L.layout.corners.size()},
                        {"sides", L.layout.curves.size()},
                        {"layout_mesh_vertices", L.layout.mesh.mesh.n_vertices()},
                        {"split_log", splits},
                        {"seconds", run.layoutSeconds + run.designSeconds}};
  json boundaries = json::array();
  for (const auto& b : run.graph.boundaries) {
    json patches = json::array(), uses = json::array();
    for (const auto& u : b.uses) {
      patches.push_back(u.patch);
      uses.push_back({{"patch", u.patch},
                      {"side", u.side},
                      {"from", u.from},
                      {"to", u.to},
                      {"reversed", u.reversed}});
    }
    boundaries.push_back({{"id", b.id},
                          {"kind", toString(b.kind)},
                          {"patches", patches},
                          {"length_m", b.lengthM},
                          {"on_patches", uses}});
  }
  if (run.initial) {
    report["patching"]["workflow2"] = {{"blocks", run.initial->blocks},
                                       {"holes", run.initial->holes},
                                       {"initial_patches", run.initial->quads.size()},
                                       {"peaks_snapped", run.initial->peaksSnapped},
                                       {"notes", run.initial->notes},
                                       {"seconds", run.initial->seconds}};
  }
  report["boundaries"] = boundaries;
  json tj = json::array();
  for (const auto& t : run.graph.tJunctions)
    tj.push_back({{"corner", t.corner},
                  {"position_m", point(L.layout.corners[t.corner])},
                  {"patches_through", t.patchesThrough},
                  {"patches_at", t.patchesAt}});
  report["t_junctions"] = tj;
  json chains = json::array();
  for (const auto& c : run.graph.chains) {
    json nodes = json::array();
    for (const auto& n : c.nodes)
      nodes.push_back({{"patch", n.patch}, {"family", familyName(n.family)}});
    chains.push_back({{"nodes", nodes}, {"ring", c.ring}, {"branching", c.branching}});
  }
  report["chains"] = chains;
  json cutOffs = json::array();
  for (const auto& c : run.coverage.cutOffs)
    cutOffs.push_back({{"area_m2", c.areaM2}, {"centroid_m", point(c.centroid)}});
  report["coverage"] = {{"covered_area_m2", run.coverage.coveredAreaM2},
                        {"surface_area_m2", run.coverage.surfaceAreaM2},
                        {"fraction", run.coverage.fraction},
                        {"cut_offs", cutOffs}};
}

void writePatchesJson(const PatchingRun& run, const std::filesystem::path& file) {
  const auto& layout = run.layout.layout;
  json corners = json::array(), sides = json::array(), patches = json::array();
  for (const auto& c : layout.corners) corners.push_back(point(c));
  for (const auto& c : layout.curves) {
    json polyline = json::array();
    for (const auto& p : c.positions) polyline.push_back(point(p));
    sides.push_back({{"from", c.from},
                     {"to", c.to},
                     {"corners", c.corners},
                     {"length_m", c.length},
                     {"polyline_m", polyline}});
  }
  for (size_t p = 0; p < layout.patches.size(); ++p) {
    const auto& d = run.layout.patches[p];
    json entry{{"id", p}, {"corners", layout.patches[p]}, {"feasible", d.feasible()}};
    if (!d.feasible()) entry["reason"] = d.failure;
    if (d.cut) entry["area_m2"] = d.cut->patch.area;
    patches.push_back(entry);
  }
  json doc{{"units", {{"length", "m"}}},
           {"workflow", run.workflow},
           {"corners_m", corners},
           {"sides", sides},
           {"patches", patches}};
  json report;
  addPatchingReport(run, report);
  for (const char* key : {"boundaries", "t_junctions", "chains", "coverage"})
    doc[key] = report[key];
  doc["splits"] = report["patching"]["split_log"];
  writeFileAtomically(file, doc.dump(1) + "\n");
}

namespace {

// The analytical sheet: the layout over the K map, with the surface's K peaks and their
// injectivity circles (computed here: only this sheet needs them) and the cut-offs.
json writeCurvatureSheet(const RunState& state, const std::filesystem::path& file) {
  const PatchingRun& run = *state.patching;
  const TriMesh& surface = state.surface->mesh;
  patching::CurvatureDrawing drawing;
  drawing.surface = &surface;
  drawing.layout = &run.layout.layout;
  for (const auto& p : run.layout.patches)
    drawing.patchProblems.push_back(p.feasible() ? "" : p.failure);
  drawing.peaks = patching::findSurfacePeaks(surface);
  drawing.circles = patching::injectivityCircles(surface, *state.surfaceSolver, drawing.peaks);
  drawing.coverage = &run.coverage;
  drawing.title = state.scene.name + ": curvature and injectivity";
  patching::writeCurvatureSheet(file, drawing);
  json peaks = json::array();
  for (size_t i = 0; i < drawing.peaks.size(); ++i) {
    const auto& peak = drawing.peaks[i];
    const auto& circle = drawing.circles[i];
    peaks.push_back({{"p_max_m", point(peak.position)},
                     {"gaussian_max_1_m2", peak.gaussianMax},
                     {"injectivity_radius_m", peak.radiusM},
                     {"on_boundary", peak.onBoundary},
                     {"circle_complete", circle.complete},
                     {"circle_covers_surface", circle.coversSurface},
                     {"circle_length_m", circle.lengthM}});
  }
  return peaks;
}

// The architect's plan: outlines, areas, members, supports, dimensions, section lines.
int writeSitePlan(const RunState& state, const std::filesystem::path& file) {
  const PatchingRun& run = *state.patching;
  patching::SitePlanDrawing drawing;
  drawing.surface = &state.surface->mesh;
  drawing.layout = &run.layout.layout;
  for (const auto& p : run.layout.patches) {
    drawing.patchProblems.push_back(p.feasible() ? "" : p.failure);
    drawing.patchAreasM2.push_back(p.cut ? p.cut->patch.area : 0.0);
  }
  // With generalised patches in the cut-offs, what they cover is no longer cut off.
  patching::Coverage coverage = run.coverage;
  if (state.infill) {
    std::set<int> filled;
    for (size_t i = 0; i < state.infill->pieces.size(); ++i) {
      const auto& piece = state.infill->pieces[i];
      if (!piece.design) continue;
      filled.insert(piece.layoutFaces.begin(), piece.layoutFaces.end());
      int patchId = -1;
      for (const auto& g : state.generalised)
        if (g.piece == static_cast<int>(i)) patchId = g.patchId;
      drawing.generalised.push_back(
          {fmt::format("G{}", i), patchId, piece.layoutFaces, piece.areaM2});
    }
    std::vector<patching::CutOff> left;
    for (auto cut : coverage.cutOffs) {
      std::vector<int> faces;
      for (int f : cut.faces)
        if (!filled.count(f)) faces.push_back(f);
      if (faces.size() == cut.faces.size()) {
        left.push_back(std::move(cut));
        continue;
      }
      if (faces.empty()) continue;
      const double kept = static_cast<double>(faces.size()) / cut.faces.size();
      cut.areaM2 *= kept;  // by face count: the plan's label, not a measurement
      cut.faces = std::move(faces);
      left.push_back(std::move(cut));
    }
    coverage.cutOffs = std::move(left);
    coverage.coveredAreaM2 += state.infill->designedAreaM2;
    coverage.fraction =
        coverage.surfaceAreaM2 > 0 ? coverage.coveredAreaM2 / coverage.surfaceAreaM2 : 0.0;
    for (const auto& line : infillMemberLines(state))
      drawing.members.push_back({-1, line.family == 0, false, line.points});
  }
  drawing.coverage = &coverage;
  for (const auto& p : state.patches) {
    if (!p.egg) continue;
    for (const auto* family : {&p.egg->grid.u, &p.egg->grid.v})
      for (const auto& m : *family)
        drawing.members.push_back({p.id, m.family == Family::U, m.boundary, m.spatial});
  }
  if (state.fabricated)
    for (const auto& s : state.fabricated->supports)
      drawing.supports.push_back({s.id, s.position, !s.block});
  for (const auto& s : sectionPlanes(state.surface->mesh))
    drawing.sections.push_back({s.name, s.alongX, s.atM});
  drawing.title = state.scene.name;
  const std::string svg = patching::sitePlanSvg(drawing);
  writeFileAtomically(file, svg);
  const size_t at = svg.find("data-labels-left-out=\"");
  return at == std::string::npos ? 0 : std::atoi(svg.c_str() + at + 22);
}

}  // namespace

void writePlan(const RunState& state, const std::filesystem::path& folder, json& report) {
  const auto started = std::chrono::steady_clock::now();
  report["labels_left_out"] = writeSitePlan(state, folder / "plan.svg");
  report["peaks"] = writeCurvatureSheet(state, folder / "curvature.svg");
  report["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void patchingStage(RunState& state) {
  const Stopwatch watch;
  state.surfaceSolver.emplace(state.surface->mesh);
  PatchingRun patching = runPatching(state.surface->mesh, *state.surfaceSolver, state.scene);
  const double solverSeconds = watch.seconds() - patching.layoutSeconds - patching.designSeconds;
  state.report.stageRan("patching", patching.layoutSeconds + solverSeconds);
  state.report.stageRan("design", patching.designSeconds);
  addPatchingReport(patching, state.report.document());
  state.patches = layoutPatches(patching);
  state.patching = std::move(patching);
}

}  // namespace egg::pipeline
