#include "pipeline/deployment_stage.hpp"

#include "assembly/flat_grid.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "core/rods/deployment.hpp"
#include "core/timing.hpp"
#include "export/deployment_glb.hpp"
#include "pipeline/deployment_joining.hpp"
#include "pipeline/plot_frame.hpp"

#include <fmt/core.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <tuple>

namespace egg::pipeline {

using nlohmann::json;

namespace {

struct PatchDeployment {
  int patch = 0;
  std::optional<rods::DeploymentResult> result;
  std::string failure;  // an error before any step (not a non-converged step)
  std::string path;     // the path chosen: "corners first" or "all supports together"
  std::string choice;   // why
  json alternative;     // the other path's summary, when it ran
  double placementRmsM = 0.0;
  double flatMisfitM = 0.0;
  double endVsSimulationRmsM = -1.0;  // against the simulation's weightless equilibrium
  double boltOffsetMaxM = -1.0;       // largest bolt position difference from the simulation's
};

// The force at which a bolt pressing on the end of its notch crushes the lamella there: the
// embedment capacity f_h d t. Timber: f_h,k = 0.082 (1 - 0.01 d) rho_k (solid timber, EN 1995-1-1
// eq. 8.32) or 0.11 (1 - 0.01 d) rho_k (plywood, eq. 8.36), MPa with d in mm and rho_k in kg/m3
// (the catalogue's density stands for rho_k). Other materials (GFRP, steel): their bending
// strength as the bearing stress, a lower bound of their bearing resistance.
double embedmentCapacityN(const Scene& scene) {
  const MaterialProperties& m = materialByName(scene.lamella.material);
  const double d = scene.fabricationOptions().boltDiameterMm;
  const bool timber = m.densityKgM3 < 1000.0;
  const bool plywood = m.name.find("plywood") != std::string::npos;
  const double fhPa = timber ? (plywood ? 0.11 : 0.082) * (1.0 - 0.01 * d) * m.densityKgM3 * 1e6
                             : m.bendingStrengthPa;
  return fhPa * d * 1e-3 * scene.lamella.thicknessM;
}

double jamForceN(const Scene& scene) {
  return scene.deployment.jamForceN > 0.0 ? scene.deployment.jamForceN : embedmentCapacityN(scene);
}

rods::DeploymentOptions deploymentOptions(const Scene& scene, int patches) {
  rods::DeploymentOptions o;
  o.model = scene.simulation.rods.model;
  o.solver = scene.simulation.rods.solver;
  if (patches > 1) o.solver.threads = 1;  // patches in parallel, as the simulation stage
  o.solver.timeLimitS = scene.deployment.timeLimitS;
  o.steps = scene.deployment.steps;
  o.jamForceN = jamForceN(scene);
  o.snapEnergyDrop = scene.deployment.snapEnergyDrop;
  const MaterialProperties& material = materialByName(scene.lamella.material);
  o.bendingStrengthPa = material.bendingStrengthPa;
  o.shearStrengthPa = material.shearStrengthPa;
  return o;
}

json patchJson(const PatchDeployment& d) {
  json entry{{"patch", d.patch}};
  if (!d.failure.empty()) {
    entry["completed"] = false;
    entry["failure"] = d.failure;
    return entry;
  }
  const rods::DeploymentResult& r = *d.result;
  const rods::DeploymentStep& end = r.steps.back();
  double supportForce = 0.0, notchForce = 0.0, angleMin = M_PI, angleMax = 0.0;
  json steps = json::array();
  for (const auto& s : r.steps) {
    supportForce = std::max(supportForce, s.maxSupportForceN);
    notchForce = std::max(notchForce, s.maxNotchForceN);
    angleMin = std::min(angleMin, s.minCrossingAngleRad);
    angleMax = std::max(angleMax, s.maxCrossingAngleRad);
    steps.push_back(stepJson(s));
  }
  entry.update(pathTotalsJson(r));
  entry.update(
      {{"path_kind", d.path},
       {"path_choice", d.choice},
       {"engaged_from_t", r.engagedFromT >= 0.0 ? json(r.engagedFromT) : json(nullptr)},
       {"end_t", end.t},
       {"max_support_force_n", supportForce},
       {"max_notch_force_n", notchForce},
       {"crossing_angle_deg", {angleMin * 180.0 / M_PI, angleMax * 180.0 / M_PI}},
       {"flat_placement_rms_m", d.placementRmsM},
       {"flat_bolt_misfit_max_m", d.flatMisfitM},
       {"end_vs_simulation_rms_m",
        d.endVsSimulationRmsM >= 0.0 ? json(d.endVsSimulationRmsM) : json(nullptr)},
       {"end_bolt_offset_max_m", d.boltOffsetMaxM >= 0.0 ? json(d.boltOffsetMaxM) : json(nullptr)},
       {"path", steps}});
  if (!r.completed) entry["reason"] = r.reason;
  if (!d.alternative.is_null()) entry["alternative"] = d.alternative;
  return entry;
}

std::string csvRows(const std::string& name, const rods::DeploymentResult& r) {
  std::string out;
  for (size_t k = 0; k < r.steps.size(); ++k) {
    const rods::DeploymentStep& s = r.steps[k];
    for (size_t a = 0; a < s.supportPositionsM.size(); ++a) {
      const Eigen::Vector3d& p = s.supportPositionsM[a];
      const Eigen::Vector3d f =
          a < s.supportForcesN.size() ? s.supportForcesN[a] : Eigen::Vector3d::Zero();
      out += fmt::format(
          "{},{},{:.6f},{},{:.4f},{:.4f},{:.4f},{:.2f},{:.2f},{:.2f},{:.4f},{:.3f},{},{},"
          "{:.2f},{:.2f}\n",
          name, k, s.t, a, p.x(), p.y(), p.z(), f.x(), f.y(), f.z(), s.maxStressRatio,
          s.maxNotchForceN, s.jammedBolts, s.snap ? 1 : 0, s.minCrossingAngleRad * 180.0 / M_PI,
          s.maxCrossingAngleRad * 180.0 / M_PI);
    }
  }
  return out;
}

// One row per step and support: the patches' paths, then the joining ("joined").
std::string csvOf(const std::vector<PatchDeployment>& runs, const JoiningRun& joining) {
  std::ostringstream out;
  out << "patch,step,t,support,x_m,y_m,z_m,force_x_n,force_y_n,force_z_n,step_max_stress_ratio,"
         "step_max_notch_force_n,step_jammed_bolts,step_snap,step_min_crossing_deg,"
         "step_max_crossing_deg\n";
  for (const PatchDeployment& d : runs)
    if (d.result) out << csvRows(fmt::format("P{}", d.patch), *d.result);
  if (joining.result) out << csvRows("joined", *joining.result);
  return out.str();
}

// One line of a chart panel: (t, value) per step, snaps marked.
struct Series {
  std::string label, colour;
  std::vector<std::pair<double, double>> points;
  std::vector<std::pair<double, double>> snaps;
  bool dashed = false;
};

// A panel of the chart: a frame with y ticks, t ticks, the limit line when asked, the series and
// their labels on the right.
void drawPanel(std::ostringstream& svg, const PlotFrame& f, const std::string& title,
               const std::string& xLabel, bool limitLine, const std::vector<Series>& series,
               bool labels) {
  svg << fmt::format("<text x=\"{}\" y=\"{}\" font-weight=\"bold\">{}</text>\n", f.left, f.top - 16,
                     title);
  svg << fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n",
      f.left, f.top, f.width, f.height);
  const double step = tickStep(f.yMax, 5);
  for (double y = 0.0; y <= f.yMax + 1e-12; y += step)
    svg << fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:g}</text>\n", f.left - 6,
                       f.py(y) + 4, y);
  for (double x = f.xMin; x <= f.xMax + 1e-9; x += (f.xMax > 2.0 ? 0.5 : 0.25 * f.xMax))
    svg << fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{:g}</text>\n", f.px(x),
                       f.top + f.height + 16, x);
  svg << fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     f.left + f.width / 2, f.top + f.height + 34, xLabel);
  if (limitLine)
    svg << fmt::format(
        "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#c00\" "
        "stroke-dasharray=\"6 4\"/><text x=\"{1}\" y=\"{3}\" fill=\"#c00\" "
        "text-anchor=\"end\">limit 1</text>\n",
        f.left, f.left + f.width, f.py(1.0), f.py(1.0) - 4);
  for (size_t k = 0; k < series.size(); ++k) {
    const Series& line = series[k];
    std::string points;
    for (const auto& [t, y] : line.points)
      points += fmt::format("{:.1f},{:.1f} ", f.px(t), f.py(y));
    svg << fmt::format(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"{}/>\n", points,
        line.colour, line.dashed ? " stroke-dasharray=\"5 3\"" : "");
    for (const auto& [t, y] : line.snaps)
      svg << fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"#c00\"/>\n", f.px(t),
                         f.py(y));
    if (labels)
      svg << fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n", f.left + f.width + 6,
                         f.top + 12 + 14 * k, line.colour, line.label);
  }
}

