#include "core/egg/members.hpp"
#include "core/egg/illinois_bracket.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace egg {

void MemberOptions::validate() const {
  if (count == 1 || count < 0)
    throw InvalidInput("grid.members_per_family must be \"auto\" or >= 2 (both boundaries)");
  if (!(lamellaWidthM > 0.0)) throw InvalidInput("lamella.width_m must be > 0");
  if (!(spacingFactor >= 1.0))
    throw InvalidInput("grid spacing factor must be >= 1 (members cannot overlap)");
  if (!(featureFraction >= 0.0 && featureFraction <= 1.0))
    throw InvalidInput("grid feature fraction must lie in [0, 1]");
  if (!(smoothingFraction > 0.0)) throw InvalidInput("grid smoothing fraction must be > 0");
  if (scanSamplesPerSigma < 2)
    throw InvalidInput("grid scan samples per smoothing length must be >= 2");
  if (!(tieBand >= 0.0 && tieBand < 1.0)) throw InvalidInput("grid tie band must lie in [0, 1)");
}

double lamellaFootprint(double width, double angle) {
  return width / std::max(std::sin(angle), 1e-6);
}

std::array<double, 2> boundaryAngles(const PlanarQuad& quad, Family family, double x1, double x2) {
  const auto k = familyCorners(family);
  const auto ends = planarMember(quad, family, x1, x2);
  const Eigen::Vector2d member = (ends[1] - ends[0]).normalized();
  const auto acuteAngle = [&](const Eigen::Vector2d& side) {
    return std::acos(std::clamp(std::abs(member.dot(side.normalized())), 0.0, 1.0));
  };
  return {acuteAngle(quad.corners[k[1]] - quad.corners[k[0]]),
          acuteAngle(quad.corners[k[3]] - quad.corners[k[2]])};
}

namespace {

// The smoothing width is at least this many of C's longest sample steps (see placeMembers).
constexpr double kSigmaInSteps = 1.5;

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
    const size_t hi =
        std::min<size_t>(std::upper_bound(t.begin(), t.end(), value) - t.begin(), t.size() - 1);
    const size_t lo = hi - 1;
    const double span = t[hi] - t[lo];
    const double s = span > 0 ? (value - t[lo]) / span : 0.0;
    return f.points[lo] + s * (f.points[hi] - f.points[lo]);
  }
};

// C(t), piecewise linear over the cladding curve's vertices and continued linearly beyond both
// ends (so the ends add no bend of their own), convolved with a Gaussian of standard deviation
// sigma. With s_0 the first segment's slope and ds_j the change of slope at interior vertex t_j,
//   C_s'(t)   = s_0 + sum_j ds_j Phi(z_j),   z_j = (t - t_j) / sigma,
//   C_s''(t)  = sum_j ds_j phi(z_j) / sigma,
//   C_s'''(t) = -sum_j ds_j z_j phi(z_j) / sigma^2,
// exact for the piecewise-linear C. The extrema of Section 2.4.4 are then roots of smooth
// functions of t that move continuously with C, wherever they fall between samples, and sigma is
// a physical length (a fraction of the target spacing), not a number of samples.
class SmoothedLength {
 public:
  SmoothedLength(const std::vector<double>& t, const std::vector<double>& c, double sigma)
      : sigma_(sigma) {
    std::vector<double> tt, cc;
    for (size_t k = 0; k < t.size(); ++k)
      if (tt.empty() || t[k] > tt.back())
        tt.push_back(t[k]), cc.push_back(c[k]);  // skip zero-length segments
    for (size_t k = 1; k < tt.size(); ++k)
      slope_.push_back((cc[k] - cc[k - 1]) / (tt[k] - tt[k - 1]));
    if (slope_.empty()) slope_.push_back(0.0);
    for (size_t k = 1; k + 1 < tt.size(); ++k)
      knot_.push_back(tt[k]), jump_.push_back(slope_[k] - slope_[k - 1]);
  }

