// egg sweep: a 2 x 2 grid (one key, one zip group of two keys) expanded into scenes, jobs.txt,
// variants.csv and slurm.sh; a key not in the base scene names itself and writes nothing.
#include "apps/bench/sweep.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>
#include <fstream>
#include <sstream>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path freshDir(const std::string& tag) {
  const fs::path d =
      fs::temp_directory_path() / ("egg_sweep_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d / "in" / "meshes");
  return d;
}

// A base scene with a relative surface file, to check the rewrite of relative paths.
void writeBase(const fs::path& dir) {
  std::ofstream(dir / "in" / "meshes" / "m.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "in" / "base.json")
      << R"({"name": "b", "surface": {"file": "meshes/m.obj", "edge_length_m": 0.5},
    "grid": {"members_per_family": 5, "map_resolution": 30}, "lamella": {"width_m": 0.1, "thickness_m": 0.01}, "outputs": ["report"]})";
}

TEST(Sweep, ExpandsGridAndZipGroup) {
  const fs::path d = freshDir("grid");
  writeBase(d);
  std::ofstream(d / "in" / "sweep.json") << R"({"base": "base.json",
    "parameters": {"grid.members_per_family": [5, 7]},
    "zip": [{"lamella.width_m": [0.1, 0.2], "/lamella/thickness_m": [0.01, 0.02]}]})";
  const fs::path out = d / "out";
  const SweepExpansion e = expandSweep({d / "in" / "sweep.json", out, "/opt/my egg/egg", false});
  ASSERT_EQ(e.variants, (std::vector<std::string>{"v001", "v002", "v003", "v004"}));
  EXPECT_EQ(e.keys, (std::vector<std::string>{"/grid/members_per_family", "/lamella/thickness_m",
                                              "/lamella/width_m"}));
  // Odometer order: the zip group (last axis) varies fastest; its keys move together.
  const double members[] = {5, 5, 7, 7}, width[] = {0.1, 0.2, 0.1, 0.2},
               thick[] = {0.01, 0.02, 0.01, 0.02};
  for (int v = 0; v < 4; ++v) {
    const auto scene = nlohmann::json::parse(slurp(out / "scenes" / (e.variants[v] + ".json")));
    EXPECT_EQ(scene["grid"]["members_per_family"].get<double>(), members[v]);
    EXPECT_DOUBLE_EQ(scene["lamella"]["width_m"].get<double>(), width[v]);
    EXPECT_DOUBLE_EQ(scene["lamella"]["thickness_m"].get<double>(), thick[v]);
    EXPECT_EQ(scene["name"], "b-" + e.variants[v]);
    EXPECT_EQ(fs::path(scene["surface"]["file"].get<std::string>()),
              fs::absolute(d / "in" / "meshes" / "m.obj").lexically_normal());
  }
  const fs::path absOut = fs::absolute(out).lexically_normal();
  std::istringstream jobs(slurp(out / "jobs.txt"));
  std::string line;
  for (int v = 0; v < 4; ++v) {
    ASSERT_TRUE(std::getline(jobs, line));
    EXPECT_EQ(line, "'/opt/my egg/egg' run '" +
                        (absOut / "scenes" / (e.variants[v] + ".json")).string() + "' -o '" +
                        (absOut / "runs" / e.variants[v]).string() + "' -q");
  }
  EXPECT_FALSE(std::getline(jobs, line));
  EXPECT_EQ(slurp(out / "variants.csv"),
            "variant,/grid/members_per_family,/lamella/thickness_m,/lamella/"
            "width_m\nv001,5,0.01,0.1\nv002,5,0.02,0.2\nv003,7,0.01,0.1\nv004,7,0.02,0.2\n");
  const std::string slurm = slurp(out / "slurm.sh");
  EXPECT_NE(slurm.find("#SBATCH --array=1-4\n"), std::string::npos);
  EXPECT_NE(slurm.find("sed -n \"${SLURM_ARRAY_TASK_ID}p\" jobs.txt | bash"), std::string::npos);
  // A second expansion into the now non-empty folder is refused without --force, allowed with it.
  EXPECT_THROW(expandSweep({d / "in" / "sweep.json", out, "/bin/egg", false}), InvalidInput);
  std::ofstream(out / "mine.txt") << "keep";
  expandSweep({d / "in" / "sweep.json", out, "/bin/egg", true});
  EXPECT_TRUE(fs::exists(out / "mine.txt"));
  EXPECT_EQ(slurp(out / "jobs.txt").rfind("'/bin/egg' run", 0), 0u);
  fs::remove_all(d);
}

