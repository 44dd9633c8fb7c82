#include "verification/fe_model.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::verification {

const char* toString(SupportKind kind) {
  switch (kind) {
    case SupportKind::Pin: return "pin";
    case SupportKind::Hinge: return "hinge";
    case SupportKind::Clamp: return "clamp";
  }
  return "unknown";
}

namespace {

bool validName(const std::string& name) {
  if (name.empty() || name.size() > 60) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

void checkAt(const FeModel& model, const FeAt& at, const std::string& what) {
  if (at.lamella < 0 || at.lamella >= static_cast<int>(model.lamellas.size()))
    throw InvalidInput(fmt::format("{}: lamella {} does not exist", what, at.lamella));
  const FeLamella& l = model.lamellas[at.lamella];
  if (!(at.sM >= -1e-9 * l.restLengthM && at.sM <= l.restLengthM * (1 + 1e-9)))
    throw InvalidInput(fmt::format("{}: s = {} m lies outside lamella {} (0 .. {} m)", what, at.sM,
                                   l.name, l.restLengthM));
}

// Position and normal on a lamella at vertex parameter u (0 .. vertices-1), linear between
// vertices.
Eigen::Vector3d along(const std::vector<Eigen::Vector3d>& points, double u) {
  const int last = static_cast<int>(points.size()) - 1;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, last - 1);
  const double f = u - i;
  return (1 - f) * points[i] + f * points[i + 1];
}

double paramOf(const FeLamella& l, double sM) {
  const double n = static_cast<double>(l.centreline.size() - 1);
  return std::clamp(sM / l.restLengthM * n, 0.0, n);
}

Eigen::Vector3d across(const Eigen::Vector3d& direction, const Eigen::Vector3d& hint) {
  Eigen::Vector3d a = hint - hint.dot(direction) * direction;
  if (a.norm() < 1e-6 * hint.norm() || hint.norm() == 0) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    Eigen::Index k = 0;
    direction.cwiseAbs().minCoeff(&k);
    e[k] = 1.0;
    a = e - e.dot(direction) * direction;
  }
  return a.normalized();
}

struct Mandatory {
  double u;
  int node = 0;
};

}  // namespace

void FeModel::validate() const {
  if (materials.empty()) throw InvalidInput("FE model: no material");
  for (const auto& m : materials) {
    if (!validName(m.name)) throw InvalidInput("FE model: bad material name \"" + m.name + "\"");
    if (!(m.youngsModulusPa > 0) || !(m.densityKgM3 >= 0) || !(m.poissonRatio > -1) ||
        !(m.poissonRatio < 0.5))
      throw InvalidInput("FE model: material " + m.name + " needs E > 0, rho >= 0, -1 < nu < 0.5");
  }
  if (lamellas.empty()) throw InvalidInput("FE model: no lamella");
  for (const auto& l : lamellas) {
    if (!validName(l.name)) throw InvalidInput("FE model: bad lamella name \"" + l.name + "\"");
    if (!l.group.empty() && !validName(l.group))
      throw InvalidInput("FE model: lamella " + l.name + ": bad group name \"" + l.group + "\"");
    if (l.material < 0 || l.material >= static_cast<int>(materials.size()))
      throw InvalidInput("FE model: lamella " + l.name + ": no material " +
                         std::to_string(l.material));
    if (l.centreline.size() < 2 || l.normals.size() != l.centreline.size())
      throw InvalidInput("FE model: lamella " + l.name +
                         " needs >= 2 centreline points and one normal per point");
    if (!(l.restLengthM > 0) || !(l.widthM > 0) || !(l.thicknessM > 0))
      throw InvalidInput("FE model: lamella " + l.name + " needs length, width, thickness > 0");
  }
  for (const auto& b : bolts) {
    if (!validName(b.name)) throw InvalidInput("FE model: bad bolt name \"" + b.name + "\"");
    checkAt(*this, b.lower, "bolt " + b.name);
    checkAt(*this, b.upper, "bolt " + b.name);
    if (b.lower.lamella == b.upper.lamella)
      throw InvalidInput("FE model: bolt " + b.name + " joins lamella " +
                         lamellas[b.lower.lamella].name + " to itself");
  }
  for (const auto& s : supports) {
    if (!validName(s.name)) throw InvalidInput("FE model: bad support name \"" + s.name + "\"");
    checkAt(*this, s.at, "support " + s.name);
    if (s.kind != SupportKind::Pin && !(s.axis.norm() > 0))
      throw InvalidInput("FE model: support " + s.name + " needs an axis");
  }
  if (!(boltDiameterM > 0)) throw InvalidInput("FE model: bolt diameter must be > 0");
}