  struct Derivatives {
    double d1 = 0.0, d2 = 0.0, d3 = 0.0;
  };
  Derivatives at(double t) const {
    // Vertices further than 8 sigma contribute below 1e-14 of their jump to C_s'' and C_s''';
    // those on the left count fully in C_s' (Phi = 1), i.e. as the slope left of the window.
    constexpr double kWindow = 8.0;
    const size_t lo =
        std::lower_bound(knot_.begin(), knot_.end(), t - kWindow * sigma_) - knot_.begin();
    const size_t hi =
        std::upper_bound(knot_.begin(), knot_.end(), t + kWindow * sigma_) - knot_.begin();
    constexpr double kInvSqrt2Pi = 0.3989422804014327;
    Derivatives d;
    d.d1 = slope_[lo];
    for (size_t j = lo; j < hi; ++j) {
      const double z = (t - knot_[j]) / sigma_;
      const double phi = std::exp(-0.5 * z * z) * kInvSqrt2Pi;
      d.d1 += jump_[j] * 0.5 * std::erfc(-z * M_SQRT1_2);
      d.d2 += jump_[j] * phi;
      d.d3 -= jump_[j] * z * phi;
    }
    d.d2 /= sigma_;
    d.d3 /= sigma_ * sigma_;
    return d;
  }

 private:
  double sigma_;
  std::vector<double>
      slope_;  // slope_[j]: slope left of knot_[j]; slope_.back(): right of the last
  std::vector<double> knot_, jump_;  // interior vertices and their changes of slope
};

// The root of f in [a, b], where f(a) and f(b) lie on opposite sides of zero, to within tol:
// Illinois false position (superlinear, never leaves the bracket; illinois_bracket.hpp).
template <class Function>
double bracketedRoot(const Function& f, double a, double fa, double b, double fb, double tol) {
  IllinoisBracket bracket{a, b, fa, fb};
  double c = a, previous = b;
  for (int iteration = 0; iteration < 200; ++iteration) {
    c = bracket.gb != bracket.ga ? std::clamp(bracket.falsePosition(), bracket.a, bracket.b)
                                 : 0.5 * (bracket.a + bracket.b);
    const double fc = f(c);
    if (fc == 0.0 || std::abs(c - previous) < tol || bracket.b - bracket.a < tol) return c;
    previous = c;
    bracket.replace(c, fc, (fc > 0) == (bracket.gb > 0));
  }
  return c;
}

// The numerator of kappa' for kappa = C'' / (1 + C'^2)^(3/2): kappa' (1 + C'^2)^(5/2).
double curvatureSlope(const SmoothedLength::Derivatives& d) {
  return d.d3 * (1.0 + d.d1 * d.d1) - 3.0 * d.d1 * d.d2 * d.d2;
}

// Candidates of both tiers of Section 2.4.4 on the smoothed C: the extrema of C_s (roots of C_s',
// locally longest and shortest members) and the extrema of its curvature kappa (roots of
// curvatureSlope), keeping those with |C_s''| >= featureFraction * max |C_s''|. Both are
// prioritised by |C_s''| at the root. Roots are bracketed by sign changes on a scan of
// scanSamplesPerSigma points per sigma and solved to 1e-12 of the length: the scan density only
// decides whether two roots closer than its step (a nearly flat extremum) are seen at all.
std::array<std::vector<Candidate>, 2> featureCandidates(const SmoothedLength& c, double total,
                                                        double sigma,
                                                        const MemberOptions& options) {
  const double wanted = std::ceil(total * options.scanSamplesPerSigma / sigma);
  const int steps = static_cast<int>(std::clamp(wanted, 16.0, 262144.0));
  const double tol = 1e-12 * total;
  std::vector<double> ts(steps + 1);
  std::vector<SmoothedLength::Derivatives> ds(steps + 1);
  for (int k = 0; k <= steps; ++k)
    ts[k] = k == steps ? total : total * k / steps, ds[k] = c.at(ts[k]);
  std::vector<double> lengthRoots, curvatureRoots;
  double largest = 0.0;
  for (const auto& d : ds) largest = std::max(largest, std::abs(d.d2));
  for (int k = 0; k < steps; ++k) {
    const auto &a = ds[k], &b = ds[k + 1];
    if ((a.d1 > 0) != (b.d1 > 0))
      lengthRoots.push_back(
          bracketedRoot([&](double t) { return c.at(t).d1; }, ts[k], a.d1, ts[k + 1], b.d1, tol));
    if ((a.d3 > 0) != (b.d3 > 0)) {  // an extremum of C_s'' between the scan points
      const double t =
          bracketedRoot([&](double t) { return c.at(t).d3; }, ts[k], a.d3, ts[k + 1], b.d3, tol);
      largest = std::max(largest, std::abs(c.at(t).d2));
    }
    const double ga = curvatureSlope(a), gb = curvatureSlope(b);
    if ((ga > 0) != (gb > 0))
      curvatureRoots.push_back(bracketedRoot([&](double t) { return curvatureSlope(c.at(t)); },
                                             ts[k], ga, ts[k + 1], gb, tol));
  }
  // An extremum whose slope changes by less than 1e-9 over sigma is flat to rounding (e.g. a C
  // whose every feature the smoothing removed): its sign changes are noise, not features.
  const double flat = 1e-9 / sigma;
  std::array<std::vector<Candidate>, 2> tiers;
  for (double t : lengthRoots) {
    const double priority = std::abs(c.at(t).d2);
    if (t > 0.0 && t < total && priority > flat)
      tiers[0].push_back({t, priority, MemberOrigin::LengthExtremum});
  }
  for (double t : curvatureRoots) {
    const double priority = std::abs(c.at(t).d2);
    if (t > 0.0 && t < total && priority > flat && priority >= options.featureFraction * largest)
      tiers[1].push_back({t, priority, MemberOrigin::CurvatureExtremum});
  }
  // Highest priority first; priorities equal up to rounding (mirror images) in order of t, so the
  // order does not hang on their last bits.
  for (auto& tier : tiers) {
    std::sort(tier.begin(), tier.end(),
              [](const Candidate& a, const Candidate& b) { return a.priority > b.priority; });
    for (size_t first = 0; first < tier.size();) {
      size_t last = first + 1;
      while (last < tier.size() &&
             tier[first].priority - tier[last].priority <= 1e-9 * tier[first].priority)
        ++last;
      std::sort(tier.begin() + first, tier.begin() + last,
                [](const Candidate& a, const Candidate& b) { return a.t < b.t; });
      first = last;
    }
  }
  return tiers;
}

}  // namespace

