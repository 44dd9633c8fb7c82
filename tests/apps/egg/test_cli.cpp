// Drives the `egg` program through runCli, as a user would from the shell: exit codes,
// messages, and the promise that bad input leaves no partial output folder.
#include "apps/egg/commands.hpp"
#include "core/io/child_process.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace egg::app {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int code;
  std::string out;
  std::string err;
};

Outcome runEgg(std::vector<std::string> args) {
  args.insert(args.begin(), "egg");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = runCli(static_cast<int>(argv.size()), argv.data());
  Outcome o{code, testing::internal::GetCapturedStdout(), testing::internal::GetCapturedStderr()};
  return o;
}

// Standard output on a full device: the run fails and says so (a script would read nothing).
TEST(CliOutput, AFullStandardOutputIsAFailureNotSuccess) {
  const fs::path log = fs::temp_directory_path() / ("egg_cli_full_" + std::to_string(::getpid()));
  const ChildOutcome o = runChild(
      [] {
        if (!std::freopen("/dev/full", "w", stdout)) return 99;
        std::string a = "egg", b = "scene-reference";
        char* argv[] = {a.data(), b.data()};
        return runCli(2, argv);
      },
      60.0, log);
  fs::remove(log);
  EXPECT_EQ(o.exitCode, kExitFailure) << o.output;
  EXPECT_NE(o.output.find("cannot write to standard output"), std::string::npos) << o.output;
}