FeMesh buildMesh(const FeModel& model) {
  model.validate();
  FeMesh mesh;
  auto addNode = [&](const Eigen::Vector3d& p) {
    mesh.nodes.push_back(p);
    return static_cast<int>(mesh.nodes.size());
  };
  const int lamellaCount = static_cast<int>(model.lamellas.size());
  // Per lamella the points that must be nodes: bolts and supports.
  std::vector<std::vector<Mandatory>> mandatory(lamellaCount);
  for (const auto& b : model.bolts) {
    mandatory[b.lower.lamella].push_back({paramOf(model.lamellas[b.lower.lamella], b.lower.sM)});
    mandatory[b.upper.lamella].push_back({paramOf(model.lamellas[b.upper.lamella], b.upper.sM)});
  }
  for (const auto& s : model.supports)
    mandatory[s.at.lamella].push_back({paramOf(model.lamellas[s.at.lamella], s.at.sM)});

  mesh.lamellaNodes.resize(lamellaCount);
  mesh.vertexNodes.resize(lamellaCount);
  std::vector<std::vector<double>> nodeParams(lamellaCount);
  constexpr double kMerge = 0.02;  // a bolt this close (in edges) to a vertex uses the vertex
  constexpr double kGiveWay = 0.3;
  for (int l = 0; l < lamellaCount; ++l) {
    const FeLamella& lam = model.lamellas[l];
    const int n = static_cast<int>(lam.centreline.size());
    std::vector<double> params;
    for (const auto& m : mandatory[l]) params.push_back(m.u);
    std::sort(params.begin(), params.end());
    params.erase(std::unique(params.begin(), params.end(),
                             [](double a, double b) { return std::abs(a - b) < 1e-9; }),
                 params.end());
    std::vector<double> all;
    mesh.vertexNodes[l].assign(n, 0);
    std::vector<int> vertexAt(n, -1);
    for (double& u : params) {  // snap to a vertex right next to it
      const double r = std::round(u);
      if (std::abs(u - r) < kMerge) u = r;
    }
    for (int i = 0; i < n; ++i) {
      const bool end = i == 0 || i == n - 1;
      bool keep = true;
      for (double u : params)
        if (std::abs(u - i) < kGiveWay && std::abs(u - i) > 0 && !end) keep = false;
      if (keep) all.push_back(i);
    }
    all.insert(all.end(), params.begin(), params.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end(),
                          [](double a, double b) { return std::abs(a - b) < 1e-12; }),
              all.end());
    for (double u : all) {
      const int id = addNode(along(lam.centreline, u));
      mesh.lamellaNodes[l].push_back(id);
      nodeParams[l].push_back(u);
      if (u == std::round(u)) mesh.vertexNodes[l][static_cast<int>(u)] = id;
    }
    const double edge = lam.restLengthM / (n - 1);
    for (size_t k = 0; k + 1 < all.size(); ++k) {
      const double um = 0.5 * (all[k] + all[k + 1]);
      FeMesh::Element e;
      e.nodes = {mesh.lamellaNodes[l][k], addNode(along(lam.centreline, um)),
                 mesh.lamellaNodes[l][k + 1]};
      e.part = FeMesh::Part::Lamella;
      e.owner = l;
      const Eigen::Vector3d& a = mesh.nodes[e.nodes[0] - 1];
      const Eigen::Vector3d& m = mesh.nodes[e.nodes[1] - 1];
      const Eigen::Vector3d& b = mesh.nodes[e.nodes[2] - 1];
      e.lengthM = (m - a).norm() + (b - m).norm();
      if (!(e.lengthM > 0))
        throw InvalidInput(fmt::format("FE model: lamella {} has coinciding points", lam.name));
      e.sectionAxis1 = across((b - a).normalized(), along(lam.normals, um));
      e.sM = {all[k] * edge, all[k + 1] * edge};
      mesh.elements.push_back(e);
    }
  }
  auto nodeAt = [&](const FeAt& at) {
    const double u = paramOf(model.lamellas[at.lamella], at.sM);
    const auto& ps = nodeParams[at.lamella];
    size_t best = 0;
    for (size_t k = 1; k < ps.size(); ++k)
      if (std::abs(ps[k] - u) < std::abs(ps[best] - u)) best = k;
    return mesh.lamellaNodes[at.lamella][best];
  };
  for (size_t i = 0; i < model.bolts.size(); ++i) {
    const FeBolt& bolt = model.bolts[i];
    const int a = nodeAt(bolt.lower), b = nodeAt(bolt.upper);
    mesh.boltNodes.push_back({a, b});
    const Eigen::Vector3d pa = mesh.nodes[a - 1], pb = mesh.nodes[b - 1];
    if ((pb - pa).norm() < 1e-9)
      throw InvalidInput("FE model: bolt " + bolt.name + " joins two coinciding points");
    FeMesh::Element e;
    e.nodes = {a, addNode(0.5 * (pa + pb)), b};
    e.part = FeMesh::Part::Bolt;
    e.owner = static_cast<int>(i);
    e.lengthM = (pb - pa).norm();
    e.sectionAxis1 = across((pb - pa).normalized(), Eigen::Vector3d::Zero());
    mesh.elements.push_back(e);
  }
  for (size_t i = 0; i < model.supports.size(); ++i) {
    const FeSupport& s = model.supports[i];
    const int node = nodeAt(s.at);
    mesh.supportNodes.push_back(node);
    if (s.kind == SupportKind::Pin) {
      mesh.reactionNodes.push_back(node);
      mesh.reactionSupport.push_back(static_cast<int>(i));
      continue;
    }
    // Arms: a hinge is a stiff beam through the node along the axis, pinned at both ends: the
    // node's translations and its rotations across the axis are held, the one about it is free.
    const double arm = model.lamellas[s.at.lamella].widthM;
    const Eigen::Vector3d p = mesh.nodes[node - 1];
    const Eigen::Vector3d d = s.axis.normalized();
    std::vector<Eigen::Vector3d> ends{p - arm * d, p + arm * d};
    if (s.kind == SupportKind::Clamp) ends.push_back(p + arm * across(d, s.secondAxis));
    for (const Eigen::Vector3d& q : ends) {
      FeMesh::Element e;
      const int far = addNode(q);
      e.nodes = {far, addNode(0.5 * (p + q)), node};
      e.part = FeMesh::Part::SupportArm;
      e.owner = static_cast<int>(i);
      e.lengthM = arm;
      e.sectionAxis1 = across((p - q).normalized(), Eigen::Vector3d::Zero());
      mesh.elements.push_back(e);
      mesh.reactionNodes.push_back(far);
      mesh.reactionSupport.push_back(static_cast<int>(i));
    }
  }
  return mesh;
}

