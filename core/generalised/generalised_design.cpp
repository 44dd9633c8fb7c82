// The built generalised grid: traced members, planar layout, rods (see generalised_design.hpp).
#include "core/generalised/generalised_design.hpp"

#include "core/errors.hpp"
#include "core/geodesic/geodesic_intersection.hpp"
#include "core/timing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace egg::generalised {
namespace {

// The unit surface normal at a surface point: the curvature field's vertex normals, interpolated.
Eigen::Vector3d designNormalAt(const GridDomain& domain, const SurfacePoint& point) {
  const auto ids = faceVertices(domain.mesh(), point.face);
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) n += point.barycentric[k] * domain.curvature().normals[ids[k]];
  return n.normalized();
}

// Where the planar centre lines of two lamellas cross, as arc lengths from their starts (clamped
// to the lamellas; parallel lines: the surface fractions).
std::pair<double, double> designPlanarCrossing(const Segment2& g, const Segment2& h, double lambdaG,
                                               double lambdaH) {
  const Eigen::Vector2d dg = g[1] - g[0], dh = h[1] - h[0];
  const double lengthG = dg.norm(), lengthH = dh.norm();
  Eigen::Matrix2d a;
  a << dg, -dh;
  if (std::abs(a.determinant()) < 1e-12 * lengthG * lengthH)
    return {lambdaG * lengthG, lambdaH * lengthH};
  const Eigen::Vector2d t = a.partialPivLu().solve(h[0] - g[0]);
  return {std::clamp(t[0], 0.0, 1.0) * lengthG, std::clamp(t[1], 0.0, 1.0) * lengthH};
}

rods::Notch designNotch(double surfaceS, double planarS, double length) {
  rods::Notch notch;
  const double l = surfaceS - planarS;  // the bolt slides from s_bar to s (assembly/grid_to_rods)
  if (l > 0.0) notch.afterM = std::min(l, length - planarS);
  if (l < 0.0) notch.beforeM = std::min(-l, planarS);
  return notch;
}

// The rectangle of a lamella: its four corners, counter-clockwise.
std::array<Eigen::Vector2d, 4> designRectangle(const Segment2& s, double width) {
  const Eigen::Vector2d d = (s[1] - s[0]).normalized();
  const Eigen::Vector2d n = 0.5 * width * Eigen::Vector2d(-d.y(), d.x());
  return {s[0] - n, s[1] - n, s[1] + n, s[0] + n};
}

// How far two convex quadrilaterals overlap along their least separating axis (<= 0: apart).
double designOverlapDepth(const std::array<Eigen::Vector2d, 4>& a,
                          const std::array<Eigen::Vector2d, 4>& b) {
  double depth = INFINITY;
  for (const auto* poly : {&a, &b}) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d edge = (*poly)[k + 1] - (*poly)[k];
      const Eigen::Vector2d axis = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
      double loA = INFINITY, hiA = -INFINITY, loB = INFINITY, hiB = -INFINITY;
      for (const auto& p : a) loA = std::min(loA, axis.dot(p)), hiA = std::max(hiA, axis.dot(p));
      for (const auto& p : b) loB = std::min(loB, axis.dot(p)), hiB = std::max(hiB, axis.dot(p));
      depth = std::min(depth, std::min(hiA, hiB) - std::max(loA, loB));
    }
  }
  return depth;
}

}  // namespace

std::vector<std::pair<int, int>> overlappingLamellas(const std::vector<Segment2>& segments,
                                                     const std::vector<int>& families,
                                                     double widthM, double tolerance) {
  if (families.size() != segments.size())
    throw InvalidInput("overlappingLamellas: one family per segment is needed");
  std::vector<std::array<Eigen::Vector2d, 4>> rectangles;
  for (const auto& s : segments) rectangles.push_back(designRectangle(s, widthM));
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < segments.size(); ++i) {
    for (size_t j = i + 1; j < segments.size(); ++j) {
      if (families[i] == families[j] &&
          designOverlapDepth(rectangles[i], rectangles[j]) > tolerance)
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  }
  return pairs;
}

void GeneralisedDesignOptions::validate() const {
  if (!(section.widthM > 0.0))
    throw InvalidInput("GeneralisedDesignOptions.section.width_m must be positive");
  if (!(section.thicknessM > 0.0))
    throw InvalidInput("GeneralisedDesignOptions.section.thickness_m must be positive");
  if (!(material.youngsModulusPa > 0.0))
    throw InvalidInput("GeneralisedDesignOptions.material.youngs_modulus_pa must be positive");
  if (!(material.shearModulusPa > 0.0))
    throw InvalidInput("GeneralisedDesignOptions.material.shear_modulus_pa must be positive");
  planarisation.validate();
}