// A file-size limit (ulimit -f) below the report's size: the write fails with EFBIG and the run
// says which file, instead of dying by SIGXFSZ without a word and leaving its staging folder.
TEST(CliOutput, AFileSizeLimitIsANamedWriteFailureNotASignal) {
  const fs::path dir = fs::temp_directory_path() / ("egg_cli_fsize_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "run", log = dir / "log";
  const std::string scene =
      (fs::path(EGG_SOURCE_DIR) / "samples" / "scenes" / "bump_patch.json").string();
  const ChildOutcome o = runChild(
      [&] {
        const rlimit limit{256 * 1024, 256 * 1024};  // bytes: report.html is megabytes
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return 99;
        std::string a = "egg", b = "run", c = scene, d = "--out", e = out.string(), f = "-q";
        char* argv[] = {a.data(), b.data(), c.data(), d.data(), e.data(), f.data()};
        return runCli(6, argv);
      },
      120.0, log);
  EXPECT_EQ(o.signal, 0) << o.output;
  EXPECT_EQ(o.exitCode, kExitFailure) << o.output;
  EXPECT_NE(o.output.find("cannot write output"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("File too large"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(out)) << "a failed run leaves no run folder";
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_TRUE(entry.path() == log) << "left behind: " << entry.path();
  fs::remove_all(dir);
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() / ("egg_cli_test_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
  }
  void TearDown() override { fs::remove_all(root); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(root / name) << text;
    return root / name;
  }
  fs::path root;
};

TEST_F(Cli, HelpAndVersionExitZero) {
  EXPECT_EQ(runEgg({"--help"}).code, kExitOk);
  EXPECT_EQ(runEgg({"run", "--help"}).code, kExitOk);
  EXPECT_EQ(runEgg({"--version"}).code, kExitOk);
}

TEST_F(Cli, UnknownSubcommandOrOptionIsBadInput) {
  EXPECT_EQ(runEgg({"frobnicate"}).code, kExitBadInput);
  EXPECT_EQ(runEgg({"surface", "plane", "--no-such-flag"}).code, kExitBadInput);
}

TEST_F(Cli, MissingSceneIsBadInputAndWritesNothing) {
  const auto o =
      runEgg({"run", (root / "nope.json").string(), "--out", (root / "out").string(), "--quiet"});
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_NE(o.err.find("nope.json"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(root / "out"));
}

// Issue 40: a one-triangle mesh made Workflow 2 say "patch 0: corner 1 appears twice", its own
// internals (and read past an arc of one point, found under ASan); the message names what the
// user can change.
TEST_F(Cli, ASurfaceTooCoarseForWorkflow2SaysWhatToChange) {
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const fs::path scene =
      write("tri.json", R"({"surface": {"file": "tri.obj"}, "outputs": ["report"]})");
  const auto o = runEgg({"run", scene.string(), "--out", (root / "out").string(), "--quiet"});
  EXPECT_EQ(o.code, kExitBadInput) << o.err;
  EXPECT_NE(o.err.find("outline has only 3 vertices"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("surface.edge_length_m"), std::string::npos) << o.err;
  EXPECT_EQ(o.err.find("corner 1"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(root / "out"));
}

// `egg run` without a scene works from any folder: the default sample is found beside the program.
TEST_F(Cli, TheDefaultSceneIsFoundFromAnyFolder) {
  const fs::path before = fs::current_path();
  fs::current_path(root);
  const std::string scene = defaultRunScene();
  fs::current_path(before);
  EXPECT_TRUE(fs::path(scene).is_absolute()) << scene;
  EXPECT_TRUE(fs::exists(scene)) << scene;
  EXPECT_EQ(fs::path(scene).filename(), "great_court.json");
}

// A script that asked for --json parses the failure from stdout: kind, message, exit code.
TEST_F(Cli, WithJsonAFailureIsAJsonObjectOnStdout) {
  const auto o = runEgg(
      {"run", (root / "nope.json").string(), "--out", (root / "out").string(), "--json", "-q"});
  EXPECT_EQ(o.code, kExitBadInput);
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["error"]["kind"], "io_error");
  EXPECT_EQ(j["error"]["exit_code"], kExitBadInput);
  EXPECT_NE(j["error"]["message"].get<std::string>().find("nope.json"), std::string::npos);
  EXPECT_NE(o.err.find("nope.json"), std::string::npos) << o.err;
  EXPECT_EQ(j["error"]["file"], (root / "nope.json").string());
  EXPECT_TRUE(j["error"]["field"].is_null());
}

// Issue 39: a script learns the file and the key at fault without parsing the message.
TEST_F(Cli, WithJsonABadSceneKeyNamesItsFileAndField) {
  const auto scene =
      write("bad.json", R"({"surface": {"sample": "plane"}, "lamella": {"width_m": -1}})");
  const auto o = runEgg({"run", scene.string(), "--out", (root / "out").string(), "--json", "-q"});
  EXPECT_EQ(o.code, kExitBadInput);
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["error"]["kind"], "invalid_input");
  EXPECT_EQ(j["error"]["file"], scene.string());
  EXPECT_EQ(j["error"]["field"], "lamella.width_m");
  const auto syntax =
      write("syntax.json", R"({"surface": {"sample": "plane", "edge_length_m": }})");
  const auto s = runEgg({"run", syntax.string(), "--json", "-q"});
  const auto k = nlohmann::json::parse(s.out);
  EXPECT_EQ(k["error"]["file"], syntax.string());
  EXPECT_EQ(k["error"]["field"], "surface.edge_length_m");
  EXPECT_FALSE(fs::exists(root / "out"));
}

// Issue 39: `egg init` writes a scene that `egg run` takes as it is, and never replaces a file.
TEST_F(Cli, InitWritesAStartingSceneThatRunsAsItIs) {
  const auto scene = root / "start" / "bump.json";
  fs::create_directories(scene.parent_path());
  const auto init = runEgg({"init", "bump", "--out", scene.string()});
  ASSERT_EQ(init.code, kExitOk) << init.err;
  EXPECT_NE(init.err.find("run it with: egg run " + scene.string()), std::string::npos) << init.err;
  const auto text = nlohmann::json::parse(std::ifstream(scene));
  EXPECT_TRUE(text.contains("$comment"));
  const auto run = runEgg({"run", scene.string(), "--out", (root / "out").string(), "-q"});
  EXPECT_EQ(run.code, kExitOk) << run.out << run.err;
  EXPECT_TRUE(fs::exists(root / "out" / "report.json"));

  // An existing file is kept unless --force.
  std::ofstream(root / "mine.json") << "my notes";
  const auto again = runEgg({"init", "bump", "--out", (root / "mine.json").string()});
  EXPECT_EQ(again.code, kExitBadInput);
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
  std::ifstream mine(root / "mine.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(mine), {}), "my notes");
  EXPECT_EQ(runEgg({"init", "bump", "--out", (root / "mine.json").string(), "--force"}).code,
            kExitOk);
  // Without --out it prints the scene; the schema prints as JSON too.
  const auto printed = runEgg({"init", "plane"});
  EXPECT_EQ(nlohmann::json::parse(printed.out)["surface"]["sample"], "plane");
  const auto schema = runEgg({"scene-schema"});
  EXPECT_EQ(nlohmann::json::parse(schema.out)["title"], "eggshell scene");
}

TEST_F(Cli, BrokenSceneIsBadInputNamingTheFieldAndWritesNothing) {
  const auto scene =
      write("typo.json", R"({"surface": {"sample": "plane"}, "grid": {"alpha": "min"}})");
  const auto o = runEgg({"run", scene.string(), "--out", (root / "out").string(), "--quiet"});
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_NE(o.err.find("grid.alpha"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(root / "out"));
}

TEST_F(Cli, BadMeshFileIsBadInputNamingTheFile) {
  write("garbage.obj", "this is not a mesh\n");
  const auto scene = write("bad_mesh.json", R"({"surface": {"file": "garbage.obj"}})");
  const auto o = runEgg({"run", scene.string(), "--out", (root / "out").string(), "--quiet"});
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_NE(o.err.find("garbage.obj"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(root / "out"));
}

TEST_F(Cli, UnknownSampleIsBadInput) {
  const auto o = runEgg({"surface", "no_such_sample", "--stats"});
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_NE(o.err.find("no_such_sample"), std::string::npos) << o.err;
}

TEST_F(Cli, SurfaceStatsOfAPlaneAreExact) {
  const auto o = runEgg({"surface", "plane", "--stats", "--json", "--edge-length", "1.0"});
  ASSERT_EQ(o.code, kExitOk) << o.err;
  const auto stats = nlohmann::json::parse(o.out);
  const auto& defaults = stats["bbox_m"];
  EXPECT_NEAR(stats["area_m2"].get<double>(), defaults[0].get<double>() * defaults[1].get<double>(),
              1e-9);
  EXPECT_NEAR(defaults[2].get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(stats["validation"]["ok"].get<bool>());
  EXPECT_EQ(stats["components"], 1);
}

TEST_F(Cli, SurfaceExportRoundTripsThroughAFile) {
  const auto path = root / "plane.obj";
  ASSERT_EQ(runEgg({"surface", "plane", "--edge-length", "2.0", "--export", path.string()}).code,
            kExitOk);
  const auto a = nlohmann::json::parse(
      runEgg({"surface", "plane", "--edge-length", "2.0", "--stats", "--json"}).out);
  const auto b = nlohmann::json::parse(runEgg({"surface", path.string(), "--stats", "--json"}).out);
  EXPECT_EQ(a["faces"], b["faces"]);
  EXPECT_EQ(a["vertices"], b["vertices"]);
  EXPECT_NEAR(a["area_m2"].get<double>(), b["area_m2"].get<double>(), 1e-6);
}

TEST_F(Cli, RunWritesACompleteReport) {
  const auto scene = write(
      "small.json",
      R"({"name": "small", "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5}, "edge_length_m": 0.5},
                                             "patching": {"patches": [[[-3, -3, 0], [3, -3, 0], [3, 3, 0], [-3, 3, 0]]]},
                                             "grid": {"map_resolution": 20, "members_per_family": 4},
                                             "simulation": {"enabled": false}, "outputs": ["report"]})");
  const auto out = root / "run";
  const auto o = runEgg({"run", scene.string(), "--out", out.string(), "--quiet"});
  ASSERT_EQ(o.code, kExitOk) << o.err;
  std::ifstream in(out / "report.json");
  ASSERT_TRUE(in.good());
  const auto report = nlohmann::json::parse(in);
  for (const char* key : {"scene", "units", "surface", "stages", "patches", "coverage",
                          "propagation", "simulation", "fabrication", "timings"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_EQ(report["scene"]["name"], "small");
  EXPECT_TRUE(report["stages"]["surface"]["ran"].get<bool>());
  EXPECT_GT(report["surface"]["faces"].get<int>(), 0);
  EXPECT_FALSE(report["simulation"]["ran"].get<bool>());
}

// Issue 36: a 20 m birch dome (4.4 m rise) cut from 200 x 8 mm lamellas cannot carry its own
// weight. The run completes, but ends with exit 1 and says so on the terminal, naming each missed
// criterion with its value and limit; at 20 mm the same dome stands and passes.
TEST_F(Cli, ACollapsingDomeEndsWithExit1AndNamesTheCriteria) {
  auto dome = [&](const std::string& name, double thicknessM) {
    return write(name + ".json", R"({"name": ")" + name + R"(",
      "surface": {"sample": "sphere", "params": {"radius": 13.56, "extent": 10}, "edge_length_m": 0.5},
      "patching": {"workflow": 2, "max_patch_size_m": 25},
      "grid": {"members_per_family": "auto", "map_resolution": 100},
      "lamella": {"width_m": 0.2, "thickness_m": )" +
                                     std::to_string(thicknessM) +
                                     R"(, "material": "birch_plywood"},
      "simulation": {"enabled": true, "gravity": true}, "fabrication": {"enabled": false},
      "outputs": ["report"]})");
  };
  const auto collapsed =
      runEgg({"run", dome("thin", 0.008).string(), "--out", (root / "thin").string(), "--quiet"});
  ASSERT_EQ(collapsed.code, kExitFailure) << collapsed.out << collapsed.err;
  EXPECT_NE(collapsed.out.find("max_sag"), std::string::npos) << collapsed.out;
  EXPECT_NE(collapsed.out.find("FAILED"), std::string::npos) << collapsed.out;
  EXPECT_EQ(collapsed.out.find("passed"), std::string::npos) << collapsed.out;
  std::ifstream in(root / "thin" / "report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_FALSE(report["acceptance"]["passed"].get<bool>());
  bool named = false;
  for (const auto& failure : report["failures"])
    named |= failure.get<std::string>().find("patch_by_patch_max_error") != std::string::npos;
  EXPECT_TRUE(named) << report["failures"].dump();
  const auto standing =
      runEgg({"run", dome("thick", 0.02).string(), "--out", (root / "thick").string(), "--quiet"});
  EXPECT_EQ(standing.code, kExitOk) << standing.out << standing.err;
  EXPECT_NE(standing.out.find("passed"), std::string::npos) << standing.out;
}

}  // namespace
}  // namespace egg::app

namespace egg::app {
namespace {

// On a flat convex sheet the geodesic distance is the straight-line distance: `egg geodesic`
// must write exactly that for every vertex.
TEST_F(Cli, GeodesicCommandWritesEuclideanDistancesOnAPlane) {
  const auto csv = root / "d.csv";
  const auto o = runEgg({"geodesic", "plane", "--source", "0.3,-0.2,0", "--out", csv.string()});
  ASSERT_EQ(o.code, kExitOk) << o.err;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z,distance");
  int rows = 0;
  double worst = 0.0;
  while (std::getline(in, line)) {
    double x, y, z, d;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &z, &d), 4) << line;
    worst = std::max(worst, std::abs(d - std::hypot(x - 0.3, y + 0.2, z)));
    ++rows;
  }
  EXPECT_GT(rows, 100);
  EXPECT_LT(worst, 1e-9);
}

TEST_F(Cli, GeodesicCommandRejectsABadSourceWithoutWriting) {
  const auto csv = root / "d.csv";
  const auto o = runEgg({"geodesic", "plane", "--source", "1,2", "--out", csv.string()});
  EXPECT_EQ(o.code, kExitBadInput);
  EXPECT_NE(o.err.find("--source"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(csv));
  // A tolerance out of range names the option the user gave, not the solver's field.
  for (const char* bad : {"5", "-1", "0.001"}) {
    const auto t = runEgg({"geodesic", "plane", "--source", "0,0,0", "--merge-tolerance", bad,
                           "--out", csv.string()});
    EXPECT_EQ(t.code, kExitBadInput) << bad;
    EXPECT_NE(t.err.find(std::string("--merge-tolerance ") + bad), std::string::npos) << t.err;
    EXPECT_EQ(t.err.find("DistanceSolverOptions"), std::string::npos) << t.err;
    EXPECT_FALSE(fs::exists(csv));
  }
}

// --exact and --merge-tolerance reach the solver: on the sphere cap sample merging near images
// makes fewer windows than --merge-tolerance 0, which gives --exact's distances (the cap has no
// saddles to skip); a tolerance out of range is bad input naming the option, with nothing written.
TEST_F(Cli, GeodesicCommandTakesTheExactModeAndTheMergeTolerance) {
  auto run = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args{
        "geodesic", "sphere", "--source", "1,2,9.7", "--out", (root / name).string(), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto o = runEgg(args);
    EXPECT_EQ(o.code, kExitOk) << o.err;
    return nlohmann::json::parse(o.out);
  };
  const auto merged = run("merged.csv", {});
  const auto unmerged = run("unmerged.csv", {"--merge-tolerance", "0"});
  const auto exact = run("exact.csv", {"--exact"});
  EXPECT_LT(merged["windows"].get<long>(), unmerged["windows"].get<long>());
  EXPECT_EQ(unmerged["windows"], exact["windows"]);
  std::ifstream a(root / "unmerged.csv"), b(root / "exact.csv");
  const std::string textA((std::istreambuf_iterator<char>(a)), {}),
      textB((std::istreambuf_iterator<char>(b)), {});
  EXPECT_EQ(textA, textB);
  const auto csv = root / "bad.csv";
  const auto bad = runEgg({"geodesic", "sphere", "--source", "1,2,9.7", "--out", csv.string(),
                           "--merge-tolerance", "-1"});
  EXPECT_EQ(bad.code, kExitBadInput);
  EXPECT_NE(bad.err.find("--merge-tolerance -1"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(csv));
}

}  // namespace
}  // namespace egg::app

namespace egg::app {
namespace {

// Inputs fine, output impossible: a failure of the run (exit 1), not bad input (exit 2); the
// message names the file and nothing is left behind.
TEST_F(Cli, UnwritableOutputIsAFailureNamingTheFile) {
  const auto csv = root / "no_such_folder" / "d.csv";
  const auto o = runEgg({"geodesic", "plane", "--source", "0,0,0", "--out", csv.string()});
  EXPECT_EQ(o.code, kExitFailure);
  EXPECT_NE(o.err.find(csv.string()), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(root / "no_such_folder"));
  const auto obj = root / "missing" / "plane.obj";
  const auto e = runEgg({"surface", "plane", "--edge-length", "2.0", "--export", obj.string()});
  EXPECT_EQ(e.code, kExitFailure);
  EXPECT_NE(e.err.find("plane.obj"), std::string::npos) << e.err;
}

TEST_F(Cli, GeodesicBenchTabulatesErrorAgainstTimeOverTheSaddleTolerance) {
  // The exact mode is the reference of its own run (error 0); the default stays inside the 1e-4
  // bar.
  const Outcome o = runEgg({"bench", "geodesic", "--sizes", "400", "--cgal-sources", "0",
                            "--sources", "8", "--timed-sources", "3", "--saddle-tolerance",
                            "0,7e-4", "--engine-rows", "none", "--json"});
  ASSERT_EQ(o.code, 0) << o.err;
  // With --json, stdout is the JSON document alone (issue 17: the table went first); the table is
  // on stderr.
  ASSERT_TRUE(nlohmann::json::accept(o.out)) << o.out;
  EXPECT_NE(o.err.find("vertices"), std::string::npos) << o.err;
  const auto table = nlohmann::json::parse(o.out)["saddle_tolerance"];
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(table[0]["max_relative_error_vertices"].get<double>(), 0.0);
  EXPECT_EQ(table[0]["max_relative_error_side_to_side"].get<double>(), 0.0);
  EXPECT_LT(table[1]["max_relative_error_vertices"].get<double>(), 1e-4);
  EXPECT_LT(table[1]["max_relative_error_side_to_side"].get<double>(), 1e-4);
  EXPECT_GT(table[0]["windows_per_source"].get<double>(), 0.0);
  const Outcome bad = runEgg({"bench", "geodesic", "--saddle-tolerance", "-1"});
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("--saddle-tolerance"), std::string::npos) << bad.err;
}

TEST_F(Cli, GridBenchTabulatesErrorAgainstTimeOfMapsOnAProxy) {
  // Rows: the exact maps on the patch (the reference, error 0), --map-proxy 0 (the adaptive maps on
  // the patch), and a 300-vertex proxy: fewer fields, a map error above zero and below the bound.
  const Outcome o = runEgg({"bench", "grid", "--sizes", "1100", "--repeats", "1", "--resolution",
                            "31", "--map-proxy", "0,300", "--json"});
  ASSERT_EQ(o.code, 0) << o.err;
  // With --json, stdout is the JSON document alone (issue 17: the table went first); the table is
  // on stderr.
  ASSERT_TRUE(nlohmann::json::accept(o.out)) << o.out;
  EXPECT_NE(o.err.find("vertices"), std::string::npos) << o.err;
  const auto table = nlohmann::json::parse(o.out)["map_tolerance"];
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[0]["max_map_error_m"].get<double>(), 0.0);
  EXPECT_EQ(table[0]["proxy_vertices"].get<int>(), 0);
  EXPECT_EQ(table[1]["proxy_vertices"].get<int>(), 0);
  EXPECT_EQ(table[1]["proxy_vertices_option"].get<int>(), 0);
  EXPECT_LT(table[1]["max_map_error_m"].get<double>(), 1e-3);
  EXPECT_EQ(table[2]["proxy_vertices_option"].get<int>(), 300);
  EXPECT_GT(table[2]["proxy_vertices"].get<int>(), 250);
  EXPECT_LE(table[2]["proxy_vertices"].get<int>(), 300);
  EXPECT_GT(table[2]["max_map_error_m"].get<double>(), 1e-5);
  EXPECT_LT(table[2]["max_map_error_m"].get<double>(), 3.5e-3);  // 2.4e-3 measured
  EXPECT_LT(table[2]["map_fields"].get<int>(), table[0]["map_fields"].get<int>());
  EXPECT_TRUE(table[2]["member_counts_equal"].get<bool>());
  const Outcome bad = runEgg({"bench", "grid", "--map-proxy", "-5"});
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("--map-proxy"), std::string::npos) << bad.err;
}

TEST_F(Cli, PatchingBenchDecomposesTheGreatCourtUnattended) {
  // Workflow 2 on the default scene: four patches round the Reading Room (the paper's hand layout
  // had four), every one feasible, the hole's tangent box as the only cut-off.
  const auto scene =
      (std::filesystem::path(EGG_SOURCE_DIR) / "samples" / "great_court.json").string();
  const auto o = runEgg({"bench", "patching", "--samples", scene, "--json"});
  ASSERT_EQ(o.code, kExitOk) << o.err;
  const auto rows = nlohmann::json::parse(o.out);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0]["patches"], 4);
  EXPECT_EQ(rows[0]["feasible"], 4);
  EXPECT_GE(rows[0]["coverage"].get<double>(), 0.90);  // issue 14: hole and boundary cut-offs only
  EXPECT_LT(rows[0]["coverage"].get<double>(), 1.0);
}

}  // namespace
}  // namespace egg::app

