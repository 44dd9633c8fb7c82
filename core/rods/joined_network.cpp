#include "core/rods/joined_network.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace egg::rods {

JoinedNetwork joinPatches(const std::vector<RodNetwork>& patches,
                          const std::vector<PatchJoin>& joins) {
  if (patches.empty()) throw InvalidInput("joinPatches: no patches");
  JoinedNetwork joined;
  for (size_t p = 0; p < patches.size(); ++p) {
    const RodNetwork& patch = patches[p];
    try {
      validateNetwork(patch);
    } catch (const InvalidInput& e) {
      throw InvalidInput("patch " + std::to_string(p) + ": " + e.what());
    }
    const int offset = static_cast<int>(joined.network.rods.size());
    joined.firstRod.push_back(offset);
    joined.network.rods.insert(joined.network.rods.end(), patch.rods.begin(), patch.rods.end());
    for (Connection c : patch.connections) {
      c.rodA += offset;
      c.rodB += offset;
      joined.network.connections.push_back(c);
    }
    for (Anchor a : patch.anchors) {
      a.rod += offset;
      joined.network.anchors.push_back(a);
    }
  }
  joined.firstJoin = static_cast<int>(joined.network.connections.size());
  for (size_t j = 0; j < joins.size(); ++j) {
    const PatchJoin& join = joins[j];
    const std::string name = "join " + std::to_string(j);
    for (auto [patch, rod] :
         {std::pair{join.patchA, join.rodA}, std::pair{join.patchB, join.rodB}}) {
      if (patch < 0 || patch >= static_cast<int>(patches.size())) {
        throw InvalidInput(name + ": patch " + std::to_string(patch) + " does not exist");
      }
      if (rod < 0 || rod >= static_cast<int>(patches[patch].rods.size())) {
        throw InvalidInput(name + ": patch " + std::to_string(patch) + " has no rod " +
                           std::to_string(rod));
      }
    }
    if (join.patchA == join.patchB) throw InvalidInput(name + ": joins a patch to itself");
    Connection c;
    c.rodA = joined.firstRod[join.patchA] + join.rodA;
    c.sAM = join.sAM;
    c.rodB = joined.firstRod[join.patchB] + join.rodB;
    c.sBM = join.sBM;
    if (joined.network.rods[c.rodA].layer == joined.network.rods[c.rodB].layer) {
      throw InvalidInput(
          name + ": the two boundary lamellas are in the same layer; one must lie on the other");
    }
    joined.network.connections.push_back(c);
  }
  try {
    validateNetwork(joined.network);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("joined network: ") + e.what());
  }
  return joined;
}

JoinedSimulation simulateJoinedPatches(const std::vector<RodNetwork>& patches,
                                       const std::vector<PatchJoin>& joins, const TriMesh& surface,
                                       const SimulationOptions& options) {
  const JoinedNetwork joined = joinPatches(patches, joins);
  const SurfaceDistance distance(surface);
  JoinedSimulation result;
  result.converged = true;
  double sumSquares = 0.0;
  for (const RodNetwork& patch : patches) {
    result.perPatch.push_back(simulateRods(patch, &distance, options));
    const SimulationRun& run = result.perPatch.back();
    result.converged = result.converged && run.solver.converged;
    const DeviationStats& d = *run.deviation;
    sumSquares += d.rmseM * d.rmseM * d.points;
    result.patchByPatch.points += d.points;
    result.patchByPatch.maxM = std::max(result.patchByPatch.maxM, d.maxM);
  }
  result.patchByPatch.rmseM =
      result.patchByPatch.points > 0 ? std::sqrt(sumSquares / result.patchByPatch.points) : 0.0;
  result.patchByPatch.nrmse = result.patchByPatch.rmseM / options.scaleFactor;
  result.joined = simulateRods(joined.network, &distance, options);
  result.converged = result.converged && result.joined.solver.converged;
  return result;
}

}  // namespace egg::rods
