#include "core/egg/grid_io.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace egg {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GridIo, WritesJsonObjAndSvgThatReadBack) {
  const TriMesh mesh = samples::generateSample(
      "bump", {{"height", 0.8}, {"sigma", 2.0}, {"length", 8.0}, {"width", 8.0}}, 0.5);
  EggOptions options;
  options.maps.resolution = 21;
  options.members.count = 5;
  const auto r =
      solveEgg(mesh, {Eigen::Vector3d(-3, -3, 0), {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}}, options);
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_grid_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  writeGridJson(r, (dir / "grid.json").string(), 7);
  writeGridObj(r.grid, (dir / "grid.obj").string(), 7);
  writePlanarSvg(r.grid, (dir / "grid.svg").string());

  const auto doc = nlohmann::json::parse(slurp(dir / "grid.json"));
  EXPECT_EQ(doc["patch"]["id"], 7);
  EXPECT_EQ(doc["members"]["u"].size(), 5u);
  EXPECT_EQ(doc["connections"].size(), 25u);
  EXPECT_DOUBLE_EQ(doc["max_notch_m"].get<double>(), r.grid.maxNotch);
  EXPECT_DOUBLE_EQ(doc["alpha_bar"]["value_rad"].get<double>(), r.alphaBar.alphaBar);
  EXPECT_DOUBLE_EQ(doc["connections"][12]["notch_u_m"].get<double>(),
                   r.grid.connections[12].notchU);

  const std::string obj = slurp(dir / "grid.obj");
  size_t lines = 0, pos = 0;
  while ((pos = obj.find("\nl ", pos)) != std::string::npos) ++lines, ++pos;
  EXPECT_EQ(lines, 10u);
  // Members named by their lamella ids (issue 38).
  EXPECT_NE(obj.find("\no P7-U0\ng P7-U0\n"), std::string::npos);
  EXPECT_NE(obj.find("\no P7-V4\ng P7-V4\n"), std::string::npos);
  const std::string svg = slurp(dir / "grid.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "grid.svg.tmp"));
  EXPECT_THROW(writeGridObj(r.grid, (dir / "missing" / "grid.obj").string()), IoError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace egg
