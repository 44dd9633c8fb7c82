#include "core/egg/solve_patch.hpp"
#include "core/timing.hpp"

#include <chrono>
#include <utility>

namespace egg {

EggResult solveEgg(const TriMesh& surface, const std::array<Eigen::Vector3d, 4>& corners,
                   const EggOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();

  auto t = std::chrono::steady_clock::now();
  Patch patch = makePatch(surface, corners, options.patch);
  const double patchSeconds = secondsSince(t);

  PatchDesign design = designPatch(std::move(patch), options);
  requireFeasible(design);

  EggResult result;
  result.seconds = design.seconds;
  result.seconds.patch = patchSeconds;

  t = std::chrono::steady_clock::now();
  result.membersU = placeDesignMembers(design, Family::U, options.members);
  result.membersV = placeDesignMembers(design, Family::V, options.members);
  result.seconds.members = secondsSince(t);

  t = std::chrono::steady_clock::now();
  result.grid = traceDesignGrid(design, result.membersU, result.membersV, options.grid);
  result.seconds.tracing = secondsSince(t);
  result.propagations = design.propagations + design.patch.propagations + result.grid.propagations;

  result.patch = std::move(design.patch);
  result.uniqueness = std::move(design.uniqueness);
  result.maps = std::move(design.maps);
  result.alphaBar = std::move(design.alphaBar);
  result.seconds.total = secondsSince(started);
  return result;
}

}  // namespace egg
