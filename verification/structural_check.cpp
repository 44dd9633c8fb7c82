#include "verification/structural_check.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/timing.hpp"
#include "fabrication/stress.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::verification {

namespace fs = std::filesystem;

FeModel feModelFromRods(const rods::RodNetwork& network, const rods::SimulationRun& deployed,
                        const MaterialProperties& strength, const RodNames& names) {
  rods::validateNetwork(network);
  if (deployed.centrelines.size() != network.rods.size() ||
      deployed.normals.size() != network.rods.size())
    throw InvalidInput("FE model: the deployed state does not match the rod network");
  FeModel model;
  for (size_t r = 0; r < network.rods.size(); ++r) {
    const rods::Rod& rod = network.rods[r];
    int material = -1;
    for (size_t m = 0; m < model.materials.size(); ++m)
      if (model.materials[m].youngsModulusPa == rod.material.youngsModulusPa &&
          model.materials[m].densityKgM3 == rod.material.densityKgM3)
        material = static_cast<int>(m);
    if (material < 0) {
      material = static_cast<int>(model.materials.size());
      model.materials.push_back({fmt::format("LAMELLA_{}", material), rod.material.youngsModulusPa,
                                 0.0, rod.material.densityKgM3, strength.bendingStrengthPa});
    }
    FeLamella l;
    l.name = r < names.rods.size() ? names.rods[r] : fmt::format("L{}", r);
    l.group = r < names.groups.size() ? names.groups[r] : std::string();
    l.material = material;
    l.restLengthM = rod.lengthM;
    l.widthM = rod.section.widthM;
    l.thicknessM = rod.section.thicknessM;
    l.centreline = deployed.centrelines[r];
    l.normals = deployed.normals[r];
    model.lamellas.push_back(std::move(l));
  }
  for (size_t c = 0; c < network.connections.size(); ++c) {
    const rods::Connection& conn = network.connections[c];
    double sA = conn.sAM, sB = conn.sBM;
    if (c < deployed.boltPositionsM.size())
      sA = deployed.boltPositionsM[c][0], sB = deployed.boltPositionsM[c][1];
    FeBolt bolt;
    bolt.name = c < names.connections.size() ? names.connections[c] : fmt::format("C{}", c);
    const bool aLower = network.rods[conn.rodA].layer == 0;
    bolt.lower = aLower ? FeAt{conn.rodA, sA} : FeAt{conn.rodB, sB};
    bolt.upper = aLower ? FeAt{conn.rodB, sB} : FeAt{conn.rodA, sA};
    model.bolts.push_back(bolt);
  }
  for (size_t a = 0; a < network.anchors.size(); ++a) {
    const rods::Anchor& anchor = network.anchors[a];
    FeSupport s;
    s.name = fmt::format("S{}", a);
    s.at = {anchor.rod, anchor.sM};
    s.kind = SupportKind::Hinge;  // position and normal held, free about the normal (E_a)
    s.axis = anchor.normal;
    model.supports.push_back(s);
  }
  return model;
}

std::string bucklingVerdict(double firstFactor, bool firstOrderCases) {
  if (!(firstFactor > 0)) return "no positive buckling factor found under the governing case";
  if (firstFactor >= 10.0)
    return fmt::format(
        "alpha_cr = {:.3g} >= 10: buckling does not govern; a first-order analysis suffices "
        "(EN 1993-1-1 5.2.1(3))",
        firstFactor);
  // Below 10 the load cases' own results are not the answer where they were first order.
  const std::string firstOrder =
      firstOrderCases ? "; the load cases here were solved first order (the model is above "
                        "loads.max_nonlinear_fe_elements), so run their nonlinear decks "
                        "(fem/nl_<case>.inp) before relying on them"
                      : "";
  if (firstFactor >= 3.0)
    return fmt::format(
        "alpha_cr = {:.3g} in [3, 10): second-order effects matter; design with a geometrically "
        "nonlinear analysis with imperfections (EN 1993-1-1 5.2.1(3), 5.2.2(5)B){}",
        firstFactor, firstOrder);
  return fmt::format(
      "alpha_cr = {:.3g} < 3: too close to buckling for the amplification method "
      "(EN 1993-1-1 5.2.2(5)B){}; the structure needs stiffening{}",
      firstFactor,
      firstFactor < 1.0 ? ", and below 1 it buckles under the load case itself (linear buckling)"
                        : "",
      firstOrder);
}