namespace egg::app {
namespace {

// Issue 17: NaN passed CLI11's range checks; absurd --threads aborted (std::terminate); absurd
// sizes ran for minutes, grew past 12 GB or silently benchmarked something else (int overflow).
TEST_F(Cli, AbsurdOrNanFlagsAreBadInputBeforeAnyWork) {
  const std::vector<std::vector<std::string>> cases{
      {"bench", "sim", "--tolerances", "nan"},
      {"bench", "sim", "--notch-fraction", "nan"},
      {"bench", "sim", "--spacings", "0.001"},
      {"bench", "sim", "--threads", "100000"},
      {"bench", "sim", "--joined", "lilium", "--thread-counts", "0"},
      {"bench", "grid", "--height", "nan"},
      {"bench", "grid", "--sizes", "2000000000"},
      {"bench", "grid", "--map-tolerance", "nan"},
      {"bench", "geodesic", "--threads", "1000000000"},
      {"bench", "geodesic", "--sources", "2000000000"},
      {"bench", "geodesic", "--sizes", "2000000000"},
      {"bench", "geodesic", "--saddle-tolerance", "nan"},
      {"stress", "--time-limit", "nan"},
      {"surface", "plane", "--edge-length", "nan"},
      {"run", "--threads", "100000"},
  };
  for (const auto& args : cases) {
    const auto start = std::chrono::steady_clock::now();
    const Outcome o = runEgg(args);
    EXPECT_EQ(o.code, kExitBadInput)
        << args[args.size() - 2] << " " << args.back() << ": " << o.err;
    EXPECT_NE(o.err.find(args[args.size() - 2]), std::string::npos) << o.err;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  }
}

// Issue 17: `geodesic --out` onto a character device replaced the device node with a file.
TEST_F(Cli, AnOutputOntoADeviceIsRefused) {
  const Outcome o = runEgg({"geodesic", "plane", "--source", "0,0,0", "--out", "/dev/null"});
  EXPECT_EQ(o.code, kExitFailure) << o.err;
  EXPECT_NE(o.err.find("character device"), std::string::npos) << o.err;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// Issue 40: `--out ""` wrote to ./out/<name>, and --out below a regular file was exit 1 (a write
// failure) though it is the user's path that cannot be.
TEST_F(Cli, AnEmptyOutOrOneBelowAFileIsBadInputBeforeAnyWork) {
  const auto scene = write("s.json", R"({"surface": {"sample": "bump"}, "outputs": ["report"]})");
  const Outcome empty = runEgg({"run", scene.string(), "--out", "", "--quiet"});
  EXPECT_EQ(empty.code, kExitBadInput) << empty.err;
  EXPECT_NE(empty.err.find("--out: an empty path"), std::string::npos) << empty.err;
  const auto file = write("plain.txt", "the user's");
  const Outcome below =
      runEgg({"run", scene.string(), "--out", (file / "run").string(), "--quiet"});
  EXPECT_EQ(below.code, kExitBadInput) << below.err;
  EXPECT_NE(below.err.find("is not a folder"), std::string::npos) << below.err;
  EXPECT_TRUE(fs::is_regular_file(file));
}

// Issue 17: a folder as the scene and 1e400 in a field were "internal error", exit 1.
TEST_F(Cli, AFolderAsSceneAndAnOverflowingNumberAreBadInputNamingTheField) {
  fs::create_directories(root / "dir.json");
  const Outcome dir = runEgg({"run", (root / "dir.json").string(), "--quiet"});
  EXPECT_EQ(dir.code, kExitBadInput) << dir.err;
  EXPECT_EQ(dir.err.find("internal error"), std::string::npos) << dir.err;
  const auto scene =
      write("big.json", R"({"surface": {"sample": "bump"}, "lamella": {"width_m": 1e400}})");
  const Outcome big = runEgg({"run", scene.string(), "--out", (root / "out").string(), "--quiet"});
  EXPECT_EQ(big.code, kExitBadInput) << big.err;
  EXPECT_NE(big.err.find("lamella.width_m"), std::string::npos) << big.err;
  EXPECT_FALSE(fs::exists(root / "out"));
}

// Issue 17: `egg run run/scene.json --out run` onto an earlier run deleted the run's own scene.
TEST_F(Cli, ARunNeverReplacesAFolderHoldingTheUsersFiles) {
  const std::string text =
      R"({"name": "small", "surface": {"sample": "bump", "params": {"length": 8, "width": 8, "height": 1, "sigma": 1.5}, "edge_length_m": 0.5},
                               "patching": {"patches": [[[-3, -3, 0], [3, -3, 0], [3, 3, 0], [-3, 3, 0]]]},
                               "grid": {"map_resolution": 20, "members_per_family": 4},
                               "simulation": {"enabled": false}, "outputs": ["report"]})";
  const auto first = write("small.json", text);
  const auto out = root / "run";
  ASSERT_EQ(runEgg({"run", first.string(), "--out", out.string(), "--quiet"}).code, kExitOk);
  ASSERT_EQ(runEgg({"run", first.string(), "--out", out.string(), "--quiet"}).code, kExitOk)
      << "a pure run is replaced";
  std::ofstream(out / "scene.json") << text;
  std::ofstream(out / "notes.txt") << "mine";
  const Outcome o =
      runEgg({"run", (out / "scene.json").string(), "--out", out.string(), "--quiet"});
  EXPECT_EQ(o.code, kExitBadInput) << o.err;
  EXPECT_NE(o.err.find("did not write"), std::string::npos) << o.err;
  EXPECT_TRUE(fs::exists(out / "scene.json"));
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::exists(out / "report.json"));
}

}  // namespace
}  // namespace egg::app
