// Generalised grid layouts, their consistency and crossings (Sections 4.4-4.5): see
// generalised_grid.hpp.
#include "core/generalised/generalised_grid.hpp"

#include "core/errors.hpp"
#include "core/geodesic/geodesic_intersection.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace egg::generalised {
namespace {

Eigen::Vector2d layoutDirection(const LayoutParameters& p, int family) {
  const double angle = p.angleRad + family * (std::numbers::pi / 2 + p.skewRad);
  return {std::cos(angle), std::sin(angle)};
}

// Forward boundary length from sample a to sample b.
double layoutForward(const GridDomain& domain, int a, int b) {
  const double d = domain.arcLength(b) - domain.arcLength(a);
  return d >= 0.0 ? d : d + domain.loopLengthM();
}

// x strictly inside the forward arc from a to b.
bool layoutInArc(int x, int a, int b, int n) {
  const int dx = ((x - a) % n + n) % n, db = ((b - a) % n + n) % n;
  return dx > 0 && dx < db;
}

// Appends the member a -> b, split at its first and last contact with a non-convex segment where
// its shortest connection would touch the boundary (at most `depth` times recursively).
void layoutAddMember(const GridDomain& domain, GridMemberSpec member, int depth,
                     std::vector<GridMemberSpec>& members) {
  if (member.start == member.end) return;
  const auto touching = depth > 0 ? domain.contacts(member.start, member.end) : std::vector<int>{};
  if (touching.empty()) {
    members.push_back(member);
    return;
  }
  GridMemberSpec before = member, after = member;
  before.end = touching.front();
  after.start = touching.back();
  before.split = after.split = true;
  layoutAddMember(domain, before, depth - 1, members);
  layoutAddMember(domain, after, depth - 1, members);
}

}  // namespace

void LayoutParameters::validate() const {
  if (!std::isfinite(angleRad)) throw InvalidInput("LayoutParameters.angle_rad must be finite");
  if (!(std::abs(skewRad) < std::numbers::pi / 3))
    throw InvalidInput("LayoutParameters.skew_rad must be within (-pi/3, pi/3)");
  for (int f = 0; f < 2; ++f) {
    if (lines[f] < 1 || lines[f] > 500)
      throw InvalidInput("LayoutParameters.lines[" + std::to_string(f) + "] must be in 1..500");
    if (!(offsets[f] >= 0.0 && offsets[f] < 1.0))
      throw InvalidInput("LayoutParameters.offsets[" + std::to_string(f) + "] must be in [0, 1)");
  }
}

void LayoutOptions::validate() const {
  if (!std::isfinite(minAnchorSpacingM))
    throw InvalidInput("LayoutOptions.min_anchor_spacing_m must be finite");
}

bool membersCross(int n, const GridMemberSpec& first, const GridMemberSpec& second) {
  const int a = first.start, b = first.end, c = second.start, d = second.end;
  if (c == a || c == b || d == a || d == b) return false;
  return layoutInArc(c, a, b, n) != layoutInArc(d, a, b, n);
}

std::vector<GridMemberSpec> lineMembers(const GridDomain& domain, const Eigen::Vector2d& direction,
                                        double offsetM, int family, int line, bool split) {
  const auto& polygon = domain.projectedBoundary();
  const int n = static_cast<int>(polygon.size());
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  // Where the line enters and leaves the projected boundary, in order along it; each crossing
  // snaps to the nearer sample of its boundary edge.
  std::vector<std::pair<double, int>> hits;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double vi = normal.dot(polygon[i]) - offsetM, vj = normal.dot(polygon[j]) - offsetM;
    if ((vi < 0.0) == (vj < 0.0)) continue;
    const double tau = vi / (vi - vj);
    const Eigen::Vector2d at = polygon[i] + tau * (polygon[j] - polygon[i]);
    hits.emplace_back(direction.dot(at), tau < 0.5 ? i : j);
  }
  std::sort(hits.begin(), hits.end());
  std::vector<GridMemberSpec> members;
  for (size_t k = 0; k + 1 < hits.size(); k += 2) {
    layoutAddMember(domain, {family, hits[k].second, hits[k + 1].second, line}, split ? 3 : 0,
                    members);
  }
  return members;
}

GeneralisedLayout layoutFromLines(const GridDomain& domain, const LayoutParameters& parameters,
                                  const LayoutOptions& options) {
  parameters.validate();
  options.validate();
  const auto& polygon = domain.projectedBoundary();
  const int n = static_cast<int>(polygon.size());
  GeneralisedLayout layout;
  for (int family = 0; family < 2; ++family) {
    const Eigen::Vector2d direction = layoutDirection(parameters, family);
    const Eigen::Vector2d normal(-direction.y(), direction.x());
    double low = INFINITY, high = -INFINITY;
    for (const auto& p : polygon) {
      low = std::min(low, normal.dot(p));
      high = std::max(high, normal.dot(p));
    }
    const double spacing = (high - low) / parameters.lines[family];
    for (int line = 0; line < parameters.lines[family]; ++line) {
      const double c = low + (line + parameters.offsets[family]) * spacing;
      for (const auto& m : lineMembers(domain, direction, c, family, line, true)) {
        layout.members.push_back(m);
        layout.splitMembers += m.split ? 1 : 0;
      }
    }
  }
  // Inside segments that cross nothing (slivers at a corner of the footprint) carry no load.
  std::vector<GridMemberSpec> kept;
  for (const auto& m : layout.members) {
    bool crosses = false;
    for (const auto& other : layout.members) {
      if (other.family != m.family && membersCross(n, m, other)) {
        crosses = true;
        break;
      }
    }
    if (crosses)
      kept.push_back(m);
    else
      ++layout.droppedMembers;
  }
  layout.members = std::move(kept);
  return layout;
}

