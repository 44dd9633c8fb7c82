#include "core/io/mesh_precheck.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

namespace egg {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("egg_precheck_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

TEST(MeshPrecheck, ObjPositionsComeBackInFileOrder) {
  const auto path =
      writeFile("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
  const auto positions = precheckMeshFile(path);
  ASSERT_EQ(positions.size(), 4u);
  EXPECT_EQ(positions[2], aiVector3D(1.0f, 1.0f, 0.5f));
  fs::remove_all(path.parent_path());
}

TEST(MeshPrecheck, OffIndexOutOfRangeNamesTheLineAndFace) {
  const auto path = writeFile("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  try {
    precheckMeshFile(path);
    FAIL() << "an OFF face naming vertex 7 of 3 passed";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("line 6"), std::string::npos) << what;
    EXPECT_NE(what.find("face 0"), std::string::npos) << what;
  }
  fs::remove_all(path.parent_path());
}

TEST(MeshPrecheck, PlyCountsBeyondTheFileAreRefused) {
  const auto path = writeFile(
      "big.ply",
      "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n");
  EXPECT_THROW(precheckMeshFile(path), IoError);
  fs::remove_all(path.parent_path());
}

TEST(MeshPrecheck, ExtensionsCompareWithoutCase) {
  EXPECT_EQ(mesh_precheck::lowerExtension("Roof.GLB"), ".glb");
}

}  // namespace
}  // namespace egg