double largestOf(const std::vector<Series>& series, double floor) {
  for (const auto& line : series)
    for (const auto& point : line.points) floor = std::max(floor, point.second);
  return floor;
}

// Against t: the peak stress ratio (with the limit 1) and the largest support force per patch;
// below, when the patches were joined, the same for the joining with the joints' pull.
std::string chartSvg(const std::vector<PatchDeployment>& runs, const JoiningRun& joining) {
  // 16 distinct colours: the Lilium and the Yas have 16 patches.
  const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02",
                           "#a6761d", "#666666", "#1f78b4", "#e31a1c", "#6a3d9a", "#b15928",
                           "#33a02c", "#ff7f00", "#fb9a99", "#a6cee3"};
  std::vector<Series> ratios, forces;
  double tMax = 1.0;
  for (const auto& d : runs) {
    if (!d.result) continue;
    Series ratio{fmt::format("P{}", d.patch), colours[ratios.size() % 16], {}, {}};
    Series force = ratio;
    for (const auto& s : d.result->steps) {
      ratio.points.emplace_back(s.t, s.maxStressRatio);
      force.points.emplace_back(s.t, 1e-3 * s.maxSupportForceN);
      if (s.snap)
        ratio.snaps.push_back(ratio.points.back()), force.snaps.push_back(force.points.back());
      tMax = std::max(tMax, s.t);
    }
    ratios.push_back(std::move(ratio));
    forces.push_back(std::move(force));
  }
  const bool joined = joining.result.has_value();
  const double width = 960, height = joined ? 660 : 340;
  std::ostringstream svg;
  svg << fmt::format(
      "<svg id=\"deployment-chart\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" "
      "height=\"{1}\" viewBox=\"0 0 {0} "
      "{1}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
      "fill=\"white\"/>\n",
      width, height);
  PlotFrame f;
  f.top = 40;
  f.width = 360;
  f.height = 240;
  f.xMax = tMax > 1.0 ? 2.0 : 1.0;
  const std::string xLabel =
      f.xMax > 1.0 ? "t: 0 flat, 1 corners placed, 2 every support fixed" : "t: 0 flat, 1 deployed";
  f.left = 70;
  f.yMax = 1.1 * largestOf(ratios, 1.0);
  drawPanel(svg, f, "Peak stress ratio (bending + axial, torsion) per step", xLabel, true, ratios,
            false);
  f.left = 510;
  f.yMax = 1.1 * largestOf(forces, 1.0);
  drawPanel(svg, f, "Largest support force per step (kN)", xLabel, false, forces, true);
  if (joined) {
    Series ratio{"joined", "#000000", {}, {}}, support{"supports", "#000000", {}, {}},
        pull{"joints", "#1f78b4", {}, {}, true};
    for (const auto& s : joining.result->steps) {
      ratio.points.emplace_back(s.t, s.maxStressRatio);
      support.points.emplace_back(s.t, 1e-3 * s.maxSupportForceN);
      pull.points.emplace_back(s.t, 1e-3 * s.maxJoinForceN);
      if (s.snap) ratio.snaps.push_back(ratio.points.back());
    }
    // The phases that ran, each over one unit of t (joinDeployedPatches).
    std::string joinLabel = "t: 0 patches standing";
    int phase = 0;
    if (joining.selfWeight) joinLabel += fmt::format(", {} self-weight", ++phase);
    if (joining.joints > 0) joinLabel += fmt::format(", {} joints bolted", ++phase);
    if (joining.temporarySupports > 0) joinLabel += fmt::format(", {} shoring off", ++phase);
    f.top = 360;
    f.xMax = joining.result->steps.back().t > 0.0 ? std::ceil(joining.result->steps.back().t) : 1.0;
    f.left = 70;
    f.yMax = 1.1 * largestOf({ratio}, 1.0);
    drawPanel(svg, f, "Joining the patches: peak stress ratio", joinLabel, true, {ratio}, false);
    f.left = 510;
    f.yMax = 1.1 * largestOf({support, pull}, 1.0);
    drawPanel(svg, f, "Joining: largest support and joint forces (kN)", joinLabel, false,
              {support, pull}, true);
  }
  svg << fmt::format(
      "<text x=\"70\" y=\"{}\" fill=\"#444\">Red dots: snap-through. Supports move "
      "along straight lines; self-weight not included{}.</text>\n</svg>\n",
      height - 6, joined && joining.selfWeight ? " until the joining" : "");
  return svg.str();
}

