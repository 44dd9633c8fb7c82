#include "core/egg/members.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace egg {

void MemberOptions::validate() const {
  if (count == 1 || count < 0) throw InvalidInput("grid.members_per_family must be \"auto\" or >= 2 (both boundaries)");
  if (!(lamellaWidthM > 0.0)) throw InvalidInput("lamella.width_m must be > 0");
  if (!(spacingFactor >= 1.0)) throw InvalidInput("grid spacing factor must be >= 1 (members cannot overlap)");
  if (!(featureFraction >= 0.0 && featureFraction <= 1.0)) throw InvalidInput("grid feature fraction must lie in [0, 1]");
}

double lamellaFootprint(double width, double angle) { return width / std::max(std::sin(angle), 1e-6); }

std::array<double, 2> boundaryAngles(const PlanarQuad& quad, Family family, double x1, double x2) {
  const auto k = familyCorners(family);
  const auto ends = planarMember(quad, family, x1, x2);
  const Eigen::Vector2d member = (ends[1] - ends[0]).normalized();
  const auto acuteAngle = [&](const Eigen::Vector2d& side) {
    return std::acos(std::clamp(std::abs(member.dot(side.normalized())), 0.0, 1.0));
  };
  return {acuteAngle(quad.corners[k[1]] - quad.corners[k[0]]), acuteAngle(quad.corners[k[3]] - quad.corners[k[2]])};
}

namespace {

struct Candidate {
  double t;         // position along the cladding curve (metres, mean of the two sides)
  double priority;  // |C''|
  MemberOrigin origin;
};

// The cladding curve parametrised by t = mean distance travelled along the two sides, so that
// spacing in t is spacing of the members' feet on the boundaries.
struct CurveParameter {
  std::vector<double> t;
  const CladdingFunction& f;
  double total() const { return t.back(); }
  Eigen::Vector2d at(double value) const {
    value = std::clamp(value, 0.0, total());
    const size_t hi = std::min<size_t>(std::upper_bound(t.begin(), t.end(), value) - t.begin(), t.size() - 1);
    const size_t lo = hi - 1;
    const double span = t[hi] - t[lo];
    const double s = span > 0 ? (value - t[lo]) / span : 0.0;
    return f.points[lo] + s * (f.points[hi] - f.points[lo]);
  }
  double lengthAt(double value) const {
    value = std::clamp(value, 0.0, total());
    const size_t hi = std::min<size_t>(std::upper_bound(t.begin(), t.end(), value) - t.begin(), t.size() - 1);
    const size_t lo = hi - 1;
    const double span = t[hi] - t[lo];
    const double s = span > 0 ? (value - t[lo]) / span : 0.0;
    return f.lengths[lo] + s * (f.lengths[hi] - f.lengths[lo]);
  }
};

}  // namespace