// Issue 40: a swept `name` was overwritten by "<base>-vNNN", and swept relative surface files were
// left relative, so every variant run from scenes/ failed to find its mesh.
TEST(Sweep, SweptNamesAreKeptAndSweptFilesResolvedLikeTheBases) {
  const fs::path d = freshDir("names");
  writeBase(d);
  std::ofstream(d / "in" / "meshes" / "n.obj") << "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n";
  std::ofstream(d / "in" / "sweep.json") << R"({"base": "base.json",
    "zip": [{"name": ["first", "second"], "surface.file": ["meshes/m.obj", "meshes/n.obj"]}]})";
  const fs::path out = d / "out";
  const SweepExpansion e = expandSweep({d / "in" / "sweep.json", out, "/bin/egg", false});
  ASSERT_EQ(e.variants.size(), 2u);
  const char* names[] = {"first", "second"};
  const char* meshes[] = {"m.obj", "n.obj"};
  for (int v = 0; v < 2; ++v) {
    const auto scene = nlohmann::json::parse(slurp(out / "scenes" / (e.variants[v] + ".json")));
    EXPECT_EQ(scene["name"], names[v]);
    const fs::path file = scene["surface"]["file"].get<std::string>();
    EXPECT_TRUE(file.is_absolute()) << file;
    EXPECT_EQ(file, fs::absolute(d / "in" / "meshes" / meshes[v]).lexically_normal());
    EXPECT_TRUE(fs::exists(file)) << file;
  }
  fs::remove_all(d);
}

// Issue 40: a killed sweep's staging folder (.egg-tmp-PID-*, beside DIR) was never cleaned; one a
// sweep is still at work on (its lock held) stays.
TEST(Sweep, AKilledSweepsStagingFolderIsCleanedAndALiveOneKept) {
  const fs::path d = freshDir("leftover");
  writeBase(d);
  std::ofstream(d / "in" / "sweep.json")
      << R"({"base": "base.json", "parameters": {"grid.members_per_family": [5, 7]}})";
  const pid_t dead = [] {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
  }();
  const fs::path killed = d / (temporaryFilePrefix() + std::to_string(dead) + "-abcdefgh");
  const fs::path live = d / (temporaryFilePrefix() + std::to_string(dead) + "-bcdefghi");
  for (const fs::path& f : {killed, live}) {
    fs::create_directories(f / "scenes");
    std::ofstream(f / "scenes" / "v001.json") << "{}";
  }
  {
    const LiveLock atWork(live);
    expandSweep({d / "in" / "sweep.json", d / "out", "/bin/egg", false});
    EXPECT_FALSE(fs::exists(killed));
    EXPECT_TRUE(fs::exists(live / "scenes" / "v001.json"));
  }
  EXPECT_TRUE(fs::exists(d / "out" / "jobs.txt"));
  fs::remove_all(d);
}

// Paths in jobs.txt and slurm.sh: a newline would split a job or inject a #SBATCH line; a user's
// own scenes/ folder is never replaced by --force.
TEST(Sweep, ControlCharactersInPathsAndForeignScenesAreRefused) {
  const fs::path d = freshDir("hostile");
  writeBase(d);
  std::ofstream(d / "in" / "sweep.json")
      << R"({"base": "base.json", "parameters": {"lamella.width_m": [0.1, 0.2]}})";
  try {
    expandSweep({d / "in" / "sweep.json", d / "out\n#SBATCH --x", "/bin/egg", false});
    FAIL() << "a newline in --out was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--out"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(d / "out\n#SBATCH --x"));
  fs::create_directories(d / "mine" / "scenes");
  std::ofstream(d / "mine" / "scenes" / "base.json") << "{}";
  EXPECT_THROW(expandSweep({d / "in" / "sweep.json", d / "mine", "/bin/egg", true}), InvalidInput);
  EXPECT_TRUE(fs::exists(d / "mine" / "scenes" / "base.json"));
  EXPECT_FALSE(fs::exists(d / "mine" / "jobs.txt"));
  // An earlier sweep's own scenes are replaced.
  expandSweep({d / "in" / "sweep.json", d / "out", "/bin/egg", false});
  expandSweep({d / "in" / "sweep.json", d / "out", "/bin/egg", true});
  EXPECT_TRUE(fs::exists(d / "out" / "scenes" / "v002.json"));
  fs::remove_all(d);
}

TEST(Sweep, KeyNotInBaseSceneIsNamedAndNothingWritten) {
  const fs::path d = freshDir("badkey");
  writeBase(d);
  std::ofstream(d / "in" / "sweep.json")
      << R"({"base": "base.json", "parameters": {"lamella.width_m": [0.1], "lamella.widht_m": [0.2]}})";
  try {
    expandSweep({d / "in" / "sweep.json", d / "out", "/bin/egg", false});
    FAIL() << "a misspelt key was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("lamella.widht_m"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sweep.json"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(d / "out"));
  // A value the scene rejects is an error too, before anything is written.
  std::ofstream(d / "in" / "sweep.json")
      << R"({"base": "base.json", "parameters": {"lamella.width_m": [0.1, -1]}})";
  EXPECT_THROW(expandSweep({d / "in" / "sweep.json", d / "out", "/bin/egg", false}), InvalidInput);
  EXPECT_FALSE(fs::exists(d / "out"));
  for (const auto& entry : fs::directory_iterator(d))
    EXPECT_EQ(entry.path().filename().string().rfind(".egg-tmp", 0), std::string::npos);
  fs::remove_all(d);
}

TEST(Sweep, ShellQuote) {
  EXPECT_EQ(shellQuote("a b"), "'a b'");
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
}

}  // namespace
}  // namespace egg::app
