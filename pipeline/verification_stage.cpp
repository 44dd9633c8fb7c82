#include "pipeline/verification_stage.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "core/timing.hpp"
#include "pipeline/verification_figure.hpp"
#include "verification/structural_check.hpp"

#include <fmt/core.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Structure {
  const rods::RodNetwork* network = nullptr;
  const rods::SimulationRun* deployed = nullptr;
  verification::RodNames names;
  std::string what;  // "joined structure" or "patch N"
};

// The joined structure when it ran, else the only simulated patch; null network: neither.
Structure structureOf(const RunState& state) {
  Structure s;
  if (state.joined && state.joinedNetwork) {
    s.network = &state.joinedNetwork->network;
    s.deployed = &*state.joined;
    s.what = "joined structure";
    // Rods and connections come patch after patch (core/rods/joined_network.cpp), the join bolts
    // last; firstRod follows the simulated patches in layout order, then the generalised ones.
    std::vector<int> ids;
    for (const auto& p : state.patches)
      if (p.egg) ids.push_back(p.id);
    for (const auto& g : state.generalised) ids.push_back(g.patchId);
    if (ids.size() != state.joinedNetwork->firstRod.size()) {
      s.network = nullptr;  // cannot be named: not checked (an internal mismatch, said why)
      s.what = fmt::format("the joined network has {} patches, the run {}",
                           state.joinedNetwork->firstRod.size(), ids.size());
      return s;
    }
    const auto& first = state.joinedNetwork->firstRod;
    const int rodCount = static_cast<int>(s.network->rods.size());
    std::vector<int> patchOf(rodCount, -1), localOf(rodCount, 0);
    for (size_t k = 0; k < first.size(); ++k) {
      const int end = k + 1 < first.size() ? first[k + 1] : rodCount;
      for (int r = first[k]; r < end; ++r) patchOf[r] = ids[k], localOf[r] = r - first[k];
    }
    for (int r = 0; r < rodCount; ++r) {
      s.names.rods.push_back(fmt::format("P{}_L{}", patchOf[r], localOf[r]));
      s.names.groups.push_back(fmt::format("P{}", patchOf[r]));
    }
    std::map<int, int> perPatch;
    int joins = 0;
    for (const auto& c : s.network->connections) {
      const int pa = patchOf[c.rodA], pb = patchOf[c.rodB];
      s.names.connections.push_back(pa == pb ? fmt::format("P{}_C{}", pa, perPatch[pa]++)
                                             : fmt::format("J{}", joins++));
    }
    return s;
  }
  const SolvedPatch* only = nullptr;
  int simulated = 0;
  for (const auto& p : state.patches)
    if (p.simulation && p.network) ++simulated, only = &p;
  if (simulated != 1) return s;
  s.network = &*only->network;
  s.deployed = &only->simulation->deployed;
  s.what = fmt::format("patch {}", only->id);
  for (size_t r = 0; r < s.network->rods.size(); ++r) {
    s.names.rods.push_back(fmt::format("P{}_L{}", only->id, r));
    s.names.groups.push_back(fmt::format("P{}", only->id));
  }
  for (size_t c = 0; c < s.network->connections.size(); ++c)
    s.names.connections.push_back(fmt::format("P{}_C{}", only->id, c));
  return s;
}

// Plan area of the design surface: its triangles projected on the ground (z = 0).
double planArea(const TriMesh& mesh) {
  const TriangleSoup soup = soupFromMesh(mesh);
  double area = 0.0;
  for (const auto& t : soup.triangles) {
    const Eigen::Vector3d a = soup.vertices[t[0]], b = soup.vertices[t[1]], c = soup.vertices[t[2]];
    area += 0.5 * std::abs((b - a).head<2>().x() * (c - a).head<2>().y() -
                           (b - a).head<2>().y() * (c - a).head<2>().x());
  }
  return area;
}

std::vector<verification::LoadCase> loadCases(const Scene& scene) {
  std::vector<verification::LoadCase> cases{{"self_weight", true, 0.0, {}}};
  if (scene.loads.uniformKnM2 > 0)
    cases.push_back({"uniform", true, scene.loads.uniformKnM2 * 1e3, {}});
  if (scene.loads.pointLoadKn > 0) {
    verification::LoadCase point{"point", true, 0.0, {}};
    for (const auto& name : scene.loads.pointLoadConnections)
      point.pointLoads.push_back({name, Eigen::Vector3d(0, 0, -scene.loads.pointLoadKn * 1e3)});
    cases.push_back(point);
  }
  return cases;
}

json caseJson(const verification::CaseResult& c) {
  json top = json::array();
  for (const auto& u : c.top)
    top.push_back({{"lamella", u.lamella},
                   {"utilisation", u.utilisation},
                   {"deployment_stress_pa", u.deploymentStressPa},
                   {"load_stress_pa", u.loadStressPa}});
  return {{"name", c.name},
          {"analysis", c.nonlinear ? "nonlinear" : "first_order"},
          {"max_displacement_m", c.maxDisplacementM},
          {"applied_n", {c.appliedN.x(), c.appliedN.y(), c.appliedN.z()}},
          {"reactions_n", {c.reactionN.x(), c.reactionN.y(), c.reactionN.z()}},
          {"reaction_ratio", c.reactionRatio},
          {"equilibrium_residual", c.equilibriumResidual},
          {"max_utilisation", c.maxUtilisation},
          {"top", top},
          {"ccx_seconds", c.seconds}};
}