namespace {

void writeText(const fs::path& file, const std::string& text) { writeFileAtomically(file, text); }

// Axial fibre stress: the stress tensor (frd order xx, yy, zz, xy, yz, zx) along direction t.
double axialStress(const std::vector<double>& s, const Eigen::Vector3d& t) {
  if (s.size() < 6) return 0.0;
  return s[0] * t.x() * t.x() + s[1] * t.y() * t.y() + s[2] * t.z() * t.z() +
         2.0 * (s[3] * t.x() * t.y() + s[4] * t.y() * t.z() + s[5] * t.z() * t.x());
}

struct Deployment {
  std::vector<fabrication::LamellaStress> perLamella;
};

Deployment deploymentOf(const FeModel& model) {
  Deployment d;
  for (const FeLamella& l : model.lamellas) {
    MaterialProperties m;
    m.youngsModulusPa = model.materials[l.material].youngsModulusPa;
    m.shearModulusPa = m.youngsModulusPa / 16.0;  // torsion unused here
    m.bendingStrengthPa = model.materials[l.material].bendingStrengthPa;
    m.shearStrengthPa = 1.0;
    d.perLamella.push_back(
        fabrication::lamellaStress(l.centreline, &l.normals, l.thicknessM, m,
                                   fabrication::curvatureWindowM(l.centreline, l.widthM)));
  }
  return d;
}

CaseResult readCase(const FeModel& model, const FeMesh& mesh, const fs::path& folder,
                    const LoadCase& loadCase, const std::vector<Eigen::Vector3d>& loads,
                    const Deployment& deployment) {
  CaseResult out;
  out.name = loadCase.name;
  const DatResults dat = readDat(folder / (loadCase.name + ".dat"));
  const auto disp = dat.displacements.find("NALL");
  const auto rf = dat.forces.find("REACTIONS");
  if (disp == dat.displacements.end() || rf == dat.forces.end())
    throw SolverFailure("ccx " + loadCase.name + ": no displacements or reactions in its .dat");
  out.displacements.assign(mesh.nodes.size(), Eigen::Vector3d::Zero());
  for (const auto& [node, u] : disp->second)
    if (node >= 1 && node <= static_cast<int>(mesh.nodes.size())) out.displacements[node - 1] = u;
  for (const auto& e : mesh.elements) {
    if (e.part != FeMesh::Part::Lamella) continue;
    for (int n : e.nodes)
      if (out.displacements[n - 1].norm() > out.maxDisplacementM)
        out.maxDisplacementM = out.displacements[n - 1].norm(), out.maxDisplacementNode = n;
  }
  for (const auto& f : loads) out.appliedN += f;
  // ccx prints a constrained node's internal force: its reaction plus the load applied there.
  for (int node : mesh.reactionNodes) {
    const auto it = rf->second.find(node);
    if (it == rf->second.end())
      throw SolverFailure(fmt::format("ccx {}: no reaction at node {}", loadCase.name, node));
    out.reactionN += it->second - loads[node - 1];
  }
  const double applied = out.appliedN.norm();
  out.reactionRatio = applied > 0 ? out.reactionN.norm() / applied : 0.0;
  out.equilibriumResidual = applied > 0 ? (out.reactionN + out.appliedN).norm() / applied : 0.0;

  const FrdResults frd = readFrd(folder / (loadCase.name + ".frd"), "STRESS");
  std::vector<LamellaUtilisation> worst(model.lamellas.size());
  for (size_t l = 0; l < model.lamellas.size(); ++l) worst[l].lamella = model.lamellas[l].name;
  for (size_t i = 0; i < mesh.elements.size(); ++i) {
    const auto& e = mesh.elements[i];
    if (e.part != FeMesh::Part::Lamella) continue;
    const auto brick = frd.elements.find(static_cast<int>(i) + 1);
    if (brick == frd.elements.end()) continue;
    const Eigen::Vector3d t =
        (mesh.nodes[e.nodes[2] - 1] - mesh.nodes[e.nodes[0] - 1]).normalized();
    double load = 0.0;
    for (int n : brick->second) {
      const auto s = frd.values.find(n);
      if (s != frd.values.end()) load = std::max(load, std::abs(axialStress(s->second, t)));
    }
    const auto& dep = deployment.perLamella[e.owner];
    const double bend =
        fabrication::maxStressOver(dep.bendingArcM, dep.bendingPa, e.sM[0], e.sM[1]);
    const double fm = model.materials[model.lamellas[e.owner].material].bendingStrengthPa;
    // Conservative: the two add at the worse fibre (their signs are not compared).
    const double u = fm > 0 ? (bend + load) / fm : 0.0;
    if (u >= worst[e.owner].utilisation) worst[e.owner] = {worst[e.owner].lamella, u, bend, load};
  }
  for (const auto& w : worst) out.lamellaUtilisation.push_back(w.utilisation);
  std::sort(worst.begin(), worst.end(),
            [](const auto& a, const auto& b) { return a.utilisation > b.utilisation; });
  if (!worst.empty()) out.maxUtilisation = worst.front().utilisation;
  worst.resize(std::min<size_t>(worst.size(), 10));
  out.top = std::move(worst);
  return out;
}

}  // namespace