// One patch: corners first, and all supports together when corners first misses a limit; the
// path kept and why.
PatchDeployment deployPatch(const SolvedPatch& patch, const rods::DeploymentOptions& options) {
  PatchDeployment run;
  run.patch = patch.id;
  try {
    const assembly::FlatGrid flat = assembly::flatGrid(patch.egg->grid, *patch.network);
    run.placementRmsM = flat.placementRmsM;
    run.flatMisfitM = flat.boltMisfitMaxM;
    const rods::SupportPath path = rods::straightSupportPath(flat.flat, flat.deployed);
    // Corners first: the crew moves the patch's four corner supports and fixes the rest of the
    // boundary once the grid stands. Every boundary support moved at once along straight lines
    // shortens the boundary lamellas' short spans between them (a chord of the flat and the
    // deployed positions is shorter than both) and buckles them.
    std::vector<bool> corners(patch.network->anchors.size(), false);
    int cornerCount = 0;
    for (size_t a = 0; a < patch.egg->grid.anchors.size() && a < corners.size(); ++a)
      if (patch.egg->grid.anchors[a].reason == "corner") corners[a] = true, ++cornerCount;
    const bool twoPaths = cornerCount >= 3 && cornerCount < static_cast<int>(corners.size());
    rods::DeploymentOptions cornerOptions = options;
    if (twoPaths) cornerOptions.movedSupports = corners;
    rods::DeploymentResult first = rods::deploy(flat.network, path, cornerOptions);
    run.path = twoPaths ? "corners first" : "all supports together";
    run.choice = twoPaths ? "" : "the grid's only supports are its corners";
    const auto fine = [&](const rods::DeploymentResult& r) {
      return r.completed && r.snaps == 0 && r.jammedSteps == 0 &&
             r.steps[r.peakStep].maxStressRatio <= 1.0;
    };
    const auto summary = [](const std::string& name, const rods::DeploymentResult& r) {
      return json{{"path", name},
                  {"completed", r.completed},
                  {"peak_stress_ratio", r.steps[r.peakStep].maxStressRatio},
                  {"snaps", r.snaps},
                  {"jammed_steps", r.jammedSteps},
                  {"seconds", r.seconds}};
    };
    if (twoPaths && fine(first)) {
      run.choice = "corners first stays within the limits (no snap, no jam, stress ratio <= 1)";
    } else if (twoPaths && first.timedOut) {
      run.choice =
          "corners first ran out of time (deployment.time_limit_s); the other path was "
          "not tried";
    } else if (twoPaths) {
      rods::DeploymentResult all = rods::deploy(flat.network, path, options);
      const auto rank = [](const rods::DeploymentResult& r) {
        return std::make_tuple(!r.completed, r.steps[r.peakStep].maxStressRatio, r.snaps);
      };
      if (rank(all) < rank(first)) {
        run.alternative = summary("corners first", first);
        first = std::move(all);
        run.path = "all supports together";
        run.choice = "a lower peak stress ratio than corners first";
      } else {
        run.alternative = summary("all supports together", all);
        run.choice = "a lower peak stress ratio than all supports together";
      }
    }
    run.result = std::move(first);
    if (patch.simulation) {
      const rods::SimulationRun& sim = patch.simulation->deployed;
      // Where the bolts stopped in their notches against where the simulation put them: pseudo-
      // friction (Section 2.5) can hold a bolt short on the way, as wood's friction does.
      if (sim.boltPositionsM.size() == run.result->last.boltPositionsM.size()) {
        run.boltOffsetMaxM = 0.0;
        for (size_t c = 0; c < sim.boltPositionsM.size(); ++c)
          for (int side = 0; side < 2; ++side)
            run.boltOffsetMaxM = std::max(
                run.boltOffsetMaxM,
                std::abs(sim.boltPositionsM[c][side] - run.result->last.boltPositionsM[c][side]));
      }
      run.endVsSimulationRmsM = contactRmsM(
          run.result->last.contactPoints,
          sim.weightlessContactPoints.empty() ? sim.contactPoints : sim.weightlessContactPoints);
    }
  } catch (const Error& e) {
    run.failure = e.what();
  }
  return run;
}

}  // namespace

