#pragma once
// The joined simulation of a multi-patch grid (beyond the paper, whose patches were simulated
// apart, 3.7.1): the patches' rod networks side by side, with the two boundary lamellas of every
// shared side bolted together at the member ends they share (assembly/patch_joins.hpp).
#include "assembly/generalised_patch.hpp"
#include "core/rods/joined_network.hpp"
#include "pipeline/patching_stage.hpp"
#include "pipeline/run_state.hpp"
#include "pipeline/scene.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

struct JoinedRun {
  std::optional<rods::SimulationResult>
      simulation;  // the joined structure (with notches as the scene says)
  std::vector<rods::PatchJoin> joins;
  std::optional<rods::JoinedNetwork> network;  // what was simulated
  std::vector<char> swapped;                   // per patch: u members on top
  int sidesJoined = 0;                         // shared sides carrying at least one bolt
  int sidesSkipped = 0;                        // shared sides whose lamellas fell in one layer
  bool warmStart = false;  // started from the converged patch-by-patch equilibria
  // Generalised patches (issue 41) in the structure, after the quads: their member ends on a quad's
  // side bolted to its boundary lamella where they lie in the other layer (ringBeamJoins).
  int generalisedPatches = 0;
  int ringBeamBolts = 0, ringBeamSameLayer = 0, ringBeamUnmatched = 0;
  double ringBeamMaxGapM = 0.0;
  std::string failure;  // an error of the joined run (not non-convergence)
  double seconds = 0.0;
};

// The generalised patches of the run, each with its own deployment (per piece, as
// RunState::infillSimulations) for the warm start.
struct JoinedGeneralised {
  const std::vector<assembly::GeneralisedPatch>* patches = nullptr;
  const std::vector<std::optional<rods::SimulationResult>>* runs = nullptr;
};

JoinedRun simulateJoined(const PatchingRun& run, const std::vector<SolvedPatch>& patches,
                         const TriMesh& surface, const Scene& scene,
                         const JoinedGeneralised& generalised = {});

// report.json simulation.joined{}.
nlohmann::json joinedSection(const JoinedRun& joined);

// The pipeline's step: when members were propagated (or generalised patches bolt to a quad), the
// scene joins patches and two or more are solved, simulates the joined structure; writes
// simulation.joined{} (or why it did not run) and simulation.patch_by_patch{rmse_m, max_error_m}
// (the pooled per-patch figures beside it). `patchesHeldAllRound`: the patch-by-patch runs held
// every patch along all its sides; then a patch that collapsed there skips the joined run
// (collapsedWhileHeld), which would only spend its whole iteration budget falling (Yas: 500
// iterations, ~8 minutes on 142k unknowns). Returns the joined run's deployed state when it ran
// (for the report's deviation figure).
std::optional<rods::SimulationRun> addJoinedSimulation(
    const PatchingRun& run, const std::vector<SolvedPatch>& patches, const TriMesh& surface,
    const Scene& scene, bool propagated, int solved, nlohmann::json& simulation,
    bool patchesHeldAllRound = false, std::optional<rods::JoinedNetwork>* network = nullptr,
    const JoinedGeneralised& generalised = {});

// Why the joined run is pointless, or empty: the first patch whose patch-by-patch run (held along
// all its sides) collapsed under its own weight (Section 3.5.2, Fig. 3.11).
std::string collapsedWhileHeld(const std::vector<SolvedPatch>& patches);

}  // namespace egg::pipeline