// ccx's own scratch files (solver statistics, convergence logs) stay out of the run folder.
void removeScratch(const fs::path& folder) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".12d" || ext == ".cvg" || ext == ".sta" || entry.path().filename() == "spooles.out")
      fs::remove(entry.path(), ec);
  }
}

}  // namespace

std::string verificationSkipReason(const RunState& state) {
  if (verification::findCcx().empty())
    return "ccx (CalculiX) is not installed (scripts/install-deps.sh installs calculix-ccx)";
  if (const Structure s = structureOf(state); !s.network)
    return s.what.empty() ? "no single deployed structure: neither a joined run nor exactly one "
                            "simulated patch"
                          : s.what;
  return {};
}

void verificationStage(RunState& state) {
  const Stopwatch watch;
  const Scene& scene = state.scene;
  json& section = state.report.section("verification");
  section = json::object();
  try {
    const Structure s = structureOf(state);
    section["structure"] = s.what;
    state.progress("verification: rod simulation, weightless", 0.9);
    rods::SimulationOptions options = scene.simulation.rods;
    options.historyEvery = 0;
    options.compareWithoutNotches = false;
    rods::RodNetwork start = *s.network;
    rods::startFrom(start, *s.deployed);
    // The weightless equilibrium is the FE model's geometry; the rods' own self-weight solve
    // from it is needed only to compare with a solved FE case (on the Yas, whose model is only
    // written, it took 88 of the stage's 135 s).
    rods::SimulationRun weightless = verification::derWeightless(start, options);
    verification::FeModel model = verification::feModelFromRods(
        *s.network, weightless, materialByName(scene.lamella.material), s.names);
    model.boltDiameterM = scene.fabrication.options.boltDiameterMm / 1000.0;
    verification::CheckOptions check;
    check.cases = loadCases(scene);
    check.planAreaM2 = planArea(state.surface->mesh);
    check.bucklingModes = scene.loads.bucklingModes;
    check.ccx.timeLimitS = scene.loads.ccxTimeLimitS;
    check.ccx.threads = std::max(1, tbb::this_task_arena::max_concurrency());
    check.maxElements = scene.loads.maxFeElements;
    check.maxNonlinearElements = scene.loads.maxNonlinearFeElements;
    state.progress("verification: ccx", 0.93);
    const fs::path folder = state.staging / "fem";
    const verification::CheckResult r = verification::runCheck(model, folder, check);
    removeScratch(folder);
    section["ccx_version"] = r.ccxVersion;
    section["model_file"] = "fem/model.inp";
    section["model"] = {{"nodes", r.mesh.nodes.size()},      {"elements", r.mesh.elements.size()},
                        {"lamellas", model.lamellas.size()}, {"bolts", model.bolts.size()},
                        {"supports", model.supports.size()}, {"plan_area_m2", check.planAreaM2}};
    section["solved"] = r.solved;
    if (!r.solved) {
      // Not a failure: the model is there for the engineer; the run says plainly it is unsolved.
      section["not_solved_reason"] = r.notSolvedReason;
      state.report.warn("verification: not solved: " + r.notSolvedReason);
      section["seconds"] = watch.seconds();
      return;
    }
    state.progress("verification: rod simulation under self-weight", 0.96);
    const verification::DerSelfWeight der =
        verification::derSelfWeightFrom(start, std::move(weightless), options);
    const verification::SagComparison sag = verification::compareSag(der, r.mesh, r.cases[0]);
    json cases = json::array();
    for (const auto& c : r.cases) cases.push_back(caseJson(c));
    section["cases"] = cases;
    section["buckling_case"] = r.buckling.loadCase;
    section["buckling_factors"] = r.buckling.factors;
    section["buckling_verdict"] = r.buckling.verdict;
    section["buckling_ccx_seconds"] = r.buckling.seconds;
    // Too close to buckling for the amplification method (the verdict's own threshold): the run
    // says so where it is read, not only in the section.
    if (!r.buckling.factors.empty() && r.buckling.factors.front() < 3.0)
      state.report.warn("verification: buckling factor " +
                        fmt::format("{:.3g}", r.buckling.factors.front()) + " under case " +
                        r.buckling.loadCase + ": " + r.buckling.verdict);
    section["der_vs_fem"] = {
        {"rms_m", sag.rmsM},
        {"max_m", sag.maxM},
        {"der_max_sag_m", sag.derMaxSagM},
        {"fem_max_sag_m", sag.feMaxSagM},
        {"points", sag.points},
        {"differs_by_construction",
         "the rods are straight at rest and carry the deployment's bending and twist as prestress; "
         "ccx's beams are stress-free in the deployed shape (no prestress stiffness); ccx's "
         "isotropic beams have G = E/2, the rods the material's G; bolts are rigid steel beams in "
         "ccx, penalty springs in the rods (docs/verification.md)"}};
    double worst = 0.0;
    for (const auto& c : r.cases) {
      worst = std::max(worst, c.equilibriumResidual);
      if (c.equilibriumResidual > 1e-6)
        state.failures.push_back(
            fmt::format("verification: case {}: the reactions miss the load by {:.3g} (relative)",
                        c.name, c.equilibriumResidual));
    }
    section["max_equilibrium_residual"] = worst;
    // The figure of report.html's section, also a file beside the decks.
    std::string figure = verificationSvg(r);
    figure.insert(4, " xmlns=\"http://www.w3.org/2000/svg\"");
    writeFileAtomically(folder / "verification.svg", figure);
    section["figure"] = "fem/verification.svg";
  } catch (const Error& e) {
    section["failure"] = e.what();
    state.failures.push_back(std::string("verification: ") + e.what());
  }
  section["seconds"] = watch.seconds();
}

}  // namespace egg::pipeline