std::string layoutProblem(const GridDomain& domain, const GeneralisedLayout& layout,
                          const LayoutOptions& options) {
  options.validate();
  const int n = domain.sampleCount();
  const double spacing =
      options.minAnchorSpacingM > 0.0 ? options.minAnchorSpacingM : 0.5 * domain.meanEdgeLengthM();
  const auto& members = layout.members;
  if (members.empty()) return "the layout has no members";
  for (size_t i = 0; i < members.size(); ++i) {
    const auto& m = members[i];
    if (m.start < 0 || m.end < 0 || m.start >= n || m.end >= n || m.start == m.end)
      return "member " + std::to_string(i) + " does not join two boundary samples";
    if (domain.connections().invalid(m.start, m.end))
      return "member " + std::to_string(i) + " runs along a non-convex part of the boundary";
  }
  for (size_t i = 0; i < members.size(); ++i) {
    bool crossesOther = false;
    for (size_t j = 0; j < members.size(); ++j) {
      if (i == j) continue;
      const bool cross = membersCross(n, members[i], members[j]);
      if (cross && members[i].family == members[j].family)
        return "members " + std::to_string(i) + " and " + std::to_string(j) +
               " of one family cross";
      crossesOther = crossesOther || cross;
      if (j < i) continue;
      // Split pieces of one line share their contact anchor on purpose.
      const bool pieces =
          members[i].line == members[j].line && members[i].family == members[j].family;
      for (int ei : {members[i].start, members[i].end}) {
        for (int ej : {members[j].start, members[j].end}) {
          if (pieces && ei == ej) continue;
          const double along =
              std::min(layoutForward(domain, ei, ej), layoutForward(domain, ej, ei));
          if (along < spacing)
            return "members " + std::to_string(i) + " and " + std::to_string(j) + " have anchors " +
                   std::to_string(along) + " m apart";
        }
      }
    }
    if (!crossesOther) return "member " + std::to_string(i) + " crosses no other member";
  }
  return "";
}

std::vector<GridCrossing> gridCrossings(const GridDomain& domain, const GeneralisedLayout& layout) {
  const int n = domain.sampleCount();
  std::vector<GridCrossing> crossings;
  for (size_t i = 0; i < layout.members.size(); ++i) {
    for (size_t j = 0; j < layout.members.size(); ++j) {
      if (layout.members[i].family == 0 && layout.members[j].family == 1 &&
          membersCross(n, layout.members[i], layout.members[j])) {
        GridCrossing c;
        c.g = static_cast<int>(i);
        c.h = static_cast<int>(j);
        crossings.push_back(c);
      }
    }
  }
  const auto& mesh = domain.mesh();
  tbb::parallel_for(size_t(0), crossings.size(), [&](size_t k) {
    auto& c = crossings[k];
    const auto& g = layout.members[c.g];
    const auto& h = layout.members[c.h];
    const auto& dA = domain.field(g.start);
    const auto& dC = domain.field(h.start);
    const auto found = geodesic::intersectGeodesics(
        mesh, dA, domain.field(g.end), dC, domain.field(h.end), domain.distance(g.start, g.end),
        domain.distance(h.start, h.end));
    c.found = found.found && found.point.face >= 0;
    if (found.point.face < 0) return;  // no finite excess anywhere: the fields do not meet
    c.point = found.point;
    c.position = found.position;
    const auto ids = faceVertices(mesh, found.point.face);
    double sG = 0.0, sH = 0.0;
    for (int v = 0; v < 3; ++v) {
      sG += found.point.barycentric[v] * dA[ids[v]];
      sH += found.point.barycentric[v] * dC[ids[v]];
    }
    c.sGM = std::clamp(sG, 0.0, domain.distance(g.start, g.end));
    c.sHM = std::clamp(sH, 0.0, domain.distance(h.start, h.end));
  });
  return crossings;
}

std::vector<std::pair<int, int>> neighbourMembers(const GridDomain& domain,
                                                  const GeneralisedLayout& layout) {
  std::vector<std::pair<int, int>> pairs;
  const auto& members = layout.members;
  for (size_t i = 0; i < members.size(); ++i) {
    for (size_t j = 0; j < members.size(); ++j) {
      const auto& a = members[i];
      const auto& b = members[j];
      if (a.family != b.family || b.line != a.line + 1) continue;
      // Overlap of their extents along the family's direction (the chord of their ends).
      const Eigen::Vector2d pa0 = domain.projectedBoundary()[a.start];
      const Eigen::Vector2d pa1 = domain.projectedBoundary()[a.end];
      const Eigen::Vector2d d = (pa1 - pa0).normalized();
      const double a0 = 0.0, a1 = (pa1 - pa0).norm();
      const double b0 = d.dot(domain.projectedBoundary()[b.start] - pa0);
      const double b1 = d.dot(domain.projectedBoundary()[b.end] - pa0);
      if (std::min(a1, std::max(b0, b1)) > std::max(a0, std::min(b0, b1)))
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  }
  return pairs;
}

}  // namespace egg::generalised
