// A generalised patch as a grid and a rod network in grid order (see generalised_patch.hpp).
#include "assembly/generalised_patch.hpp"

#include "assembly/boundary_members.hpp"
#include "core/errors.hpp"

#include <algorithm>
#include <string>

namespace egg::assembly {
namespace {

// The unit normal of a traced member at arc length s along its polyline (linear between points).
Eigen::Vector3d generalisedNormalAt(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& normals, double s) {
  double arc = 0.0;
  for (size_t i = 1; i < points.size(); ++i) {
    const double step = (points[i] - points[i - 1]).norm();
    if (arc + step >= s || i + 1 == points.size()) {
      const double f = step > 0.0 ? std::clamp((s - arc) / step, 0.0, 1.0) : 0.0;
      return ((1.0 - f) * normals[i - 1] + f * normals[i]).normalized();
    }
    arc += step;
  }
  return normals.front().normalized();
}

double generalisedPolylineLength(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

}  // namespace

GeneralisedPatch generalisedPatch(const patching::InfillPiece& piece, int pieceIndex, int patchId,
                                  bool swapLayers) {
  const std::string name = "generalised patch G" + std::to_string(pieceIndex);
  if (!piece.design) throw InvalidInput(name + " has no grid");
  const auto& design = *piece.design;
  const auto& members = design.layout.members;
  const auto& source = design.network;
  if (piece.memberEndHolds.size() != members.size() || source.rods.size() != members.size() ||
      design.planar.endpoints.size() != members.size() ||
      source.connections.size() != design.planarProblem.crossings.size() ||
      design.tracedCrossings.size() != source.connections.size())
    throw InvalidInput(name + ": its design is inconsistent (members, rods, crossings)");
  GeneralisedPatch out;
  out.patchId = patchId;
  out.piece = pieceIndex;
  out.swappedLayers = swapLayers;
  out.rodOfMember.assign(members.size(), -1);
  std::vector<int> indexInFamily(members.size(), -1);
  // u: the family in layer 0 (g, or h when the layers are swapped), as in a quad patch's grid.
  for (int layer : {0, 1}) {
    const int family = swapLayers ? 1 - layer : layer;
    auto& target = layer == 0 ? out.grid.u : out.grid.v;
    for (size_t m = 0; m < members.size(); ++m) {
      if (members[m].family != family) continue;
      rods::Rod rod = source.rods[m];
      rod.layer = layer;
      GridMember member;
      member.family = layer == 0 ? Family::U : Family::V;
      member.index = static_cast<int>(target.size());
      member.spatial = rod.guess;
      member.normals = rod.guessNormals;
      member.planarStart = design.planar.endpoints[m][0];
      member.planarEnd = design.planar.endpoints[m][1];
      member.spatialLength = generalisedPolylineLength(rod.guess);
      member.planarLength = rod.lengthM;
      indexInFamily[m] = member.index;
      out.rodOfMember[m] = static_cast<int>(out.network.rods.size());
      target.push_back(std::move(member));
      out.network.rods.push_back(rod);
      // The anchors at both ends (the design holds rod m's start and end at 2m, 2m + 1).
      for (int end : {0, 1}) {
        rods::Anchor anchor = source.anchors.at(2 * m + end);
        if (anchor.rod != static_cast<int>(m))
          throw InvalidInput(name + ": anchor " + std::to_string(2 * m + end) +
                             " is not on member " + std::to_string(m));
        anchor.rod = out.rodOfMember[m];
        out.network.anchors.push_back(anchor);
        out.anchorHolds.push_back(piece.memberEndHolds[m][end]);
      }
    }
  }
  for (size_t k = 0; k < source.connections.size(); ++k) {
    rods::Connection bolt = source.connections[k];
    const auto& crossing = design.planarProblem.crossings[k];
    if (bolt.rodA != crossing.g || bolt.rodB != crossing.h || members[bolt.rodA].family != 0)
      throw InvalidInput(name + ": bolt " + std::to_string(k) + " does not join g to h");
    const int g = bolt.rodA, h = bolt.rodB;
    // The u side of the connection: g's unless the layers are swapped.
    const int u = swapLayers ? h : g;
    const double sBarU = swapLayers ? bolt.sBM : bolt.sAM, sBarV = swapLayers ? bolt.sAM : bolt.sBM;
    const rods::Notch& notchU = swapLayers ? bolt.notchB : bolt.notchA;
    const rods::Notch& notchV = swapLayers ? bolt.notchA : bolt.notchB;
    GridConnection c;
    c.memberU = indexInFamily[u];
    c.memberV = indexInFamily[swapLayers ? g : h];
    c.spatial = design.tracedCrossings[k];
    c.normal =
        generalisedNormalAt(source.rods[g].guess, source.rods[g].guessNormals, design.tracedSGM[k]);
    const auto& ends = design.planar.endpoints[u];
    const Eigen::Vector2d along = (ends[1] - ends[0]).normalized();
    c.planar = ends[0] + sBarU * along;
    c.sBarU = sBarU;
    c.sBarV = sBarV;
    c.notchU = notchU.afterM - notchU.beforeM;  // l = s - s_bar (one side is zero)
    c.notchV = notchV.afterM - notchV.beforeM;
    c.sU = c.sBarU + c.notchU;
    c.sV = c.sBarV + c.notchV;
    out.grid.maxNotch = std::max({out.grid.maxNotch, std::abs(c.notchU), std::abs(c.notchV)});
    out.grid.connections.push_back(c);
    bolt.rodA = out.rodOfMember[g];
    bolt.rodB = out.rodOfMember[h];
    out.network.connections.push_back(bolt);
  }
  out.grid.seconds = design.seconds;
  rods::validateNetwork(out.network);
  return out;
}

RingBeamJoins ringBeamJoins(const GeneralisedPatch& patch, int generalisedIndex,
                            const std::vector<const EggGrid*>& grids,
                            const std::vector<char>& swapped, double toleranceM) {
  RingBeamJoins out;
  for (size_t a = 0; a < patch.network.anchors.size(); ++a) {
    if (patch.anchorHolds[a] != patching::AnchorHold::PatchSide) continue;
    const rods::Anchor& anchor = patch.network.anchors[a];
    // The nearest boundary lamella of any quad patch, and where along it (planar arc length).
    double best = INFINITY, bestS = 0.0;
    int bestPatch = -1, bestRod = -1, bestLayer = 0;
    for (size_t p = 0; p < grids.size(); ++p) {
      if (!grids[p]) continue;
      for (int side = 0; side < 4; ++side) {
        const BoundaryLamella lamella = boundaryLamella(*grids[p], PatchSide(side));
        const GridMember& m =
            lamella.family == Family::U ? grids[p]->u[lamella.member] : grids[p]->v[lamella.member];
        double arc = 0.0;
        for (size_t i = 1; i < m.spatial.size(); ++i) {
          const Eigen::Vector3d d = m.spatial[i] - m.spatial[i - 1];
          const double step = d.norm();
          const double t =
              step > 0.0 ? std::clamp((anchor.position - m.spatial[i - 1]).dot(d) / (step * step),
                                      0.0, 1.0)
                         : 0.0;
          const double distance = (m.spatial[i - 1] + t * d - anchor.position).norm();
          if (distance < best) {
            best = distance, bestPatch = static_cast<int>(p), bestRod = lamella.rod;
            // Spatial arc to planar arc: the lamella is cut at its geodesic's length (criterion i).
            bestS = std::clamp((arc + t * step) * m.planarLength / std::max(m.spatialLength, 1e-12),
                               0.0, m.planarLength);
            const bool swap = p < swapped.size() && swapped[p];
            bestLayer = (lamella.family == Family::U ? 0 : 1) ^ (swap ? 1 : 0);
          }
          arc += step;
        }
      }
    }
    if (bestPatch < 0 || best > toleranceM) {
      ++out.unmatched;
      continue;
    }
    if (std::find(out.quads.begin(), out.quads.end(), bestPatch) == out.quads.end())
      out.quads.insert(std::upper_bound(out.quads.begin(), out.quads.end(), bestPatch), bestPatch);
    const rods::PatchJoin join{bestPatch, bestRod, bestS, generalisedIndex, anchor.rod, anchor.sM};
    if (patch.network.rods[anchor.rod].layer == bestLayer) {
      ++out.sameLayer;
      out.brackets.push_back(join);
      continue;
    }
    out.bolts.push_back(join);
    out.releasedAnchors.push_back(static_cast<int>(a));
    out.maxGapM = std::max(out.maxGapM, best);
  }
  return out;
}

std::vector<GeneralisedPatch> generalisedPatches(const patching::InfillResult& infill,
                                                 int firstPatchId,
                                                 const std::vector<const EggGrid*>& quadGrids,
                                                 const std::vector<char>& quadSwaps,
                                                 double toleranceM) {
  std::vector<GeneralisedPatch> out;
  for (size_t i = 0; i < infill.pieces.size(); ++i) {
    if (!infill.pieces[i].design) continue;
    const int id = firstPatchId + static_cast<int>(i);
    GeneralisedPatch plain = generalisedPatch(infill.pieces[i], static_cast<int>(i), id, false);
    GeneralisedPatch swapped = generalisedPatch(infill.pieces[i], static_cast<int>(i), id, true);
    plain.ring = ringBeamJoins(plain, 0, quadGrids, quadSwaps, toleranceM);
    swapped.ring = ringBeamJoins(swapped, 0, quadGrids, quadSwaps, toleranceM);
    out.push_back(swapped.ring.bolts.size() > plain.ring.bolts.size() ? std::move(swapped)
                                                                      : std::move(plain));
  }
  return out;
}

}  // namespace egg::assembly
