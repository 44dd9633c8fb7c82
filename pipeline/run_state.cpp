#include "pipeline/run_state.hpp"

#include <algorithm>

namespace egg::pipeline {

RunState::RunState(const Scene& scene, std::filesystem::path staging,
                   std::function<void(const std::string&, double)> progress)
    : scene(scene),
      staging(std::move(staging)),
      report(sceneToJson(scene)),
      progress(std::move(progress)) {
  if (!this->progress) this->progress = [](const std::string&, double) {};
}

std::vector<const EggGrid*> gridsOf(const std::vector<SolvedPatch>& patches) {
  std::vector<const EggGrid*> grids;
  for (const auto& p : patches) grids.push_back(p.egg ? &p.egg->grid : nullptr);
  return grids;
}

std::vector<EggGrid*> editableGridsOf(std::vector<SolvedPatch>& patches) {
  std::vector<EggGrid*> grids;
  for (auto& p : patches) grids.push_back(p.egg ? &p.egg->grid : nullptr);
  return grids;
}

int solvedCount(const std::vector<SolvedPatch>& patches) {
  return static_cast<int>(std::count_if(patches.begin(), patches.end(),
                                        [](const SolvedPatch& p) { return p.egg.has_value(); }));
}

}  // namespace egg::pipeline
