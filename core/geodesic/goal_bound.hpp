#pragma once
// Internal: the lower bound that directs a propagation at its targets (A*, Hart-Nilsson-Raphael
// 1968, carried over to windows).
//
// Why: a member trace (Section 2.4.5) or a patch side (2.3.2) needs the shortest geodesic to one
// point, yet a full field covers the whole patch. Queued by d + h, where h is the straight-line
// (chord) distance to the nearest target, the propagation only sweeps the region
// d(s, p) + |p t| <= d(s, t): for a 6 m member whose geodesic is a few per cent longer than its
// chord, an ellipse about a quarter of the patch.
//
// Exactness: the chord never exceeds the geodesic distance and obeys the triangle inequality, so
// d(p) + h(p) never decreases along a path. Every queued window's key is at most the smallest
// d + h over its interval (d's minimum plus the chord distance to the interval, each a lower
// bound), so while a shorter path to a target exists, some queued window on it has a key below
// the target's current distance; once the smallest key reaches every target's distance, no
// queued window can shorten any. A pseudo-source still fires with its final distance, by the same
// argument with the vertex in the target's place. In exact mode the distances at the targets and
// the traced paths are therefore those of the full propagation (to rounding). With skipped
// near-flat saddles (the default) a bend at X offers d(X) + |X q|, which can lie a second-order
// amount below the key of the window it came from, and reads d(X) as known at that moment: the
// directed value can then be slightly longer than the full field's, never shorter (review,
// random face pairs on bumps: up to 7.8e-7 relative at 7e-4, 1.2e-5 at 3e-3), i.e. closer to or
// as far from the exact value as the full field's.
#include "core/geodesic/window_propagation.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace egg::geodesic::detail {

struct GoalBound {
  std::vector<Eigen::Vector3d> targets;  // empty: no direction (h = 0, a full field)

  bool active() const { return !targets.empty(); }

  // Chord distance from point p to the nearest target.
  double toPoint(const Eigen::Vector3d& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : targets) best = std::min(best, (t - p).norm());
    return targets.empty() ? 0.0 : best;
  }

  // Chord distance from the segment [a + f0 (b - a), a + f1 (b - a)] (0 <= f0 <= f1 <= 1) to the
  // nearest target: a lower bound of h anywhere on a window's interval.
  double toSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double f0, double f1) const {
    if (targets.empty()) return 0.0;
    const Eigen::Vector3d e = b - a;
    const double ee = e.squaredNorm();
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : targets) {
      const double f = ee > 0.0 ? std::clamp((t - a).dot(e) / ee, f0, f1) : f0;
      best = std::min(best, (a + f * e - t).norm());
    }
    return best;
  }
};

// The targets of a directed propagation: their chord bound, and when to stop.
struct DirectedTargets {
  GoalBound goal;
  std::vector<std::array<double, 3>> legs;  // per target q: |q - v| for the vertices v of q's face

  // From the targets already bucketed in `s` (Propagation::targetFace, targetWeights).
  void set(const MeshTables& t, const Propagation& s) {
    goal.targets.clear();
    legs.clear();
    for (size_t i = 0; i < s.targetFace.size(); ++i) {
      const auto& fv = t.faceVerts[s.targetFace[i]];
      const Eigen::Vector3d q = t.pointIn(s.targetFace[i], s.targetWeights[i]);
      goal.targets.push_back(q);
      legs.push_back({(q - t.positions[fv[0]]).norm(), (q - t.positions[fv[1]]).norm(),
                      (q - t.positions[fv[2]]).norm()});
    }
  }

  // The largest of the targets' current distances, counting the vertex paths d(v) + |v q| that
  // the propagation adds at the end: once the smallest queued key reaches it, every target is
  // final.
  double farthestBound(const MeshTables& t, const Propagation& s) const {
    double farthest = 0.0;
    for (size_t i = 0; i < legs.size(); ++i) {
      const auto& fv = t.faceVerts[s.targetFace[i]];
      double best = s.targetDistance[i];
      for (int k = 0; k < 3; ++k) best = std::min(best, s.vertexDistance[fv[k]] + legs[i][k]);
      farthest = std::max(farthest, best);
    }
    return farthest;
  }
};

}  // namespace egg::geodesic::detail
