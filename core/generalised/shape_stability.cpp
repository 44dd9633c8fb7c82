// Shape stability of grid members and E_shape (Section 4.6.2, Eq. 4.9): see shape_stability.hpp.
#include "core/generalised/shape_stability.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>

namespace egg::generalised {
namespace {

// `who` names the profile in messages ("member 3", or the calling function's name).
void shapeCheckProfile(const MemberCurvatureProfile& profile, const std::string& who) {
  const size_t n = profile.arcLengthM.size();
  if (profile.kappaN.size() != n)
    throw InvalidInput(who + ": " + std::to_string(profile.kappaN.size()) + " kappaN values for " +
                       std::to_string(n) + " arcLengthM values");
  if (n < 2) throw InvalidInput(who + ": a profile needs at least two samples");
  for (size_t j = 0; j < n; ++j) {
    if (!std::isfinite(profile.arcLengthM[j]) || !std::isfinite(profile.kappaN[j]))
      throw InvalidInput(who + ": sample " + std::to_string(j) + " is not finite");
    if (j > 0 && !(profile.arcLengthM[j] > profile.arcLengthM[j - 1]))
      throw InvalidInput(who + ": arcLengthM is not strictly increasing at sample " +
                         std::to_string(j));
  }
}

double shapeZeroBand(const MemberCurvatureProfile& profile, const ShapeStabilityOptions& options) {
  double maxAbs = 0.0;
  for (double k : profile.kappaN) maxAbs = std::max(maxAbs, std::abs(k));
  return std::max(options.absoluteZeroToleranceInvM, options.relativeZeroTolerance * maxAbs);
}

// +1 / -1 outside the zero band, 0 inside it.
int shapeSign(double kappa, double band) { return kappa > band ? 1 : (kappa < -band ? -1 : 0); }

std::vector<double> shapeInflections(const MemberCurvatureProfile& profile,
                                     const ShapeStabilityOptions& options) {
  const double band = shapeZeroBand(profile, options);
  std::vector<double> result;
  int last = -1;  // the last sample outside the band
  for (size_t j = 0; j < profile.kappaN.size(); ++j) {
    const int sign = shapeSign(profile.kappaN[j], band);
    if (sign == 0) continue;
    if (last >= 0 && sign != shapeSign(profile.kappaN[last], band)) {
      // Between adjacent samples this is linear interpolation; across a band it places the
      // inflection by the two lobes' edge values, one point however noisy the band is.
      const double k0 = profile.kappaN[last], k1 = profile.kappaN[j];
      const double s0 = profile.arcLengthM[last], s1 = profile.arcLengthM[j];
      result.push_back(s0 + (s1 - s0) * k0 / (k0 - k1));
    }
    last = static_cast<int>(j);
  }
  return result;
}

std::vector<Eigen::Vector2d> shapePlanarCurve(const MemberCurvatureProfile& profile) {
  std::vector<Eigen::Vector2d> points{Eigen::Vector2d::Zero()};
  double theta = 0.0;
  for (size_t j = 0; j + 1 < profile.arcLengthM.size(); ++j) {
    const double h = profile.arcLengthM[j + 1] - profile.arcLengthM[j];
    const double next = theta + 0.5 * h * (profile.kappaN[j] + profile.kappaN[j + 1]);
    const double mid = 0.5 * (theta + next);
    points.push_back(points.back() + h * Eigen::Vector2d(std::cos(mid), std::sin(mid)));
    theta = next;
  }
  return points;
}

// The curve's point at arc length s, linear between samples (s inside the profile's range).
Eigen::Vector2d shapePointAt(const MemberCurvatureProfile& profile,
                             const std::vector<Eigen::Vector2d>& points, double s) {
  const auto& a = profile.arcLengthM;
  const size_t hi =
      std::clamp<size_t>(std::upper_bound(a.begin(), a.end(), s) - a.begin(), 1, a.size() - 1);
  const double t = (s - a[hi - 1]) / (a[hi] - a[hi - 1]);
  return (1.0 - t) * points[hi - 1] + t * points[hi];
}

bool shapeTwoInflectionTest(const MemberCurvatureProfile& profile,
                            const std::vector<double>& inflections,
                            const ShapeStabilityOptions& options) {
  const auto points = shapePlanarCurve(profile);
  const Eigen::Vector2d p1 = shapePointAt(profile, points, inflections[0]);
  const Eigen::Vector2d p2 = shapePointAt(profile, points, inflections[1]);
  const double length = profile.arcLengthM.back() - profile.arcLengthM.front();
  const Eigen::Vector2d chord = p2 - p1;
  if (!(chord.norm() > 1e-9 * length)) return false;
  const Eigen::Vector2d normal = Eigen::Vector2d(-chord.y(), chord.x()).normalized();
  const double band = shapeZeroBand(profile, options);
  // The force may point either way along the line: the test passes if either orientation of the
  // normal puts every kappa > 0 sample on its positive side and every kappa < 0 one on its
  // negative side, up to the tolerance.
  double worstPlus = 0.0, worstMinus = 0.0;
  for (size_t j = 0; j < points.size(); ++j) {
    const int sign = shapeSign(profile.kappaN[j], band);
    if (sign == 0) continue;
    const double d = sign * normal.dot(points[j] - p1);
    worstPlus = std::min(worstPlus, d);
    worstMinus = std::min(worstMinus, -d);
  }
  const double tolerance = options.lineSideTolerance * length;
  return worstPlus >= -tolerance || worstMinus >= -tolerance;
}

void shapeCheckCrossing(const StabilityCrossing& c, size_t index,
                        const std::vector<MemberCurvatureProfile>& profiles) {
  const std::string who = "shapeStability: crossing " + std::to_string(index);
  const int count = static_cast<int>(profiles.size());
  const std::initializer_list<std::pair<int, double>> ends{{c.first, c.firstArcLengthM},
                                                           {c.second, c.secondArcLengthM}};
  for (const auto& [member, s] : ends) {
    if (member < 0 || member >= count)
      throw InvalidInput(who + " names member " + std::to_string(member) + " of " +
                         std::to_string(count));
    const auto& a = profiles[member].arcLengthM;
    const double slack = 1e-9 * (a.back() - a.front());
    if (!std::isfinite(s) || s < a.front() - slack || s > a.back() + slack)
      throw InvalidInput(who + " lies outside member " + std::to_string(member) + "'s arc length");
  }
  if (c.first == c.second)
    throw InvalidInput(who + " crosses member " + std::to_string(c.first) + " with itself");
}

// eta after mutual stabilisation (Fig. 4.14) of an unstable member with the given inflections,
// from the arc lengths at which members stable on their own cross it.
double shapeSupportedEta(const std::vector<double>& inflections,
                         const std::vector<double>& stableCrossings) {
  const size_t segments = inflections.size() - 1;
  int supported = 0;
  for (size_t j = 0; j < segments; ++j) {
    // The thesis' case formula for omega_j prints 0 and 1 the other way round; its text (a
    // segment crossed by a stable member is stabilised, omega_j = 1) and Fig. 4.14's eta = 1 and
    // 1/3 follow this reading. A crossing on an inflection point counts for both segments.
    const bool crossed = std::any_of(stableCrossings.begin(), stableCrossings.end(), [&](double s) {
      return s >= inflections[j] && s <= inflections[j + 1];
    });
    supported += crossed ? 1 : 0;
  }
  return static_cast<double>(supported) / static_cast<double>(segments);
}

}  // namespace

void ShapeStabilityOptions::validate() const {
  if (!(relativeZeroTolerance >= 0.0 && relativeZeroTolerance < 1.0))
    throw InvalidInput("shape stability: relativeZeroTolerance must lie in [0, 1)", {},
                       "relativeZeroTolerance");
  if (!(absoluteZeroToleranceInvM >= 0.0) || !std::isfinite(absoluteZeroToleranceInvM))
    throw InvalidInput("shape stability: absoluteZeroToleranceInvM must be finite and >= 0 (1/m)",
                       {}, "absoluteZeroToleranceInvM");
  if (!(lineSideTolerance >= 0.0) || !std::isfinite(lineSideTolerance))
    throw InvalidInput("shape stability: lineSideTolerance must be finite and >= 0", {},
                       "lineSideTolerance");
}

std::vector<double> inflectionArcLengths(const MemberCurvatureProfile& profile,
                                         const ShapeStabilityOptions& options) {
  options.validate();
  shapeCheckProfile(profile, "inflectionArcLengths");
  return shapeInflections(profile, options);
}

std::vector<Eigen::Vector2d> planarCurveFromCurvature(const MemberCurvatureProfile& profile) {
  shapeCheckProfile(profile, "planarCurveFromCurvature");
  return shapePlanarCurve(profile);
}

bool hafnerBickelTwoInflections(const MemberCurvatureProfile& profile,
                                const std::vector<double>& inflectionArcLengthsM,
                                const ShapeStabilityOptions& options) {
  options.validate();
  shapeCheckProfile(profile, "hafnerBickelTwoInflections");
  if (inflectionArcLengthsM.size() != 2)
    throw InvalidInput(
        "hafnerBickelTwoInflections: " + std::to_string(inflectionArcLengthsM.size()) +
        " inflection points given, the test is for two");
  for (double s : inflectionArcLengthsM)
    if (!(s >= profile.arcLengthM.front() && s <= profile.arcLengthM.back()))
      throw InvalidInput(
          "hafnerBickelTwoInflections: an inflection point lies outside the profile");
  return shapeTwoInflectionTest(profile, inflectionArcLengthsM, options);
}

ShapeStabilityResult shapeStability(const std::vector<MemberCurvatureProfile>& profiles,
                                    const std::vector<StabilityCrossing>& crossings,
                                    const ShapeStabilityOptions& options) {
  options.validate();
  if (profiles.empty()) throw InvalidInput("shapeStability: the grid has no members");
  for (size_t i = 0; i < profiles.size(); ++i)
    shapeCheckProfile(profiles[i], "shapeStability: member " + std::to_string(i));
  for (size_t c = 0; c < crossings.size(); ++c) shapeCheckCrossing(crossings[c], c, profiles);

  ShapeStabilityResult result;
  const size_t n = profiles.size();
  // Each member on its own (Fig. 4.13).
  for (size_t i = 0; i < n; ++i) {
    auto inflections = shapeInflections(profiles[i], options);
    const int sigma = static_cast<int>(inflections.size());
    bool stable = sigma < 2;
    if (sigma == 2) stable = shapeTwoInflectionTest(profiles[i], inflections, options);
    result.inflections.push_back(sigma);
    result.inflectionArcLengthsM.push_back(std::move(inflections));
    result.ownEta.push_back(stable ? 1.0 : 0.0);
  }
  // Where members stable on their own cross each member: only their own eta counts, so the
  // result does not depend on the order in which members are visited.
  std::vector<std::vector<double>> stableCrossings(n);
  for (const auto& c : crossings) {
    if (result.ownEta[c.second] == 1.0) stableCrossings[c.first].push_back(c.firstArcLengthM);
    if (result.ownEta[c.first] == 1.0) stableCrossings[c.second].push_back(c.secondArcLengthM);
  }
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    // An unstable member has sigma >= 2, so at least one segment R_j.
    const double eta = result.ownEta[i] == 1.0
                           ? 1.0
                           : shapeSupportedEta(result.inflectionArcLengthsM[i], stableCrossings[i]);
    result.eta.push_back(eta);
    sum += eta;
  }
  result.eShape = sum / static_cast<double>(n);  // Eq. 4.9
  return result;
}

}  // namespace egg::generalised