CheckResult runCheck(const FeModel& model, const fs::path& folder, const CheckOptions& options) {
  const Stopwatch watch;
  CheckResult out;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw WriteError("cannot create " + folder.string() + ": " + ec.message());
  out.ccxVersion = ccxVersion(folder);
  if (out.ccxVersion.empty()) throw SolverFailure("ccx (CalculiX) is not installed");
  out.mesh = buildMesh(model);
  std::vector<LoadCase> cases = options.cases;
  if (std::none_of(cases.begin(), cases.end(), [](const LoadCase& c) {
        return c.selfWeight && c.uniformPlanPa == 0 && c.pointLoads.empty();
      }))
    cases.insert(cases.begin(), LoadCase{"self_weight", true, 0.0, {}});
  for (const auto& c : cases) {
    if (c.name.empty() || c.name == "model" || c.name == "buckle" ||
        !std::all_of(c.name.begin(), c.name.end(), [](char ch) {
          return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
        }))
      throw InvalidInput("load case name \"" + c.name +
                         "\": letters, digits and underscores, not model/buckle");
  }
  writeText(folder / "model.inp", modelInp(model, out.mesh));
  const int elements = static_cast<int>(out.mesh.elements.size());
  if (options.maxElements > 0 && elements > options.maxElements) {
    for (const LoadCase& c : cases)
      writeText(folder / (c.name + ".inp"),
                caseInp("model.inp", nodalLoads(model, out.mesh, c, options.planAreaM2)));
    if (options.bucklingModes > 0)
      writeText(
          folder / "buckle.inp",
          buckleInp("model.inp", nodalLoads(model, out.mesh, cases.front(), options.planAreaM2),
                    options.bucklingModes));
    out.solved = false;
    out.notSolvedReason = fmt::format(
        "the FE model has {} beam elements, above the {} that ccx is run on here "
        "(loads.max_fe_elements); its decks are written: run `ccx -i {}` (and each other case, "
        "buckle) in the fem folder, or raise the limit",
        elements, options.maxElements, cases.front().name);
    out.seconds = watch.seconds();
    return out;
  }
  const Deployment deployment = deploymentOf(model);
  const bool nonlinear =
      options.maxNonlinearElements <= 0 || elements <= options.maxNonlinearElements;
  std::vector<std::vector<Eigen::Vector3d>> caseLoads;
  for (const LoadCase& c : cases) {
    caseLoads.push_back(nodalLoads(model, out.mesh, c, options.planAreaM2));
    writeText(folder / (c.name + ".inp"), caseInp("model.inp", caseLoads.back(), nonlinear));
    // The nonlinear deck beside a first-order one, for the engineer to run where the buckling
    // factor asks for it.
    if (!nonlinear)
      writeText(folder / ("nl_" + c.name + ".inp"), caseInp("model.inp", caseLoads.back()));
    const CcxOutcome run = runCcx(folder, c.name, options.ccx);
    out.cases.push_back(readCase(model, out.mesh, folder, c, caseLoads.back(), deployment));
    out.cases.back().seconds = run.seconds;
    out.cases.back().nonlinear = nonlinear;
  }
  if (options.bucklingModes > 0) {
    size_t governing = 0;
    for (size_t i = 1; i < out.cases.size(); ++i)
      if (out.cases[i].maxUtilisation > out.cases[governing].maxUtilisation) governing = i;
    out.buckling.loadCase = cases[governing].name;
    writeText(folder / "buckle.inp",
              buckleInp("model.inp", caseLoads[governing], options.bucklingModes));
    out.buckling.seconds = runCcx(folder, "buckle", options.ccx).seconds;
    const DatResults dat = readDat(folder / "buckle.dat");
    out.buckling.factors = dat.bucklingFactors;
    for (const auto& block : dat.displacementBlocks) {
      std::vector<Eigen::Vector3d> mode(out.mesh.nodes.size(), Eigen::Vector3d::Zero());
      double largest = 0.0;
      for (const auto& [node, u] : block)
        if (node >= 1 && node <= static_cast<int>(mode.size()))
          mode[node - 1] = u, largest = std::max(largest, u.norm());
      if (largest > 0)
        for (auto& u : mode) u /= largest;
      out.buckling.modes.push_back(std::move(mode));
    }
    if (out.buckling.factors.empty())
      throw SolverFailure("ccx buckle: no buckling factors in buckle.dat");
    out.buckling.verdict = bucklingVerdict(out.buckling.factors.front(), !nonlinear);
  }
  out.seconds = watch.seconds();
  return out;
}

