// The stage table as data: the outputs' needs followed through the stages' needs decide what
// runs (docs/architecture.md "Stage table").
#include "pipeline/stages.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace egg::pipeline {
namespace {

using S = StageId;

std::set<StageId> neededBy(const std::vector<std::string>& outputs) {
  std::set<StageId> needed;
  for (StageId stage : allStages())
    if (stageNeeded(stage, outputs)) needed.insert(stage);
  return needed;
}

TEST(Stages, TheTableHoldsEveryStageOnceInDataFlowOrder) {
  const auto& table = stageTable();
  ASSERT_EQ(table.size(), allStages().size());
  for (size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(table[i].id, allStages()[i]) << i;
    for (StageId need : table[i].needs) {
      const auto at = std::find(allStages().begin(), allStages().end(), need) - allStages().begin();
      EXPECT_LT(static_cast<size_t>(at), i) << toString(table[i].id) << " needs " << toString(need);
    }
  }
  EXPECT_STREQ(toString(S::Surface), "surface");
  EXPECT_STREQ(toString(S::Fabrication), "fabrication");
}

TEST(Stages, EachOutputNeedsItsStagesAndNothingElse) {
  const std::set<StageId> upToGrid{S::Surface, S::Patching, S::Design, S::Propagation, S::Grid};
  std::set<StageId> report = upToGrid;
  report.insert(S::Simulation);
  EXPECT_EQ(neededBy({"report"}), report);
  EXPECT_EQ(neededBy({"previews"}), report);
  EXPECT_EQ(neededBy({"plan"}), (std::set<StageId>{S::Surface, S::Patching, S::Design}));
  std::set<StageId> cut = upToGrid;
  cut.insert(S::Fabrication);
  for (const char* output : {"cut_files", "stickers", "supports"})
    EXPECT_EQ(neededBy({output}), cut) << output;
  std::set<StageId> fem = report;
  fem.insert(S::Verification);
  EXPECT_EQ(neededBy({"fem"}), fem);
  EXPECT_TRUE(neededBy({}).empty());
  std::set<StageId> all = report;
  all.insert(S::Fabrication);
  EXPECT_EQ(neededBy({"plan", "report", "cut_files"}), all);
  // The 3D model: the deployed lamellas and the fabrication stage's supports (issue 38).
  EXPECT_EQ(neededBy({"model"}), all);
}

TEST(Stages, EveryOutputIsKnownToTheTable) {
  std::set<std::string> names;
  for (const Output& output : outputTable()) {
    EXPECT_TRUE(names.insert(std::string(output.name)).second) << output.name;
    EXPECT_FALSE(output.needs.empty()) << output.name;
  }
  EXPECT_EQ(names, (std::set<std::string>{"report", "previews", "plan", "cut_files", "stickers",
                                          "supports", "fem", "model", "deployment"}));
}

}  // namespace
}  // namespace egg::pipeline
