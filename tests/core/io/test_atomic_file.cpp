#include "core/io/atomic_file.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace egg {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, ReplacesWholeAndLeavesNoTemporaries) {
  const fs::path root = fs::temp_directory_path() / ("egg_atomic_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  writeFileAtomically(root / "a.txt", "first");
  writeFileAtomically(root / "a.txt", "second");
  EXPECT_EQ(readAll(root / "a.txt"), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
  fs::remove_all(root);
}

TEST(AtomicFile, MissingFolderIsAnIoErrorNamingThePath) {
  try {
    writeFileAtomically("/nonexistent_egg_dir/sub/a.txt", "x");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_egg_dir/sub/a.txt"), std::string::npos);
  }
}

TEST(AtomicFile, SuffixesDiffer) {
  EXPECT_EQ(temporarySuffix().size(), 8u);
  EXPECT_NE(temporarySuffix(), temporarySuffix());
}

}  // namespace
}  // namespace egg
