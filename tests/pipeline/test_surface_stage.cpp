// Loading the design surface from a file: a mesh whose size is implausible for a roof in metres is
// an error naming the size found and the scale_to_m that fixes it (issue 39).
#include "pipeline/surface_stage.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace egg::pipeline {
namespace {

namespace fs = std::filesystem;

// A gently curved n x n grid of side `size` (file units) as OBJ.
fs::path writeGrid(const std::string& name, double size) {
  const fs::path file =
      fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + ".obj");
  std::ofstream out(file);
  const int n = 6;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = size * i / n, y = size * j / n;
      out << "v " << x << " " << y << " " << 0.05 * size * (x * y) / (size * size) << "\n";
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j + 1, b = a + 1, c = a + n + 1, d = c + 1;
      out << "f " << a << " " << c << " " << d << "\nf " << a << " " << d << " " << b << "\n";
    }
  return file;
}

std::string loadError(const fs::path& file, double scaleToM) {
  SurfaceSource source;
  source.file = file;
  source.scaleToM = scaleToM;
  try {
    loadSurface(source);
  } catch (const InvalidInput& e) {
    fs::remove(file);
    return e.what();
  }
  fs::remove(file);
  return {};
}

TEST(SurfaceUnits, AMillimetreModelReadAsMetresNamesItsSizeAndTheScaleThatFixesIt) {
  const std::string message = loadError(writeGrid("egg_units_mm", 30000.0), 1.0);
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("3e+04 m across"), std::string::npos) << message;
  EXPECT_NE(message.find("\"scale_to_m\": 0.001"), std::string::npos) << message;
  EXPECT_NE(message.find("millimetres"), std::string::npos) << message;
  EXPECT_NE(message.find("30 m across"), std::string::npos) << message;
}

TEST(SurfaceUnits, AMetreModelScaledAsMillimetresIsTooSmallAndMetresAreSuggested) {
  const std::string message = loadError(writeGrid("egg_units_small", 40.0), 0.001);
  ASSERT_FALSE(message.empty());
  EXPECT_NE(message.find("0.04 m across"), std::string::npos) << message;
  EXPECT_NE(message.find("\"scale_to_m\": 1}"), std::string::npos) << message;
}

TEST(SurfaceUnits, ARoofSizedModelLoads) {
  EXPECT_EQ(loadError(writeGrid("egg_units_ok", 40.0), 1.0), "");
  EXPECT_EQ(loadError(writeGrid("egg_units_ok_mm", 40000.0), 0.001), "");
}

}  // namespace
}  // namespace egg::pipeline
