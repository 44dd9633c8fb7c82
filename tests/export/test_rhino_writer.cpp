#include "export/rhino_writer.hpp"

#include "core/errors.hpp"
#include "tests/export/node_check.hpp"
#include "tests/export/synthetic_model.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

namespace egg::exporter {
namespace {

namespace fs = std::filesystem;

TEST(ExportRhino, DescriptionHasALayerPerPatchAndFamilyAndAnObjectPerLamella) {
  const StructureModel model = testing::syntheticModel(3, 2);
  const auto d = rhinoDescription(model);
  std::vector<std::string> layers;
  for (const auto& l : d["layers"]) layers.push_back(l["name"]);
  EXPECT_EQ(layers, (std::vector<std::string>{"surface", "P0", "P0-U", "P0-V", "P1", "P1-U", "P1-V",
                                              "supports"}));
  int lamellas = 0;
  for (const auto& o : d["objects"])
    if (o["user"].contains("length_m")) {
      ++lamellas;
      EXPECT_EQ(o["layer"].get<std::string>(), o["name"].get<std::string>().substr(0, 4));
      EXPECT_EQ(o["colours"].size(), o["vertices"].size());
    }
  EXPECT_EQ(lamellas, 10);
}

TEST(ExportRhino, ReadsBackThroughRhino3dmAndAWrongExpectationFails) {
  if (const std::string why = testing::nodeChecksUnavailable(); !why.empty()) GTEST_SKIP() << why;
  const fs::path dir = fs::temp_directory_path() / ("egg_test_3dm_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const StructureModel model = testing::syntheticModel(3, 2);
  write3dm(model, dir / "model.3dm");
  ASSERT_TRUE(fs::is_regular_file(dir / "model.3dm"));
  // Only the file: the description, log and temporary output are gone.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  const std::string file = (dir / "model.3dm").string();
  const auto ok = testing::runNodeScript("check_3dm.mjs", file + " P0-U,P0-V,P1-U,P1-V 10");
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  EXPECT_EQ(testing::runNodeScript("check_3dm.mjs", file + " P0-U,P0-V,P1-U 10").exitCode, 1);
  EXPECT_EQ(testing::runNodeScript("check_3dm.mjs", file + " P0-U,P0-V,P1-U,P1-V 9").exitCode, 1);
  // A model with a lamella less reads back with 9.
  StructureModel fewer = model;
  fewer.lamellas.pop_back();
  write3dm(fewer, dir / "fewer.3dm");
  EXPECT_EQ(testing::runNodeScript("check_3dm.mjs",
                                   (dir / "fewer.3dm").string() + " P0-U,P0-V,P1-U,P1-V 10")
                .exitCode,
            1);
  fs::remove_all(dir);
}

TEST(ExportRhino, MissingPackageIsAReasonNotAFile) {
  const char* before = std::getenv("EGG_EXPORT_JS");
  const std::string saved = before ? before : "";
  const fs::path empty =
      fs::temp_directory_path() / ("egg_test_nojs_" + std::to_string(::getpid()));
  fs::create_directories(empty);
  ::setenv("EGG_EXPORT_JS", empty.c_str(), 1);
  EXPECT_FALSE(rhinoUnavailableReason().empty());
  EXPECT_THROW(write3dm(testing::syntheticModel(), empty / "model.3dm"), Error);
  EXPECT_FALSE(fs::exists(empty / "model.3dm"));
  if (before)
    ::setenv("EGG_EXPORT_JS", saved.c_str(), 1);
  else
    ::unsetenv("EGG_EXPORT_JS");
  fs::remove_all(empty);
}

}  // namespace
}  // namespace egg::exporter