namespace {

void idLines(std::string& out, const std::vector<int>& ids) {
  for (size_t i = 0; i < ids.size(); ++i)
    out += fmt::format("{}{}", ids[i], (i % 16 == 15 || i + 1 == ids.size()) ? "\n" : ", ");
}

void material(std::string& out, const FeMaterial& m) {
  out += fmt::format("*MATERIAL, NAME={}\n*ELASTIC\n{:.9g}, {:.9g}\n*DENSITY\n{:.9g}\n", m.name,
                     m.youngsModulusPa, m.poissonRatio, m.densityKgM3);
}

}  // namespace

std::string modelInp(const FeModel& model, const FeMesh& mesh) {
  std::string out = "** eggshell: the deployed grid as a beam model (docs/verification.md)\n";
  out += "** units: m, N, Pa, kg/m^3\n*NODE, NSET=NALL\n";
  for (size_t i = 0; i < mesh.nodes.size(); ++i)
    out += fmt::format("{}, {:.12g}, {:.12g}, {:.12g}\n", i + 1, mesh.nodes[i].x(),
                       mesh.nodes[i].y(), mesh.nodes[i].z());
  out += "*ELEMENT, TYPE=B32R, ELSET=EALL\n";
  for (size_t i = 0; i < mesh.elements.size(); ++i) {
    const auto& e = mesh.elements[i];
    out += fmt::format("{}, {}, {}, {}\n", i + 1, e.nodes[0], e.nodes[1], e.nodes[2]);
  }
  // Sets: per lamella (elements NAME, nodes NAME_N), per group, per bolt, per support.
  std::vector<std::vector<int>> byLamella(model.lamellas.size()), byBolt(model.bolts.size()),
      arms(model.supports.size());
  std::vector<int> lamellaElements, boltElements, armElements;
  for (size_t i = 0; i < mesh.elements.size(); ++i) {
    const auto& e = mesh.elements[i];
    const int id = static_cast<int>(i) + 1;
    if (e.part == FeMesh::Part::Lamella)
      byLamella[e.owner].push_back(id), lamellaElements.push_back(id);
    if (e.part == FeMesh::Part::Bolt) byBolt[e.owner].push_back(id), boltElements.push_back(id);
    if (e.part == FeMesh::Part::SupportArm) arms[e.owner].push_back(id), armElements.push_back(id);
  }
  auto elset = [&](const std::string& name, const std::vector<int>& ids) {
    if (ids.empty()) return;
    out += "*ELSET, ELSET=" + name + "\n";
    idLines(out, ids);
  };
  auto nset = [&](const std::string& name, const std::vector<int>& ids) {
    if (ids.empty()) return;
    out += "*NSET, NSET=" + name + "\n";
    idLines(out, ids);
  };
  elset("LAMELLAS", lamellaElements);
  elset("BOLTS", boltElements);
  elset("SUPPORT_ARMS", armElements);
  std::vector<std::string> groups;
  for (size_t l = 0; l < model.lamellas.size(); ++l) {
    elset(model.lamellas[l].name, byLamella[l]);
    nset(model.lamellas[l].name + "_N", mesh.lamellaNodes[l]);
    const std::string& g = model.lamellas[l].group;
    if (!g.empty() && std::find(groups.begin(), groups.end(), g) == groups.end())
      groups.push_back(g);
  }
  for (const std::string& g : groups) {
    std::vector<int> ids;
    for (size_t l = 0; l < model.lamellas.size(); ++l)
      if (model.lamellas[l].group == g)
        ids.insert(ids.end(), byLamella[l].begin(), byLamella[l].end());
    elset(g, ids);
  }
  for (size_t b = 0; b < model.bolts.size(); ++b) {
    elset(model.bolts[b].name, byBolt[b]);
    nset(model.bolts[b].name + "_N", {mesh.boltNodes[b][0], mesh.boltNodes[b][1]});
  }
  for (size_t s = 0; s < model.supports.size(); ++s) {
    nset(model.supports[s].name + "_N", {mesh.supportNodes[s]});
    elset(model.supports[s].name + "_ARMS", arms[s]);
  }
  nset("REACTIONS", mesh.reactionNodes);
  for (const auto& m : model.materials) material(out, m);
  material(out, model.boltMaterial);
  // One section per lamella element: its 1-axis is the lamella normal there (thickness t along
  // it, width w across), so the section turns with the lamella.
  for (size_t i = 0; i < mesh.elements.size(); ++i) {
    const auto& e = mesh.elements[i];
    const Eigen::Vector3d& a = e.sectionAxis1;
    out += fmt::format("*ELSET, ELSET=S{}\n{}\n", i + 1, i + 1);
    if (e.part == FeMesh::Part::Lamella) {
      const FeLamella& l = model.lamellas[e.owner];
      out += fmt::format(
          "*BEAM SECTION, ELSET=S{}, MATERIAL={}, SECTION=RECT\n{:.9g}, {:.9g}\n{:.9g}, {:.9g}, "
          "{:.9g}\n",
          i + 1, model.materials[l.material].name, l.thicknessM, l.widthM, a.x(), a.y(), a.z());
    } else if (e.part == FeMesh::Part::Bolt) {
      // SECTION=CIRC takes the diameter in both directions (checked against a cantilever).
      out += fmt::format(
          "*BEAM SECTION, ELSET=S{}, MATERIAL={}, SECTION=CIRC\n{:.9g}, {:.9g}\n{:.9g}, {:.9g}, "
          "{:.9g}\n",
          i + 1, model.boltMaterial.name, model.boltDiameterM, model.boltDiameterM, a.x(), a.y(),
          a.z());
    } else {
      const double side = model.lamellas[model.supports[e.owner].at.lamella].widthM;
      out += fmt::format(
          "*BEAM SECTION, ELSET=S{}, MATERIAL={}, SECTION=RECT\n{:.9g}, {:.9g}\n{:.9g}, {:.9g}, "
          "{:.9g}\n",
          i + 1, model.boltMaterial.name, side, side, a.x(), a.y(), a.z());
    }
  }
  out += "*BOUNDARY\n";
  for (size_t r = 0; r < mesh.reactionNodes.size(); ++r) {
    const FeSupport& s = model.supports[mesh.reactionSupport[r]];
    for (int d = 0; d < 3; ++d)
      if (s.kind != SupportKind::Pin || s.fixed[d])
        out += fmt::format("{}, {}, {}\n", mesh.reactionNodes[r], d + 1, d + 1);
  }
  return out;
}

}  // namespace egg::verification