FamilyMembers placeMembers(const CladdingFunction& cladding, const PlanarQuad& quad,
                           double startSideLength, double endSideLength,
                           const MemberOptions& options) {
  options.validate();
  if (!cladding.bijective())
    throw InfeasiblePatch(
        "cannot place members: the cladding function is not bijective (criterion iii)");
  // Section 2.4.4 reads the member lengths C along the cladding curve; a NaN or infinite length
  // would silently drop out of every sign test below (no extremum there, filled members instead).
  if (cladding.lengths.size() != cladding.points.size())
    throw InvalidInput("cannot place members: the cladding function has " +
                       std::to_string(cladding.lengths.size()) + " member lengths for " +
                       std::to_string(cladding.points.size()) + " points");
  for (size_t k = 0; k < cladding.lengths.size(); ++k)
    if (!std::isfinite(cladding.lengths[k]))
      throw InvalidInput("cannot place members: member length C at cladding point " +
                         std::to_string(k) + " (x1 = " + std::to_string(cladding.points[k].x()) +
                         ", x2 = " + std::to_string(cladding.points[k].y()) + ") is not finite");
  const double w = options.lamellaWidthM;
  CurveParameter curve{{0.0}, cladding};
  for (size_t k = 1; k < cladding.points.size(); ++k) {
    const Eigen::Vector2d d = cladding.points[k] - cladding.points[k - 1];
    curve.t.push_back(curve.t.back() +
                      0.5 * (std::abs(d.x()) * startSideLength + std::abs(d.y()) * endSideLength));
  }
  const double total = curve.total();

  // Do members at curve positions a and b keep the lamellas apart on both sides (d+ and d-)?
  const auto spacingOk = [&](double ta, double tb, double extra) {
    const Eigen::Vector2d a = curve.at(ta), b = curve.at(tb);
    const auto angA = boundaryAngles(quad, cladding.family, a.x(), a.y());
    const auto angB = boundaryAngles(quad, cladding.family, b.x(), b.y());
    const double needStart =
        std::max(0.5 * (lamellaFootprint(w, angA[0]) + lamellaFootprint(w, angB[0])), extra);
    const double needEnd =
        std::max(0.5 * (lamellaFootprint(w, angA[1]) + lamellaFootprint(w, angB[1])), extra);
    return std::abs(b.x() - a.x()) * startSideLength >= needStart &&
           std::abs(b.y() - a.y()) * endSideLength >= needEnd;
  };

  std::vector<double> chosen;
  std::vector<MemberOrigin> origins;
  if (options.count >= 2) {
    for (int k = 0; k < options.count; ++k) {
      chosen.push_back(total * k / (options.count - 1));
      origins.push_back(k == 0 || k == options.count - 1 ? MemberOrigin::Boundary
                                                         : MemberOrigin::Even);
    }
    for (size_t k = 1; k < chosen.size(); ++k)
      if (!spacingOk(chosen[k - 1], chosen[k], 0.0))
        throw InvalidInput("grid.members_per_family = " + std::to_string(options.count) +
                           " is too dense for lamellas of width " + std::to_string(w) +
                           " m on this patch");
  } else {
    const double target = options.spacingFactor * w;
    // Section 2.4.4 on C smoothed over a physical length (MemberOptions::smoothingFraction): the
    // piecewise-linear intersection carries slope noise at the scale of the map grid that would
    // otherwise show up as spurious curvature extrema (dozens on the bench bump), and features
    // much narrower than the target spacing cannot get members of their own anyway.
    // Never narrower than 1.5 x the longest step of C's samples: C is piecewise linear, so its
    // smoothed curvature C_s'' is a sum of Gaussians of width sigma, one per sample, weighted by
    // the slope change there. With sigma well below the step each sample is a bump of its own and a
    // curvature extremum (on 40 m sides sampled every 0.4 m, sigma 0.2 m gave 15 curvature members
    // instead of 4); from about one step on the bumps merge (for equal steps h the ripple is
    // 2 exp(-2 pi^2 sigma^2 / h^2): 5e-9 at sigma = h, 1e-19 at 1.5 h, margin for uneven steps).
    // C resolves no feature narrower than its steps, so this costs little; where it applies, the
    // members depend on the sampling through sigma (steps of 0.4 m instead of 0.2 m on those sides:
    // same members, curvature extrema moved by up to 8 cm).
    double longestStep = 0.0;
    for (size_t k = 1; k < curve.t.size(); ++k)
      longestStep = std::max(longestStep, curve.t[k] - curve.t[k - 1]);
    const double sigma = std::max(options.smoothingFraction * target, kSigmaInSteps * longestStep);
    const SmoothedLength smoothed(curve.t, cladding.lengths, sigma);
    const auto tiers = featureCandidates(smoothed, total, sigma, options);

    // Greedy by priority, length extrema before curvature extrema; a candidate needs half the
    // target spacing (and the lamella footprint d+/d-) to every member placed so far. A candidate
    // blocked only by one member of its own tier whose priority it nearly ties (within tieBand)
    // pulls that member towards itself instead of being dropped, with a weight from 0 at the edge
    // of the band to 1/2 at an exact tie: as two crowding priorities cross, the member moves
    // continuously instead of jumping from one feature to the other.
    chosen = {0.0, total};
    origins = {MemberOrigin::Boundary, MemberOrigin::Boundary};
    std::vector<double> priorities{0.0, 0.0};
    std::vector<bool> merged{true,
                             true};  // boundaries never move; a feature member merges at most once
    for (const auto& tier : tiers)
      for (const auto& candidate : tier) {
        std::vector<size_t> blockers;
        for (size_t i = 0; i < chosen.size(); ++i)
          if (!spacingOk(chosen[i], candidate.t, 0.5 * target)) blockers.push_back(i);
        if (blockers.empty()) {
          chosen.push_back(candidate.t), origins.push_back(candidate.origin);
          priorities.push_back(candidate.priority), merged.push_back(false);
          continue;
        }
        const size_t b = blockers.front();
        if (blockers.size() != 1 || merged[b] || origins[b] != candidate.origin ||
            options.tieBand <= 0.0 || candidate.priority < (1.0 - options.tieBand) * priorities[b])
          continue;
        const double weight =
            0.5 * (1.0 - (priorities[b] - candidate.priority) / (options.tieBand * priorities[b]));
        const double moved = chosen[b] + weight * (candidate.t - chosen[b]);
        bool fits = true;
        for (size_t i = 0; i < chosen.size() && fits; ++i)
          fits = i == b || spacingOk(chosen[i], moved, 0.5 * target);
        if (fits) chosen[b] = moved, merged[b] = true;
      }
    std::vector<size_t> order(chosen.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return chosen[a] < chosen[b]; });
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
