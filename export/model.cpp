#include "export/model.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace egg::exporter {

const char* toString(CentrelineSource source) {
  switch (source) {
    case CentrelineSource::JoinedSimulation: return "joined simulation";
    case CentrelineSource::PatchSimulation: return "patch simulation";
    case CentrelineSource::Grid: return "grid (simulation off)";
  }
  return "unknown";
}

double StructureModel::maxDeviationM() const {
  double worst = 0.0;
  for (const auto& l : lamellas)
    for (double d : l.deviationM) worst = std::max(worst, d);
  return worst;
}

namespace {

bool finite(const Eigen::Vector3d& p) { return p.allFinite(); }

void checkMesh(const ModelMesh& mesh, const std::string& what) {
  for (const auto& v : mesh.vertices)
    if (!finite(v)) throw InvalidInput(what + ": a vertex is not finite");
  const int n = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles)
    if (t.minCoeff() < 0 || t.maxCoeff() >= n)
      throw InvalidInput(what + ": a triangle indexes a missing vertex");
}

}  // namespace

void StructureModel::validate() const {
  if (!(widthM > 0.0) || !(thicknessM > 0.0))
    throw InvalidInput(fmt::format("model {}: the lamella section {} x {} m is not positive", name,
                                   widthM, thicknessM));
  checkMesh(surface, "model " + name + ": the design surface");
  for (const auto& l : lamellas) {
    const size_t n = l.centreline.size();
    if (n < 2) throw InvalidInput("lamella " + l.id + ": fewer than two centreline points");
    if (l.normals.size() != n || l.deviationM.size() != n)
      throw InvalidInput(fmt::format("lamella {}: {} points but {} normals and {} deviations", l.id,
                                     n, l.normals.size(), l.deviationM.size()));
    for (size_t i = 0; i < n; ++i) {
      if (!finite(l.centreline[i]) || !finite(l.normals[i]) || !std::isfinite(l.deviationM[i]))
        throw InvalidInput(fmt::format("lamella {}: point {} is not finite", l.id, i));
      if (l.normals[i].norm() < 1e-9)
        throw InvalidInput(fmt::format("lamella {}: the normal at point {} is zero", l.id, i));
    }
  }
  for (const auto& b : bolts)
    if (!finite(b.position) || !finite(b.axis) || b.axis.norm() < 1e-9)
      throw InvalidInput("bolt " + b.id + ": position or axis is not finite");
  for (const auto& s : supports) checkMesh(s.solid, "support " + s.id);
}

namespace {

// Unit tangent at point i (central differences), and the normal made orthogonal to it.
std::pair<Eigen::Vector3d, Eigen::Vector3d> frameAt(const ModelLamella& l, size_t i) {
  const size_t n = l.centreline.size();
  const size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
  Eigen::Vector3d t = l.centreline[b] - l.centreline[a];
  // Coinciding points: the nearest distinct neighbours along the lamella.
  for (size_t lo = a, hi = b; t.norm() < 1e-12 && (lo > 0 || hi + 1 < n);) {
    if (lo > 0) --lo;
    if (hi + 1 < n) ++hi;
    t = l.centreline[hi] - l.centreline[lo];
  }
  if (t.norm() < 1e-12) throw InvalidInput("lamella " + l.id + ": all centreline points coincide");
  t.normalize();
  Eigen::Vector3d normal = l.normals[i] - l.normals[i].dot(t) * t;
  if (normal.norm() < 1e-9)
    throw InvalidInput(
        fmt::format("lamella {}: the normal at point {} is along the lamella", l.id, i));
  return {t, normal.normalized()};
}

}  // namespace

