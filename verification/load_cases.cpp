#include "verification/load_cases.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>

#include <cmath>

namespace egg::verification {

namespace {

void spread(std::vector<Eigen::Vector3d>& loads, const FeMesh::Element& e,
            const Eigen::Vector3d& total) {
  loads[e.nodes[0] - 1] += total / 6.0;
  loads[e.nodes[1] - 1] += total * (2.0 / 3.0);
  loads[e.nodes[2] - 1] += total / 6.0;
}

void cloads(std::string& out, const std::vector<Eigen::Vector3d>& loads) {
  out += "*CLOAD\n";
  for (size_t i = 0; i < loads.size(); ++i)
    for (int d = 0; d < 3; ++d)
      if (loads[i][d] != 0.0) out += fmt::format("{}, {}, {:.12g}\n", i + 1, d + 1, loads[i][d]);
}

}  // namespace

std::vector<Eigen::Vector3d> nodalLoads(const FeModel& model, const FeMesh& mesh,
                                        const LoadCase& loadCase, double planAreaM2) {
  std::vector<Eigen::Vector3d> loads(mesh.nodes.size(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d down(0, 0, -1);
  if (loadCase.selfWeight) {
    for (const auto& e : mesh.elements) {
      if (e.part != FeMesh::Part::Lamella) continue;
      const FeLamella& l = model.lamellas[e.owner];
      const double weight = model.materials[l.material].densityKgM3 * model.gravityMPerS2 *
                            l.widthM * l.thicknessM * e.lengthM;
      spread(loads, e, weight * down);
    }
  }
  if (loadCase.uniformPlanPa != 0.0) {
    if (!(planAreaM2 > 0))
      throw InvalidInput("load case " + loadCase.name +
                         ": a uniform plan load needs the plan area (> 0 m^2)");
    double planLength = 0.0;
    std::vector<double> lengths(mesh.elements.size(), 0.0);
    for (size_t i = 0; i < mesh.elements.size(); ++i) {
      const auto& e = mesh.elements[i];
      if (e.part != FeMesh::Part::Lamella) continue;
      const auto& a = mesh.nodes[e.nodes[0] - 1];
      const auto& m = mesh.nodes[e.nodes[1] - 1];
      const auto& b = mesh.nodes[e.nodes[2] - 1];
      lengths[i] = (m - a).head<2>().norm() + (b - m).head<2>().norm();
      planLength += lengths[i];
    }
    if (!(planLength > 0))
      throw InvalidInput("load case " + loadCase.name + ": the lamellas have no length in plan");
    const double total = loadCase.uniformPlanPa * planAreaM2;
    for (size_t i = 0; i < mesh.elements.size(); ++i)
      if (lengths[i] > 0) spread(loads, mesh.elements[i], total * lengths[i] / planLength * down);
  }
  for (const PointLoad& p : loadCase.pointLoads) {
    size_t b = 0;
    while (b < model.bolts.size() && model.bolts[b].name != p.bolt) ++b;
    if (b == model.bolts.size())
      throw InvalidInput("load case " + loadCase.name + ": no connection named \"" + p.bolt + "\"");
    loads[mesh.boltNodes[b][1] - 1] += p.forceN;  // on the upper lamella, where a load sits
  }
  return loads;
}

std::string caseInp(const std::string& modelFile, const std::vector<Eigen::Vector3d>& loads,
                    bool nonlinear) {
  std::string out = "*INCLUDE, INPUT=" + modelFile + "\n";
  if (nonlinear) {
    // Residual 1e-8 of the average force (ccx's default is 5e-3, which leaves reactions off the
    // load by ~1e-5 relative on a cantilever, measured).
    out += "*STEP, NLGEOM, INC=200\n*STATIC\n0.25, 1.0, 1e-5, 0.5\n";
    out += "*CONTROLS, PARAMETERS=FIELD\n1e-8, 1e-6\n";
  } else {
    out += "*STEP\n*STATIC\n";
  }
  cloads(out, loads);
  out += "*NODE PRINT, NSET=NALL\nU\n*NODE PRINT, NSET=REACTIONS\nRF\n";
  out += "*NODE FILE\nU\n*EL FILE\nS\n*END STEP\n";
  return out;
}

std::string buckleInp(const std::string& modelFile, const std::vector<Eigen::Vector3d>& loads,
                      int modes) {
  std::string out = "*INCLUDE, INPUT=" + modelFile + "\n";
  out += fmt::format("*STEP\n*BUCKLE\n{}\n", modes);
  cloads(out, loads);
  out += "*NODE PRINT, NSET=NALL\nU\n*NODE FILE\nU\n*END STEP\n";
  return out;
}

}  // namespace egg::verification
