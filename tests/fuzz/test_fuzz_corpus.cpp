// Replays the fuzz corpus (tests/fuzz/corpus/<target>/) through the fuzz targets' entry points in
// the normal suite (issue 17): no crash, no exception other than a typed egg::Error. The seeds
// include inputs that once crashed or hung `egg` (deep nesting, 1e400, bad indices).
#include "tests/fuzz/fuzz_entry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <vector>

namespace egg::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> corpus(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(EGG_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / target;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FuzzCorpus, SceneParserAcceptsOrRaisesATypedError) {
  const auto files = corpus("scene");
  ASSERT_GE(files.size(), 5u);
  int accepted = 0;
  for (const auto& f : files) {
    const std::string bytes = bytesOf(f);
    EXPECT_NO_THROW(accepted += scene(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()))
        << f;
  }
  EXPECT_GE(accepted, 1) << "the valid seeds parse";
}

// Issue 40: the sweep file (dry run: expanded and checked, nothing written) and the command line
// (parsed, nothing run).
TEST(FuzzCorpus, SweepFileAcceptsOrRaisesATypedError) {
  const auto files = corpus("sweep");
  ASSERT_GE(files.size(), 5u);
  int accepted = 0;
  for (const auto& f : files) {
    const std::string bytes = bytesOf(f);
    EXPECT_NO_THROW(accepted += sweep(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()))
        << f;
  }
  EXPECT_EQ(accepted, 2) << "valid_grid and valid_name_and_file, and nothing else";
}

TEST(FuzzCorpus, CommandLineAcceptsOrRaisesATypedError) {
  const auto files = corpus("cli");
  ASSERT_GE(files.size(), 5u);
  int accepted = 0;
  for (const auto& f : files) {
    const std::string bytes = bytesOf(f);
    EXPECT_NO_THROW(accepted +=
                    commandLine(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()))
        << f;
  }
  // At least run, init, geodesic, bench layout, --help, --version and surface --list parse.
  EXPECT_GE(accepted, 7);
  EXPECT_LT(accepted, static_cast<int>(files.size())) << "the bad lines are refused";
}

class MeshCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshCorpus, LoaderAcceptsOrRaisesATypedError) {
  const std::string target = GetParam();
  const auto files = corpus(target);
  ASSERT_GE(files.size(), 2u) << target;
  int accepted = 0;
  for (const auto& f : files) {
    const std::string bytes = bytesOf(f);
    EXPECT_NO_THROW(accepted += mesh("." + target, reinterpret_cast<const uint8_t*>(bytes.data()),
                                     bytes.size()))
        << f;
  }
  EXPECT_GE(accepted, 1) << "the valid seeds load";
}

INSTANTIATE_TEST_SUITE_P(Loaders, MeshCorpus,
                         ::testing::Values("obj", "stl", "ply", "off", "gltf", "glb"));

}  // namespace
}  // namespace egg::fuzz
