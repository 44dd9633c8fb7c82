// The architectural samples of Section 3.6.2 (Great Court, Lilium Tower tip, Yas Hotel canopy) with
// the closed forms of docs/architecture.md "Samples".
#include "samples/generators/architectural.hpp"

#include "samples/generators/catalog.hpp"

#include <cmath>
#include <numbers>

namespace egg::samples {

double greatCourtHeight(double x, double y) {
  using namespace great_court;
  const double fx1 = 1 - x / b, fx2 = 1 + x / b, fy1 = 1 - y / c, fy2 = 1 + y / d;
  // On the rectangle the closed form tends to h_e (psi -> 0 and beta -> 0); the terms of beta are
  // 0/0 at the corners, so the edge value is returned exactly.
  if (fx1 <= 0 || fx2 <= 0 || fy1 <= 0 || fy2 <= 0) return he;
  const double r = std::hypot(x, y);
  const double sinTheta = y / r;
  const double cos2Theta = (x * x - y * y) / (r * r);
  const double sPlus = 0.5 * (1 - cos2Theta) + sinTheta;
  const double sMinus = 0.5 * (1 - cos2Theta) - sinTheta;
  const double psi = fx1 * fx2 * fy1 * fy2;
  const double ax = a * x / (r * b), ayc = a * y / (r * c), ayd = a * y / (r * d);
  const double eta = psi / ((1 - ax) * (1 + ax) * (1 - ayc) * (1 + ayd));
  const double alpha = (r / a - 1) * psi;
  const double bx1 = b - x, bx2 = b + x, cy = c - y, dy = d + y;
  const double beta =
      (1 - a / r) / (std::hypot(bx1, cy) / (bx1 * cy) + std::hypot(bx1, dy) / (bx1 * dy) +
                     std::hypot(bx2, cy) / (bx2 * cy) + std::hypot(bx2, dy) / (bx2 * dy));
  const double z1 = (hc - he) * eta + he;
  const double z2 = alpha * ((1 - lambda) * ((35 + 10 * psi) * 0.5 * (1 + cos2Theta) + 12 * sPlus +
                                             (7.5 + 12 * psi) * sMinus - 1.6) -
                             5 * (1 + cos2Theta) + 10 * std::pow(0.5 * sPlus, 2) * (1 - 3 * alpha) +
                             2.5 * std::pow(0.5 * sMinus, 2) * std::pow(r / a - 1, 2));
  const double z3 =
      beta * (lambda * (1.75 * (1 + cos2Theta) + 1.5 * (1 - cos2Theta) + 0.3 * sinTheta) +
              1.05 * (std::exp(-mu * fx1) + std::exp(-mu * fx2)) *
                  (std::exp(-mu * fy1) + std::exp(-mu * fy2)));
  return z1 + z2 + z3;
}

Eigen::Vector3d liliumPoint(double theta, double t) {
  using namespace lilium;
  const double r = R0 * std::sqrt(std::max(0.0, 1 - t * t));
  const double rho = 1 + A0 * (1 - t) * std::cos(4 * theta);
  return {r * rho * std::cos(theta + Phi * t), r * rho * std::sin(theta + Phi * t), H * t};
}

double yasHeight(double x, double y) {
  using namespace yas;
  const double w = 1 - std::pow(x / semiX, 4) - std::pow(y / semiY, 4);
  auto tower = [&](double xi, double yi) {
    return std::exp(-0.5 * (std::pow((x - xi) / 30, 2) + std::pow((y - yi) / 25, 2)));
  };
  const double ridge =
      0.6 * std::exp(-std::pow(y - 0.2727 * x, 2) / 144) * std::exp(-std::pow(x / 70, 2));
  const double undulation =
      1 + 0.08 * std::sin(2 * std::numbers::pi * x / 55) * std::cos(2 * std::numbers::pi * y / 70);
  return N * w * (tower(-towerX, -towerY) + tower(towerX, towerY) + ridge) * undulation;
}

namespace detail {
namespace {

SurfaceSpec greatCourt(const Params&) {
  using namespace great_court;
  SurfaceSpec spec;
  spec.name = "great_court";
  spec.position = [](const Vec2& p) { return Vec3(p.x(), p.y(), greatCourtHeight(p.x(), p.y())); };
  spec.boundary = {rectangleLoop(-b, b, -d, c), ellipseLoop(Vec2::Zero(), a, a)};
  spec.inDomain = [](const Vec2& p) { return p.norm() >= a; };
  // docs/architecture.md "Samples" spot heights: z(0, 34.135) = 26.157, z(0, -36.685) = 27.573,
  // z(+-29.435, 0) = 22.664.
  spec.requiredPoints = {{0.0, 34.135}, {0.0, -36.685}, {29.435, 0.0}, {-29.435, 0.0}};
  return spec;
}

// Lilium: the domain is a disc in polar form (R0 psi, theta) with t = cos(psi), so the tip t = 1 is
// the disc centre (an ordinary interior vertex) and the base t = 0 is the rim psi = pi / 2.
SurfaceSpec liliumTower(const Params&) {
  using namespace lilium;
  SurfaceSpec spec;
  spec.name = "lilium";
  spec.position = [](const Vec2& p) {
    const double psi = p.norm() / R0;
    const double theta = psi > 0 ? std::atan2(p.y(), p.x()) : 0.0;
    return liliumPoint(theta, std::cos(psi));
  };
  spec.boundary = {ellipseLoop(Vec2::Zero(), R0 * std::numbers::pi / 2, R0 * std::numbers::pi / 2)};
  spec.inDomain = [](const Vec2& p) { return p.norm() <= R0 * std::numbers::pi / 2; };
  spec.requiredPoints = {Vec2::Zero()};  // the tip
  return spec;
}

SurfaceSpec yasCanopy(const Params& params) {
  using namespace yas;
  const double holes = params.at("holes");
  require(holes == 0 || holes == 1, "yas", "holes", holes, "must be 0 or 1");
  SurfaceSpec spec;
  spec.name = "yas";
  spec.position = [](const Vec2& p) { return Vec3(p.x(), p.y(), yasHeight(p.x(), p.y())); };
  // Polar form of the quartic rim, smooth in the angle (the signed-power form is not).
  spec.boundary.push_back({DomainCurve{[](double s) {
    const double phi = 2 * std::numbers::pi * s;
    const double rho =
        std::pow(std::pow(std::cos(phi) / semiX, 4) + std::pow(std::sin(phi) / semiY, 4), -0.25);
    return Vec2(rho * std::cos(phi), rho * std::sin(phi));
  }}});
  const bool withHoles = holes == 1;
  if (withHoles) {
    spec.boundary.push_back(ellipseLoop({-towerX, -towerY}, holeSemiX, holeSemiY));
    spec.boundary.push_back(ellipseLoop({towerX, towerY}, holeSemiX, holeSemiY));
  }
  spec.inDomain = [withHoles](const Vec2& p) {
    if (std::pow(p.x() / semiX, 4) + std::pow(p.y() / semiY, 4) > 1) return false;
    if (!withHoles) return true;
    for (const double sign : {-1.0, 1.0}) {
      const double ex = (p.x() - sign * towerX) / holeSemiX,
                   ey = (p.y() - sign * towerY) / holeSemiY;
      if (ex * ex + ey * ey < 1) return false;
    }
    return true;
  };
  return spec;
}

}  // namespace

std::vector<SampleEntry> architecturalSamples() {
  return {
      {{"great_court",
        "British Museum Great Court roof (C. J. K. Williams' closed form), 73.25 x 97.15 m with "
        "the "
        "Reading Room hole of radius 22.245 m; heights 19.71-27.60 m",
        {},
        {}},
       greatCourt},
      {{"lilium",
        "Tip of the Lilium Tower: P(theta, t) = (r rho cos(theta + Phi t), r rho sin(theta + Phi "
        "t), 37 t), "
        "48 x 48 x 37 m, tip at t = 1",
        {},
        {}},
       liliumTower},
      {{"yas",
        "Yas Hotel canopy over the quartic footprint (x/109)^4 + (y/70)^4 <= 1, 218 x 140 x 47 m; "
        "holes = 1 cuts 20 x 12 m ellipses at the towers (-55, -15) and (55, 15)",
        {{"holes", 0.0}},
        {{"holes",
          "1 cuts the two 20 x 12 m tower ellipses, 0 keeps them closed as the paper did "
          "(switch)"}}},
       yasCanopy},
  };
}

}  // namespace detail
}  // namespace egg::samples
