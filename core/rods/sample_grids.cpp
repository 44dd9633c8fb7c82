#include "core/rods/sample_grids.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace egg::rods {

void CylinderGridParameters::validate() const {
  if (!(radiusM > 0.0)) throw InvalidInput("CylinderGridParameters.radius_m must be > 0");
  if (!(halfAngleRad > 0.0 && halfAngleRad < M_PI / 2.0)) {
    throw InvalidInput("CylinderGridParameters.halfAngle_rad must be in (0, pi/2)");
  }
  if (!(lengthM > 0.0)) throw InvalidInput("CylinderGridParameters.length_m must be > 0");
  if (!(spacingM > 0.0)) throw InvalidInput("CylinderGridParameters.spacing_m must be > 0");
  if (!(notchFraction >= 0.0 && notchFraction < 0.5)) {
    throw InvalidInput("CylinderGridParameters.notchFraction must be in [0, 0.5)");
  }
  if (!(meshEdgeM > 0.0)) throw InvalidInput("CylinderGridParameters.meshEdge_m must be > 0");
}

namespace {

struct Segment {
  int family = 0;  // 0: v = u + c, 1: v = -u + c
  double c = 0.0;
  double u0 = 0.0, u1 = 0.0;  // parameter range in u
};

}  // namespace

SampleGrid cylinderGrid(const CylinderGridParameters& p) {
  p.validate();
  const double radius = p.radiusM, uMax = p.radiusM * p.halfAngleRad, vMax = p.lengthM;
  auto surfacePoint = [&](double u, double v) {
    return Eigen::Vector3d(radius * std::sin(u / radius), v, radius * std::cos(u / radius));
  };
  auto surfaceNormal = [&](double u) {
    return Eigen::Vector3d(std::sin(u / radius), 0.0, std::cos(u / radius));
  };

  // Lines v = +-u + c with c stepped so the perpendicular spacing is spacing_m.
  const double step = p.spacingM * std::sqrt(2.0);
  std::vector<Segment> segments;
  for (int family = 0; family < 2; ++family) {
    const double sign = family == 0 ? 1.0 : -1.0;
    // c ranges over all lines meeting the rectangle [-uMax, uMax] x [0, vMax].
    const double cMin = -uMax, cMax = vMax + uMax;
    for (double c = cMin + 0.5 * step; c < cMax; c += step) {
      // v = sign*u + c in [0, vMax]
      double a = (0.0 - c) / sign, b = (vMax - c) / sign;
      if (a > b) std::swap(a, b);
      const double u0 = std::max(a, -uMax), u1 = std::min(b, uMax);
      if ((u1 - u0) * std::sqrt(2.0) < 0.5 * p.spacingM) continue;
      segments.push_back({family, c, u0, u1});
    }
  }

  SampleGrid grid;
  for (const Segment& s : segments) {
    Rod rod;
    rod.lengthM = std::sqrt(2.0) * (s.u1 - s.u0);
    rod.section = p.section;
    rod.material = p.material;
    rod.layer = s.family;
    const double sign = s.family == 0 ? 1.0 : -1.0;
    const int samples =
        std::max(2, static_cast<int>(std::ceil(rod.lengthM / (0.05 * p.spacingM))) + 1);
    for (int i = 0; i < samples; ++i) {
      const double u = s.u0 + (s.u1 - s.u0) * i / (samples - 1);
      rod.guess.push_back(surfacePoint(u, sign * u + s.c));
      rod.guessNormals.push_back(surfaceNormal(u));
    }
    const int index = static_cast<int>(grid.network.rods.size());
    grid.network.rods.push_back(rod);
    for (double u : {s.u0, s.u1}) {
      Anchor a;
      a.rod = index;
      a.sM = std::sqrt(2.0) * (u - s.u0);
      a.position = surfacePoint(u, sign * u + s.c);
      a.normal = surfaceNormal(u);
      grid.network.anchors.push_back(a);
    }
  }
  const double notch = p.notchFraction * p.spacingM;
  for (size_t i = 0; i < segments.size(); ++i) {
    if (segments[i].family != 0) continue;
    for (size_t j = 0; j < segments.size(); ++j) {
      if (segments[j].family != 1) continue;
      const Segment &a = segments[i], &b = segments[j];
      const double u = 0.5 * (b.c - a.c);  // u + ca = -u + cb
      const double tolerance = 1e-9 * p.spacingM;
      if (u < a.u0 - tolerance || u > a.u1 + tolerance || u < b.u0 - tolerance ||
          u > b.u1 + tolerance)
        continue;
      Connection c;
      c.rodA = static_cast<int>(i);
      c.sAM = std::clamp(std::sqrt(2.0) * (u - a.u0), 0.0, grid.network.rods[i].lengthM);
      c.rodB = static_cast<int>(j);
      c.sBM = std::clamp(std::sqrt(2.0) * (u - b.u0), 0.0, grid.network.rods[j].lengthM);
      // Notches only for inner bolts, and only where the slot stays inside the lamella.
      for (auto [notchPtr, s, length] :
           {std::tuple{&c.notchA, c.sAM, grid.network.rods[i].lengthM},
            std::tuple{&c.notchB, c.sBM, grid.network.rods[j].lengthM}}) {
        if (notch > 0.0 && s - notch > 0.0 && s + notch < length) *notchPtr = Notch{notch, notch};
      }
      grid.network.connections.push_back(c);
    }
  }

  // The surface: a regular triangulation of the development mapped onto the cylinder.
  TriangleSoup soup;
  const int nu = std::max(2, static_cast<int>(std::ceil(2.0 * uMax / p.meshEdgeM)));
  const int nv = std::max(2, static_cast<int>(std::ceil(vMax / p.meshEdgeM)));
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i)
      soup.vertices.push_back(surfacePoint(-uMax + 2.0 * uMax * i / nu, vMax * j / nv));
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      soup.triangles.push_back({a, b, d});
      soup.triangles.push_back({a, d, c});
    }
  }
  grid.surface = meshFromSoup(soup);
  return grid;
}

}  // namespace egg::rods
