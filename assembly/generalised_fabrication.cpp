// A generalised patch's fabrication input (see generalised_fabrication.hpp).
#include "assembly/generalised_fabrication.hpp"

#include "core/errors.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace egg::assembly {
namespace {

std::string fabricationEndId(const GeneralisedPatch& g, int rod, bool atStart) {
  const bool isU = rod < static_cast<int>(g.grid.u.size());
  return fmt::format("P{}-{}{}-{}", g.patchId, isU ? 'U' : 'V',
                     isU ? rod : rod - static_cast<int>(g.grid.u.size()),
                     atStart ? "start" : "end");
}

// The unit direction of a polyline's segment nearest to p.
Eigen::Vector3d fabricationDirectionNear(const std::vector<Eigen::Vector3d>& line,
                                         const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  for (size_t i = 1; i < line.size(); ++i) {
    const Eigen::Vector3d d = line[i] - line[i - 1];
    if (d.norm() <= 0.0) continue;
    const double t = std::clamp((p - line[i - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double distance = (line[i - 1] + t * d - p).norm();
    if (distance < best) best = distance, direction = d.normalized();
  }
  return direction;
}

}  // namespace

std::vector<std::string> addGeneralisedToFabrication(
    const GeneralisedPatch& g, const RingBeamJoins& ring,
    const std::vector<const EggGrid*>& quadGrids, const GeneralisedFabricationOptions& options,
    std::vector<fabrication::FabricationPatch>& patches) {
  if (!(options.lamellaWidthM > 0.0) || !(options.endOverhangM >= 0.0) ||
      !(options.bracketGapM >= 0.0))
    throw InvalidInput("generalised fabrication: lamella width must be > 0, overhang and gap >= 0");
  std::vector<std::string> warnings;
  fabrication::FabricationPatch entry{g.patchId, &g.grid, std::nullopt};
  entry.boltedTo = ring.quads;
  entry.freeSides = {false, false, false, false};
  const int nu = static_cast<int>(g.grid.u.size());
  const auto memberOf = [&](int rod) -> const GridMember& {
    return rod < nu ? g.grid.u[rod] : g.grid.v[rod - nu];
  };
  // Bracket ends: how far the strip is cut back from the end point (metres along the member).
  std::vector<double> trim(g.network.anchors.size(), 0.0);
  std::vector<char> onQuad(g.network.anchors.size(), 0);
  for (const auto* joins : {&ring.bolts, &ring.brackets})
    for (const auto& join : *joins) onQuad[2 * join.rodB + (join.sBM == 0.0 ? 0 : 1)] = 1;
  for (const auto& bracket : ring.brackets) {
    const int a = 2 * bracket.rodB + (bracket.sBM == 0.0 ? 0 : 1);
    const GridMember& m = memberOf(bracket.rodB);
    const GridMember& lamella =
        bracket.rodA < static_cast<int>(quadGrids[bracket.patchA]->u.size())
            ? quadGrids[bracket.patchA]->u[bracket.rodA]
            : quadGrids[bracket.patchA]->v[bracket.rodA - quadGrids[bracket.patchA]->u.size()];
    const Eigen::Vector3d at = g.network.anchors[a].position;
    const Eigen::Vector3d along = fabricationDirectionNear(m.spatial, at);
    const Eigen::Vector3d across = fabricationDirectionNear(lamella.spatial, at);
    // Lamellas meet at 15 degrees or more (the optimiser's limit); a shallower meeting is capped.
    const double sine = std::max(along.cross(across).norm(), std::sin(15.0 * M_PI / 180.0));
    const double cosine = std::sqrt(std::max(0.0, 1.0 - sine * sine));
    // The square end clear of the lamella's face by the gap: its centre line (w/2)/sin back from
    // the lamella's centre line, and the corner on the acute side (w/2) cos/sin further.
    const double cut = (0.5 * options.lamellaWidthM * (1.0 + cosine) + options.bracketGapM) / sine;
    // The end's bolt sits an overhang in from the trimmed end; every crossing's hole or slot must
    // stay an overhang clear of it.
    const double hole = cut + options.endOverhangM;
    const bool atStart = bracket.sBM == 0.0;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& c : g.grid.connections) {
      const bool onIt =
          bracket.rodB < nu ? c.memberU == bracket.rodB : c.memberV == bracket.rodB - nu;
      if (!onIt) continue;
      const double s = bracket.rodB < nu ? c.sBarU : c.sBarV;
      const double l = bracket.rodB < nu ? c.notchU : c.notchV;
      nearest =
          std::min(nearest, atStart ? std::min(s, s + l) : m.planarLength - std::max(s, s + l));
    }
    // And the bolt at the other end, trimmed or not.
    const double otherEnd = trim[a ^ 1] > 0.0 ? trim[a ^ 1] + options.endOverhangM : 0.0;
    const std::string id = fabricationEndId(g, bracket.rodB, atStart);
    if (hole + options.endOverhangM > nearest) {
      warnings.push_back(fmt::format("{} (bolt {:.0f} mm, crossing {:.0f} mm from the end)", id,
                                     1000.0 * hole, 1000.0 * nearest));
      continue;
    }
    if (hole + options.endOverhangM + otherEnd > m.planarLength) {
      warnings.push_back(fmt::format("{} (bolt {:.0f} mm from the end, too short a member for it)",
                                     id, 1000.0 * hole));
      continue;
    }
    trim[a] = cut;
    entry.endTrims.push_back({m.family, m.index, atStart, 1000.0 * (cut + options.endOverhangM)});
  }
  for (size_t a = 0; a < g.network.anchors.size(); ++a) {
    const auto& anchor = g.network.anchors[a];
    const GridMember& m = memberOf(anchor.rod);
    const std::string id = fabricationEndId(g, anchor.rod, a % 2 == 0);
    // The end's bolt: at the end point, or an overhang in from a trimmed end.
    const double in = trim[a] > 0.0 ? trim[a] + options.endOverhangM : 0.0;
    entry.extraHoles.push_back(
        {m.family, m.index, a % 2 == 0 ? anchor.sM + in : anchor.sM - in, id, true});
    // A support under it unless a quad's lamella carries it (bolted or by a bracket): on the
    // design boundary or a hole's rim, at a cut between pieces, or on a side with no lamella in
    // reach, as the simulations hold it.
    if (!onQuad[a]) entry.endSupports.push_back({id, anchor.position, anchor.normal});
  }
  // The quad's lamella gets the partner hole of each bolted end (the same bolt) and the hole of
  // each bracket's second bolt.
  for (const auto* joins : {&ring.bolts, &ring.brackets}) {
    for (const auto& join : *joins) {
      for (auto& quad : patches) {
        if (quad.patchId != join.patchA) continue;
        const int u = static_cast<int>(quad.grid->u.size());
        const Family family = join.rodA < u ? Family::U : Family::V;
        const int member = join.rodA < u ? join.rodA : join.rodA - u;
        const std::string id = fabricationEndId(g, join.rodB, join.sBM == 0.0);
        const bool bracket = joins == &ring.brackets;
        quad.extraHoles.push_back({family, member, join.sAM, id, bracket});
        if (bracket)
          entry.ringBeamBrackets.push_back(
              {id, fmt::format("P{}-{}{}", quad.patchId, family == Family::U ? 'U' : 'V', member)});
      }
    }
  }
  patches.push_back(std::move(entry));
  return warnings;
}

}  // namespace egg::assembly
