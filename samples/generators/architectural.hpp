#pragma once
// The three architectural design surfaces of Section 3.6.2 in closed form (docs/architecture.md
// "Samples"). Exposed so tests and other stages can use them as exact oracles.
#include <Eigen/Dense>

namespace egg::samples {

// British Museum Great Court roof, C. J. K. Williams' closed form. Origin at the Reading Room
// centre, x east, y north; defined for r >= a inside the rectangle [-b, b] x [-d, c].
namespace great_court {
inline constexpr double a = 22.245;   // Reading Room radius (m)
inline constexpr double b = 36.625;   // half width east-west (m)
inline constexpr double c = 46.025;   // north edge (m)
inline constexpr double d = 51.125;   // south edge (m)
inline constexpr double hc = 20.955;  // height on the Reading Room circle (m)
inline constexpr double he = 19.71;   // height on the rectangle (m)
inline constexpr double lambda = 0.5;
inline constexpr double mu = 14.0;
}  // namespace great_court
double greatCourtHeight(double x, double y);

// Lilium Tower tip: P(theta, t), t in [0, 1], tip at t = 1 (height H).
namespace lilium {
inline constexpr double H = 37.0;
inline constexpr double A0 = 0.12;
inline constexpr double R0 = 21.4286;
inline constexpr double Phi = 0.785398163397448309616;  // pi / 4
}  // namespace lilium
Eigen::Vector3d liliumPoint(double theta, double t);

// Yas Hotel canopy over the footprint (x/109)^4 + (y/70)^4 <= 1 (zero on its rim).
namespace yas {
inline constexpr double semiX = 109.0;
inline constexpr double semiY = 70.0;
inline constexpr double N = 34.8896;                        // scales the maximum height to 47 m
inline constexpr double towerX = 55.0, towerY = 15.0;       // towers at (-55, -15) and (55, 15)
inline constexpr double holeSemiX = 10.0, holeSemiY = 6.0;  // 20 x 12 m ellipses (option holes)
}  // namespace yas
double yasHeight(double x, double y);

}  // namespace egg::samples