rods::SimulationRun derWeightless(const rods::RodNetwork& network,
                                  rods::SimulationOptions options) {
  options.compareWithoutNotches = false;
  options.historyEvery = 0;
  options.model.gravity = false;
  rods::SimulationRun weightless = rods::simulateRods(network, nullptr, options);
  if (!weightless.solver.converged)
    throw SolverFailure("rod simulation: the weightless equilibrium did not converge");
  return weightless;
}

DerSelfWeight derSelfWeightFrom(const rods::RodNetwork& network, rods::SimulationRun weightless,
                                rods::SimulationOptions options) {
  DerSelfWeight out;
  out.weightless = std::move(weightless);
  options.compareWithoutNotches = false;
  options.historyEvery = 0;
  rods::RodNetwork start = network;
  rods::startFrom(start, out.weightless);
  options.model.gravity = true;
  options.fastenBoltsUnderLoad = true;
  out.loaded = rods::simulateRods(start, nullptr, options);
  if (!out.loaded.solver.converged)
    throw SolverFailure("rod simulation: the self-weight equilibrium did not converge");
  return out;
}

DerSelfWeight derSelfWeight(const rods::RodNetwork& network, rods::SimulationOptions options) {
  return derSelfWeightFrom(network, derWeightless(network, options), options);
}

SagComparison compareSag(const DerSelfWeight& der, const FeMesh& mesh,
                         const CaseResult& selfWeight) {
  SagComparison out;
  double sum = 0.0;
  for (size_t l = 0; l < mesh.vertexNodes.size(); ++l) {
    for (size_t i = 0; i < mesh.vertexNodes[l].size(); ++i) {
      const int node = mesh.vertexNodes[l][i];
      if (node == 0) continue;
      const Eigen::Vector3d derSag =
          der.loaded.centrelines[l][i] - der.weightless.centrelines[l][i];
      const Eigen::Vector3d& fe = selfWeight.displacements[node - 1];
      const double d = (derSag - fe).norm();
      sum += d * d;
      out.maxM = std::max(out.maxM, d);
      out.derMaxSagM = std::max(out.derMaxSagM, derSag.norm());
      out.feMaxSagM = std::max(out.feMaxSagM, fe.norm());
      ++out.points;
    }
  }
  if (out.points > 0) out.rmsM = std::sqrt(sum / out.points);
  return out;
}

}  // namespace egg::verification