std::string deploymentSkipReason(const RunState& state) {
  for (const auto& p : state.patches)
    if (p.egg && p.network) return {};
  return "no simulated patch to deploy";
}

void deploymentStage(RunState& state) {
  const Scene& scene = state.scene;
  const Stopwatch watch;
  std::vector<PatchDeployment> runs;
  std::vector<const SolvedPatch*> sources;
  for (const auto& p : state.patches)
    if (p.egg && p.network) {
      runs.emplace_back();
      runs.back().patch = p.id;
      sources.push_back(&p);
    }
  const rods::DeploymentOptions options = deploymentOptions(scene, static_cast<int>(runs.size()));
  tbb::parallel_for(size_t(0), runs.size(),
                    [&](size_t i) { runs[i] = deployPatch(*sources[i], options); });
  // Then the standing patches joined into the structure the joined simulation solved, in its
  // order: the quads with a grid, then the generalised patches (issue 41). Those are not deployed
  // along a support path here: their members are held at both ends, fixed one by one to the ring,
  // which no synchronised straight path models; they join as their own simulation left them.
  std::vector<JoiningPart> parts;
  for (const auto& p : state.patches) {
    if (!p.egg) continue;
    JoiningPart part{p.id, p.network ? &*p.network : nullptr, nullptr, false};
    for (const auto& run : runs)
      if (run.patch == p.id && run.result)
        part.last = &run.result->last, part.reached = run.result->completed;
    parts.push_back(part);
  }
  if (state.joinedNetwork && state.joinedNetwork->firstRod.size() > parts.size())
    for (const auto& g : state.generalised) {
      const auto& own = state.infillSimulations[g.piece];
      parts.push_back(
          {g.patchId, &g.network, own ? &own->deployed : nullptr, own && own->converged});
    }
  const JoiningRun joining = joinDeployed(state, parts, options);
  json section{{"ran", true},
               {"paths",
                "corners first: the corner supports move together along straight lines from "
                "their places on the flat grid to their deployed places (normals turned at a "
                "uniform rate), t 0..1, then the other supports are fixed where the grid stands "
                "and pulled to their places, t 1..2; all supports together: every support so, t "
                "0..1. Corners first is kept when it stays within the limits, else the path with "
                "the lower peak stress ratio"},
               {"self_weight", false},
               {"steps_requested", scene.deployment.steps},
               {"jam_force_n", jamForceN(scene)},
               {"jam_force_from", scene.deployment.jamForceN > 0.0
                                      ? "deployment.jam_force_n"
                                      : "the bolt's embedment capacity in the lamella"},
               {"snap_energy_drop", scene.deployment.snapEnergyDrop}};
  json patches = json::array();
  std::vector<exporter::DeploymentAnimation> animations;
  for (const PatchDeployment& d : runs) {
    patches.push_back(patchJson(d));
    if (!d.failure.empty()) {
      state.failures.push_back(fmt::format("deployment: patch P{}: {}", d.patch, d.failure));
      continue;
    }
    const rods::DeploymentResult& r = *d.result;
    if (!r.completed)
      state.failures.push_back(fmt::format("deployment: patch P{}: {}", d.patch, r.reason));
    if (r.snaps > 0)
      state.report.warn(fmt::format(
          "deployment: patch P{} snaps through at {} step(s) of the synchronised path (first at "
          "t = {:.3f}): the crew would feel it jump; guide it there or change the supports",
          d.patch, r.snaps,
          std::find_if(r.steps.begin(), r.steps.end(), [](const auto& s) { return s.snap; })->t));
    if (r.jammedSteps > 0)
      state.report.warn(
          fmt::format("deployment: patch P{}: a bolt jams at a notch end in {} step(s) (pressing "
                      "harder than {:.0f} N): "
                      "lengthen that notch or free the bolt",
                      d.patch, r.jammedSteps, jamForceN(scene)));
    const auto& peak = r.steps[r.peakStep];
    if (peak.maxStressRatio > 1.0)
      state.report.warn(fmt::format(
          "deployment: patch P{}: stress ratio {:.2f} at t = {:.3f} on the way (end state {:.2f})",
          d.patch, peak.maxStressRatio, peak.t, r.steps.back().maxStressRatio));
    exporter::DeploymentAnimation animation;
    animation.name = fmt::format("P{}", d.patch);
    for (const auto& s : r.steps) animation.frames.push_back({s.t, s.contactPoints});
    animations.push_back(std::move(animation));
  }
  section["patches"] = patches;
  section["joined"] = joiningJson(joining);
  if (!state.generalised.empty())
    section["generalised_patches"] =
        "not deployed along a support path: each joins as its own simulation left it (its members "
        "are held at both ends and fixed to the ring one by one, which no synchronised straight "
        "path models)";
  if (!joining.failure.empty())
    state.failures.push_back("deployment: joining the patches: " + joining.failure);
  if (joining.result) {
    const rods::DeploymentResult& r = *joining.result;
    if (!r.completed) state.failures.push_back("deployment: joining the patches: " + r.reason);
    if (r.snaps > 0)
      state.report.warn(fmt::format(
          "deployment: joining the patches snaps through at {} step(s) (first at t = {:.3f})",
          r.snaps,
          std::find_if(r.steps.begin(), r.steps.end(), [](const auto& s) { return s.snap; })->t));
    const auto& peak = r.steps[r.peakStep];
    if (peak.maxStressRatio > 1.0)
      state.report.warn(fmt::format(
          "deployment: joining the patches: stress ratio {:.2f} at t = {:.3f} (end state {:.2f})",
          peak.maxStressRatio, peak.t, r.steps.back().maxStressRatio));
    exporter::DeploymentAnimation animation;
    animation.name = "joined";
    for (const auto& s : r.steps) animation.frames.push_back({s.t, s.contactPoints});
    animations.push_back(std::move(animation));
  }
  section["seconds"] = watch.seconds();
  state.report.section("deployment") = section;
  writeFileAtomically(state.staging / "deployment.csv", csvOf(runs, joining));
  writeFileAtomically(state.staging / "deployment.svg", chartSvg(runs, joining));
  if (!animations.empty())
    writeFileAtomically(state.staging / "deployment.glb", exporter::deploymentGlbBytes(animations));
}

}  // namespace egg::pipeline