GeneralisedDesign designGeneralisedGrid(const GridDomain& domain, const GeneralisedLayout& layout,
                                        const GeneralisedDesignOptions& options) {
  options.validate();
  const Stopwatch clock;
  if (const auto problem = layoutProblem(domain, layout); !problem.empty())
    throw InvalidInput("generalised grid: " + problem);
  GeneralisedDesign design;
  design.layout = layout;
  const auto& members = layout.members;
  std::vector<std::pair<int, int>> pairs;
  for (const auto& m : members) pairs.emplace_back(m.start, m.end);
  domain.prepareMembers(pairs);
  design.fieldCrossings = gridCrossings(domain, layout);
  // The traced crossings: two traced geodesics cross inside a face, where both are straight.
  const double edge = domain.meanEdgeLengthM();
  double deviationSum = 0.0;
  int measured = 0;
  for (const auto& c : design.fieldCrossings) {
    const auto& g = domain.member(members[c.g].start, members[c.g].end);
    const auto& h = domain.member(members[c.h].start, members[c.h].end);
    auto traced = geodesic::intersectPolylines(g.positions, h.positions, 1e-6 * edge);
    if (!traced.found) traced = geodesic::intersectPolylines(g.positions, h.positions, 0.5 * edge);
    if (!traced.found) {
      throw InvalidInput("generalised grid: members " + std::to_string(c.g) + " and " +
                         std::to_string(c.h) + " should cross but their traced geodesics do not");
    }
    design.tracedCrossings.push_back(traced.position);
    design.tracedSGM.push_back(traced.arcLengthFirst);
    design.crossingAnglesRad.push_back(
        crossingAngle(g, traced.arcLengthFirst, h, traced.arcLengthSecond));
    design.tracedSHM.push_back(traced.arcLengthSecond);
    if (!c.found) continue;  // eps_geo measures the field crossings that were found
    const double deviation = (traced.position - c.position).norm();
    deviationSum += deviation;
    ++measured;
    design.maxCrossingDeviationM = std::max(design.maxCrossingDeviationM, deviation);
  }
  design.minCrossingAngleRad =
      design.crossingAnglesRad.empty()
          ? 0.0
          : *std::min_element(design.crossingAnglesRad.begin(), design.crossingAnglesRad.end());
  if (measured > 0) design.epsGeoPercent = 100.0 * deviationSum / measured / edge;

  // Section 4.7: lengths from the distance map, fractions from the traced crossings.
  auto& problem = design.planarProblem;
  const Eigen::Matrix<double, 3, 2> axes = domain.planeAxes();
  for (const auto& m : members) {
    const auto& geometry = domain.member(m.start, m.end);
    problem.members.push_back({geometry.lengthM, m.family});
    problem.initial.push_back(
        {Eigen::Vector2d(axes.transpose() * (domain.position(m.start) - domain.planeOrigin())),
         Eigen::Vector2d(axes.transpose() * (domain.position(m.end) - domain.planeOrigin()))});
  }
  for (size_t k = 0; k < design.fieldCrossings.size(); ++k) {
    const auto& c = design.fieldCrossings[k];
    const double lengthG = domain.member(members[c.g].start, members[c.g].end).arcLengthM.back();
    const double lengthH = domain.member(members[c.h].start, members[c.h].end).arcLengthM.back();
    problem.crossings.push_back({c.g, c.h, std::clamp(design.tracedSGM[k] / lengthG, 0.0, 1.0),
                                 std::clamp(design.tracedSHM[k] / lengthH, 0.0, 1.0)});
  }
  design.neighbours = neighbourMembers(domain, layout);
  for (auto [first, second] : design.neighbours) problem.neighbours.push_back({first, second});
  problem.widthM = options.section.widthM;
  design.planar = planarise(problem, options.planarisation);

  std::vector<int> families;
  for (const auto& m : members) families.push_back(m.family);
  for (auto [i, j] : overlappingLamellas(design.planar.endpoints, families, problem.widthM)) {
    const auto& a = members[i];
    const auto& b = members[j];
    const bool splitPieces = a.line == b.line && (a.start == b.end || a.end == b.start ||
                                                  a.start == b.start || a.end == b.end);
    if (!splitPieces) design.planarOverlaps.emplace_back(i, j);
  }

  // The rods: family 0 in layer 0, family 1 in layer 1 (rod_network.hpp).
  auto& network = design.network;
  for (size_t i = 0; i < members.size(); ++i) {
    const auto& geometry = domain.member(members[i].start, members[i].end);
    rods::Rod rod;
    rod.lengthM = problem.members[i].lengthM;
    rod.section = options.section;
    rod.material = options.material;
    rod.layer = members[i].family;
    rod.guess = geometry.positions;
    for (const auto& p : geometry.points) rod.guessNormals.push_back(designNormalAt(domain, p));
    network.rods.push_back(std::move(rod));
    // Both ends held by anchors on the boundary ring: position and tangent plane (4.3.1).
    for (const double s : {0.0, rod.lengthM}) {
      rods::Anchor anchor;
      anchor.rod = static_cast<int>(i);
      anchor.sM = s;
      const int sample = s == 0.0 ? members[i].start : members[i].end;
      anchor.position = domain.position(sample);
      anchor.normal = domain.curvature().normals[domain.vertex(sample)].normalized();
      network.anchors.push_back(anchor);
    }
  }
  for (size_t k = 0; k < problem.crossings.size(); ++k) {
    const auto& c = problem.crossings[k];
    const double lengthG = problem.members[c.g].lengthM, lengthH = problem.members[c.h].lengthM;
    const auto [planarG, planarH] = designPlanarCrossing(
        design.planar.endpoints[c.g], design.planar.endpoints[c.h], c.lambdaG, c.lambdaH);
    rods::Connection bolt;
    bolt.rodA = c.g;
    bolt.rodB = c.h;
    bolt.sAM = planarG;
    bolt.sBM = planarH;
    if (options.notches) {
      bolt.notchA = designNotch(c.lambdaG * lengthG, planarG, lengthG);
      bolt.notchB = designNotch(c.lambdaH * lengthH, planarH, lengthH);
    }
    network.connections.push_back(bolt);
  }
  rods::validateNetwork(network);
  design.seconds = clock.seconds();
  return design;
}

}  // namespace egg::generalised