Ribbon ribbonOf(const ModelLamella& lamella, double widthM, double thicknessM) {
  const size_t n = lamella.centreline.size();
  const double hw = widthM / 2.0, ht = thicknessM / 2.0;
  // Corners c0..c3 of the section at every station: (-b,-n), (+b,-n), (+b,+n), (-b,+n), with
  // b = t x n the width direction; each side k runs from c_k to c_{k+1}.
  std::vector<std::array<Eigen::Vector3d, 4>> corners(n);
  std::vector<std::array<Eigen::Vector3d, 4>> sideNormals(n);
  std::vector<Eigen::Vector3d> tangents(n);
  for (size_t i = 0; i < n; ++i) {
    const auto [t, nrm] = frameAt(lamella, i);
    const Eigen::Vector3d b = t.cross(nrm);
    const Eigen::Vector3d& p = lamella.centreline[i];
    corners[i] = {p - hw * b - ht * nrm, p + hw * b - ht * nrm, p + hw * b + ht * nrm,
                  p - hw * b + ht * nrm};
    sideNormals[i] = {-nrm, b, nrm, -b};
    tangents[i] = t;
  }
  Ribbon r;
  auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& normal, int station) {
    r.mesh.vertices.push_back(p);
    r.normals.push_back(normal);
    r.station.push_back(station);
    return static_cast<int>(r.mesh.vertices.size()) - 1;
  };
  for (int side = 0; side < 4; ++side) {
    const int first = static_cast<int>(r.mesh.vertices.size());
    for (size_t i = 0; i < n; ++i) {
      add(corners[i][side], sideNormals[i][side], static_cast<int>(i));
      add(corners[i][(side + 1) % 4], sideNormals[i][side], static_cast<int>(i));
    }
    for (size_t i = 0; i + 1 < n; ++i) {
      const int a0 = first + 2 * static_cast<int>(i), b0 = a0 + 1, a1 = a0 + 2, b1 = a0 + 3;
      r.mesh.triangles.emplace_back(a0, a1, b0);  // outward: t x (c_{k+1} - c_k)
      r.mesh.triangles.emplace_back(b0, a1, b1);
    }
  }
  for (int end = 0; end < 2; ++end) {
    const size_t i = end == 0 ? 0 : n - 1;
    const Eigen::Vector3d outward = end == 0 ? -tangents[i] : tangents[i];
    int c[4];
    for (int k = 0; k < 4; ++k) c[k] = add(corners[i][k], outward, static_cast<int>(i));
    if (end == 0) {
      r.mesh.triangles.emplace_back(c[0], c[1], c[2]);
      r.mesh.triangles.emplace_back(c[0], c[2], c[3]);
    } else {
      r.mesh.triangles.emplace_back(c[0], c[2], c[1]);
      r.mesh.triangles.emplace_back(c[0], c[3], c[2]);
    }
  }
  return r;
}

ModelMesh boltSolid(const ModelBolt& bolt, double diameterM, double lengthM) {
  const Eigen::Vector3d a = bolt.axis.normalized();
  const Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  const double r = diameterM / 2.0, h = lengthM / 2.0;
  ModelMesh m;
  for (int level = 0; level < 2; ++level)
    for (int k = 0; k < 6; ++k) {
      const double th = k * M_PI / 3.0;
      m.vertices.push_back(bolt.position + r * (std::cos(th) * e1 + std::sin(th) * e2) +
                           (level == 0 ? -h : h) * a);
    }
  for (int k = 0; k < 6; ++k) {
    const int k1 = (k + 1) % 6;
    m.triangles.emplace_back(k, k1, 6 + k1);
    m.triangles.emplace_back(k, 6 + k1, 6 + k);
  }
  for (int k = 1; k + 1 < 6; ++k) {
    m.triangles.emplace_back(6, 6 + k, 6 + k + 1);  // top, seen from +axis
    m.triangles.emplace_back(0, k + 1, k);          // bottom
  }
  return m;
}

std::map<int, ModelMesh> boltMeshesByPatch(const StructureModel& model) {
  std::map<int, ModelMesh> bolts;
  for (const auto& b : model.bolts) {
    ModelMesh& all = bolts[b.patch];
    const ModelMesh one = boltSolid(b, model.boltDiameterM, 2.0 * model.thicknessM);
    const int base = static_cast<int>(all.vertices.size());
    all.vertices.insert(all.vertices.end(), one.vertices.begin(), one.vertices.end());
    for (const auto& t : one.triangles)
      all.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  }
  return bolts;
}

Eigen::Vector3d deviationColour(double deviationM, double maxM) {
  // Viridis at 0, 1/4, 1/2, 3/4, 1 (sRGB), converted to linear RGB for glTF's COLOR_0.
  static const std::array<Eigen::Vector3d, 5> stops{
      Eigen::Vector3d(0.267, 0.005, 0.329), Eigen::Vector3d(0.230, 0.322, 0.546),
      Eigen::Vector3d(0.128, 0.567, 0.551), Eigen::Vector3d(0.369, 0.789, 0.383),
      Eigen::Vector3d(0.993, 0.906, 0.144)};
  const double x = maxM > 0.0 ? std::clamp(deviationM / maxM, 0.0, 1.0) : 0.0;
  const double f = x * (stops.size() - 1);
  const size_t k = std::min(static_cast<size_t>(f), stops.size() - 2);
  const Eigen::Vector3d srgb = stops[k] + (f - k) * (stops[k + 1] - stops[k]);
  return srgb.unaryExpr(
      [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); });
}

}  // namespace egg::exporter