FamilyMembers placeMembers(const CladdingFunction& cladding, const PlanarQuad& quad, double startSideLength,
                           double endSideLength, const MemberOptions& options) {
  options.validate();
  if (!cladding.bijective())
    throw InfeasiblePatch("cannot place members: the cladding function is not bijective (criterion iii)");
  const double w = options.lamellaWidthM;
  CurveParameter curve{{0.0}, cladding};
  for (size_t k = 1; k < cladding.points.size(); ++k) {
    const Eigen::Vector2d d = cladding.points[k] - cladding.points[k - 1];
    curve.t.push_back(curve.t.back() + 0.5 * (std::abs(d.x()) * startSideLength + std::abs(d.y()) * endSideLength));
  }
  const double total = curve.total();

  // Do members at curve positions a and b keep the lamellas apart on both sides (d+ and d-)?
  const auto spacingOk = [&](double ta, double tb, double extra) {
    const Eigen::Vector2d a = curve.at(ta), b = curve.at(tb);
    const auto angA = boundaryAngles(quad, cladding.family, a.x(), a.y());
    const auto angB = boundaryAngles(quad, cladding.family, b.x(), b.y());
    const double needStart = std::max(0.5 * (lamellaFootprint(w, angA[0]) + lamellaFootprint(w, angB[0])), extra);
    const double needEnd = std::max(0.5 * (lamellaFootprint(w, angA[1]) + lamellaFootprint(w, angB[1])), extra);
    return std::abs(b.x() - a.x()) * startSideLength >= needStart && std::abs(b.y() - a.y()) * endSideLength >= needEnd;
  };

  std::vector<double> chosen;
  std::vector<MemberOrigin> origins;
  if (options.count >= 2) {
    for (int k = 0; k < options.count; ++k) {
      chosen.push_back(total * k / (options.count - 1));
      origins.push_back(k == 0 || k == options.count - 1 ? MemberOrigin::Boundary : MemberOrigin::Even);
    }
    for (size_t k = 1; k < chosen.size(); ++k)
      if (!spacingOk(chosen[k - 1], chosen[k], 0.0))
        throw InvalidInput("grid.members_per_family = " + std::to_string(options.count) +
                           " is too dense for lamellas of width " + std::to_string(w) + " m on this patch");
  } else {
    const double target = options.spacingFactor * w;
    // C(t) resampled uniformly and smoothed lightly: the piecewise-linear intersection carries
    // O(h) slope noise that would otherwise show up as spurious curvature extrema.
    const int samples = 256;
    const double dt = total / (samples - 1);
    std::vector<double> c(samples), smooth(samples);
    for (int k = 0; k < samples; ++k) c[k] = curve.lengthAt(k * dt);
    for (int k = 0; k < samples; ++k) {
      double sum = 0, weight = 0;
      for (int j = std::max(0, k - 6); j <= std::min(samples - 1, k + 6); ++j) {
        const double g = std::exp(-0.5 * (j - k) * (j - k) / 4.0);
        sum += g * c[j], weight += g;
      }
      smooth[k] = sum / weight;
    }
    std::vector<double> d1(samples, 0.0), d2(samples, 0.0), kappa(samples, 0.0);
    for (int k = 1; k + 1 < samples; ++k) {
      d1[k] = (smooth[k + 1] - smooth[k - 1]) / (2 * dt);
      d2[k] = (smooth[k + 1] - 2 * smooth[k] + smooth[k - 1]) / (dt * dt);
      kappa[k] = d2[k] / std::pow(1.0 + d1[k] * d1[k], 1.5);
    }
    double largestD2 = 0.0;
    for (int k = 2; k + 2 < samples; ++k) largestD2 = std::max(largestD2, std::abs(d2[k]));
    std::vector<Candidate> lengthExtrema, curvatureExtrema;
    for (int k = 2; k + 3 < samples; ++k) {
      if ((d1[k] > 0) != (d1[k + 1] > 0)) {  // C' changes sign: a locally longest/shortest member
        const double s = d1[k] / (d1[k] - d1[k + 1]);
        lengthExtrema.push_back({(k + s) * dt, std::abs(d2[k]), MemberOrigin::LengthExtremum});
      }
      const double kp0 = kappa[k] - kappa[k - 1], kp1 = kappa[k + 1] - kappa[k];
      if ((kp0 > 0) != (kp1 > 0) && std::abs(d2[k]) >= options.featureFraction * largestD2 && largestD2 > 0)
        curvatureExtrema.push_back({k * dt, std::abs(d2[k]), MemberOrigin::CurvatureExtremum});
    }
    const auto byPriority = [](const Candidate& a, const Candidate& b) { return a.priority > b.priority; };
    std::sort(lengthExtrema.begin(), lengthExtrema.end(), byPriority);
    std::sort(curvatureExtrema.begin(), curvatureExtrema.end(), byPriority);

    chosen = {0.0, total};
    origins = {MemberOrigin::Boundary, MemberOrigin::Boundary};
    // Features may not crowd closer than half the target spacing (nor the lamella footprint).
    for (const auto* tier : {&lengthExtrema, &curvatureExtrema})
      for (const auto& candidate : *tier) {
        bool fits = true;
        for (double t : chosen) fits = fits && spacingOk(t, candidate.t, 0.5 * target);
        if (fits) chosen.push_back(candidate.t), origins.push_back(candidate.origin);
      }
    std::vector<size_t> order(chosen.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return chosen[a] < chosen[b]; });
    std::vector<double> sortedT;
    std::vector<MemberOrigin> sortedOrigin;
    for (size_t k : order) sortedT.push_back(chosen[k]), sortedOrigin.push_back(origins[k]);

    // Fill the gaps; equal spacing inside a gap minimises the sum of squared neighbour distances
    // with the feature members held fixed (the evening-out step).
    chosen.clear();
    origins.clear();
    for (size_t g = 0; g + 1 < sortedT.size(); ++g) {
      chosen.push_back(sortedT[g]);
      origins.push_back(sortedOrigin[g]);
      const double a = sortedT[g], b = sortedT[g + 1];
      int extra = std::max(0, static_cast<int>(std::lround((b - a) / target)) - 1);
      for (; extra > 0; --extra) {
        bool ok = true;
        for (int j = 0; j <= extra && ok; ++j)
          ok = spacingOk(a + (b - a) * j / (extra + 1), a + (b - a) * (j + 1) / (extra + 1), 0.0);
        if (ok) break;
      }
      for (int j = 1; j <= extra; ++j) {
        chosen.push_back(a + (b - a) * j / (extra + 1));
        origins.push_back(MemberOrigin::Filled);
      }
    }
    chosen.push_back(sortedT.back());
    origins.push_back(sortedOrigin.back());
  }

  FamilyMembers members;
  members.family = cladding.family;
  for (size_t k = 0; k < chosen.size(); ++k) {
    double x1 = curve.at(chosen[k]).x();
    if (k == 0) x1 = 0.0;
    if (k + 1 == chosen.size()) x1 = 1.0;
    members.x1.push_back(x1);
    members.x2.push_back(k == 0 ? 0.0 : k + 1 == chosen.size() ? 1.0 : cladding.evaluate(x1));
    members.lengths.push_back(cladding.lengthAt(x1));
    members.origin.push_back(origins[k]);
  }
  return members;
}

}  // namespace egg
