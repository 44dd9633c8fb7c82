// egg sweep end to end: a two-variant sweep of a small bump patch expanded by the egg program, its
// jobs.txt run by GNU parallel, collected into sweep.csv (one row per variant, numbers equal to
// each run's report.json) and sweep.svg (rendered by rsvg-convert when present).
#include "apps/bench/sweep.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

std::string slurpFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',')
      out.emplace_back();
    else
      out.back().push_back(c);
  }
  return out;
}

TEST(SweepCollect, SlowSmallSweepRunsWithGnuParallelAndCollects) {
  if (!fs::exists("/usr/bin/parallel"))
    GTEST_SKIP() << "GNU parallel not installed (scripts/install-deps.sh installs it)";
  const fs::path d = fs::temp_directory_path() / ("egg_sweep_e2e_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "bump.json") << R"({"name": "bump_patch",
    "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5}, "edge_length_m": 0.5},
    "patching": {"patches": [[[-3,-3,0],[3,-3,0],[3,3,0],[-3,3,0]]]},
    "grid": {"map_resolution": 30, "members_per_family": 5},
    "lamella": {"width_m": 0.1, "thickness_m": 0.01},
    "simulation": {"gravity": false}, "outputs": ["report"]})";
  std::ofstream(d / "sweep.json")
      << R"({"base": "bump.json", "parameters": {"lamella.thickness_m": [0.01, 0.02]}})";
  const std::string egg = EGG_BINARY;
  const fs::path out = d / "sweep";
  ASSERT_EQ(std::system((shellQuote(egg) + " sweep " + shellQuote((d / "sweep.json").string()) +
                         " --out " + shellQuote(out.string()) + " > /dev/null")
                            .c_str()),
            0);
  ASSERT_EQ(std::system(("parallel --will-cite -j2 --joblog " +
                         shellQuote((out / "joblog.txt").string()) + " < " +
                         shellQuote((out / "jobs.txt").string()))
                            .c_str()),
            0);
  ASSERT_EQ(std::system(
                (shellQuote(egg) + " sweep --collect " + shellQuote(out.string()) + " > /dev/null")
                    .c_str()),
            0);

  std::istringstream csv(slurpFile(out / "sweep.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const auto header = split(line);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* key : {"variant", "/lamella/thickness_m", "status", "patches", "rmse_m",
                          "max_error_m", "wall_s", "mass_kg", "pareto"})
    ASSERT_TRUE(col.count(key)) << key;
  int rows = 0;
  while (std::getline(csv, line)) {
    const auto f = split(line);
    ASSERT_EQ(f.size(), header.size());
    ++rows;
    EXPECT_EQ(f[col["variant"]], rows == 1 ? "v001" : "v002");
    EXPECT_EQ(f[col["/lamella/thickness_m"]], rows == 1 ? "0.01" : "0.02");
    EXPECT_EQ(f[col["status"]], "ok");
    const auto report = nlohmann::json::parse(slurpFile(out / "runs" / f[0] / "report.json"));
    EXPECT_EQ(std::stod(f[col["patches"]]), report["patching"]["patches"].get<double>());
    const double rmse = std::stod(f[col["rmse_m"]]), maxError = std::stod(f[col["max_error_m"]]),
                 wall = std::stod(f[col["wall_s"]]);
    EXPECT_TRUE(std::isfinite(rmse) && rmse > 0 && maxError >= rmse && wall > 0);
    EXPECT_NEAR(rmse, report["simulation"]["rmse_m"].get<double>(),
                1e-5 * rmse);  // CSV has 6 significant digits
    EXPECT_NEAR(maxError, report["simulation"]["max_error_m"].get<double>(), 1e-5 * maxError);
    EXPECT_NEAR(wall, report["timings"]["total_s"].get<double>(), 1e-5 * wall);
  }
  EXPECT_EQ(rows, 2);
  const std::string svg = slurpFile(out / "sweep.svg");
  EXPECT_NE(svg.find("against lamella mass"), std::string::npos);
  if (std::system("command -v rsvg-convert > /dev/null 2>&1") == 0) {
    EXPECT_EQ(std::system(("rsvg-convert " + shellQuote((out / "sweep.svg").string()) + " -o " +
                           shellQuote((d / "sweep.png").string()))
                              .c_str()),
              0);
  }

  // A run that is missing is listed, and the exit status says so.
  fs::remove_all(out / "runs" / "v002");
  EXPECT_NE(std::system((shellQuote(egg) + " sweep --collect " + shellQuote(out.string()) +
                         " > /dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_NE(slurpFile(out / "sweep.csv").find("v002,0.02,missing,"), std::string::npos);
  fs::remove_all(d);
}

}  // namespace
}  // namespace egg::app
