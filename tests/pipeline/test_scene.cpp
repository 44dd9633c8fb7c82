#include "pipeline/scene.hpp"
#include "pipeline/scene_fields.hpp"

#include "core/egg/members.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"
#include "core/rods/rod_solver.hpp"
#include "core/rods/simulation.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>

#include <sys/stat.h>
#include <unistd.h>

namespace egg::pipeline {
namespace {

using nlohmann::json;

Scene parse(const std::string& text) { return parseScene(json::parse(text), "/scenes/test.json"); }

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, DefaultsFillEverythingButTheSurface) {
  const Scene s = parse(R"({"surface": {"sample": "bump"}})");
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.surface.sample, "bump");
  EXPECT_DOUBLE_EQ(s.surface.edgeLengthM,
                   defaultSampleEdgeLength("bump"));  // sized to the sample, not 1 m
  EXPECT_LT(defaultSampleEdgeLength("bump"), 0.5);
  EXPECT_DOUBLE_EQ(s.design().uniqueness.etaMax, 1.0015);
  EXPECT_DOUBLE_EQ(s.design().alphaBar.slopeMin, 0.1);
  EXPECT_DOUBLE_EQ(s.design().alphaBar.slopeMax, 10.0);
  EXPECT_EQ(s.design().maps.resolution, 100);
  EXPECT_DOUBLE_EQ(s.design().maps.toleranceRelative, egg::DistanceMapOptions{}.toleranceRelative);
  EXPECT_EQ(s.design().maps.proxyVertices, egg::DistanceMapOptions{}.proxyVertices);
  EXPECT_EQ(s.design().alphaBar.choice, AlphaBarChoice::Min);
  EXPECT_EQ(s.design().members.count, 0);  // auto
  EXPECT_DOUBLE_EQ(s.lamella.widthM, 0.25);
  EXPECT_DOUBLE_EQ(s.simulation.rods.model.frictionMu, 0.1);
  EXPECT_TRUE(s.simulation.joinPatches);
  EXPECT_FALSE(s.simulation.rods.compareWithoutNotches);  // a second full run only when asked for
  EXPECT_TRUE(s.simulation.holdSharedSides);
  EXPECT_TRUE(s.simulation.rods.fastenBoltsUnderLoad);  // the scene's bolts are tightened before
                                                        // loading; the rod library's are loose
  EXPECT_FALSE(egg::rods::SimulationOptions{}.fastenBoltsUnderLoad);
  EXPECT_DOUBLE_EQ(s.design().members.spacingFactor, egg::MemberOptions{}.spacingFactor);
  EXPECT_DOUBLE_EQ(s.simulation.rods.solver.tolerance, egg::rods::SolverOptions{}.tolerance);
  EXPECT_DOUBLE_EQ(s.simulation.rods.solver.timeLimitS, egg::rods::SolverOptions{}.timeLimitS);
  EXPECT_EQ(s.simulation.rods.solver.maxIterations, egg::rods::SolverOptions{}.maxIterations);
  EXPECT_TRUE(s.wants("cut_files"));
}

TEST(Scene, ReadsEveryDocumentedKey) {
  const Scene s = parse(R"({
    "name": "court",
    "surface": {"sample": "great_court", "params": {"holes": true, "height": 2.5}, "edge_length_m": 0.5},
    "patching": {"workflow": 1, "eta_max": 1.002, "slope_bounds": [0.2, 5], "max_patch_size_m": 30,
                 "patches": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]},
    "grid": {"members_per_family": 12, "map_resolution": 64, "map_tolerance_relative": 0.002, "alpha_bar": 1.2,
             "min_planar_angle_rad": 0.3, "map_proxy_vertices": 450, "member_spacing_factor": 11},
    "lamella": {"width_m": 0.5, "thickness_m": 0.05, "material": "birch_plywood"},
    "simulation": {"enabled": false, "gravity": false, "friction_mu": 0.3, "notches": false, "join_patches": false,
                   "compare_without_notches": true, "hold_shared_sides": false, "newton_tolerance": 1e-6,
                   "time_limit_s": 30, "max_newton_iterations": 40},
    "fabrication": {"enabled": false, "sheet_mm": [3000, 1500], "bolt_diameter_mm": 10, "kerf_mm": 0.3,
                    "margin_mm": 12, "min_notch_mm": 2, "stock_length_mm": 5000, "end_overhang_mm": 40,
                    "splice_clearance_mm": 300, "label_height_mm": 12, "sticker_margin_mm": 3,
                    "sticker_sheet_mm": [600, 400], "ground_height_m": -0.5, "support_block_mm": 200,
                    "supports_at_boundary_connections": true},
    "outputs": ["report"]})");
  EXPECT_EQ(s.name, "court");
  EXPECT_DOUBLE_EQ(s.surface.params.at("holes"), 1.0);
  EXPECT_DOUBLE_EQ(s.surface.edgeLengthM, 0.5);
  EXPECT_EQ(s.patching.workflow, 1);
  ASSERT_EQ(s.patching.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(s.patching.patches[0][2].y(), 1.0);
  EXPECT_EQ(s.design().members.count, 12);
  EXPECT_EQ(s.design().alphaBar.choice, AlphaBarChoice::Given);
  EXPECT_DOUBLE_EQ(s.design().alphaBar.givenAlphaBar, 1.2);
  EXPECT_DOUBLE_EQ(s.design().alphaBar.minPlanarAngle, 0.3);
  EXPECT_DOUBLE_EQ(s.design().maps.toleranceRelative, 0.002);
  EXPECT_EQ(s.design().maps.proxyVertices, 450);
  EXPECT_EQ(s.lamella.material, "birch_plywood");
  EXPECT_FALSE(s.simulation.enabled);
  EXPECT_FALSE(s.simulation.joinPatches);
  EXPECT_TRUE(s.simulation.rods.compareWithoutNotches);
  EXPECT_FALSE(s.simulation.holdSharedSides);
  EXPECT_DOUBLE_EQ(s.fabrication.options.sheetMm[1], 1500.0);
  EXPECT_DOUBLE_EQ(s.fabrication.options.kerfMm, 0.3);
  EXPECT_DOUBLE_EQ(s.fabrication.options.marginMm, 12.0);
  EXPECT_DOUBLE_EQ(s.fabrication.options.minNotchMm, 2.0);
  EXPECT_DOUBLE_EQ(s.fabrication.options.stockLengthMm, 5000.0);
  EXPECT_DOUBLE_EQ(*s.fabrication.options.endOverhangMm, 40.0);
  EXPECT_DOUBLE_EQ(*s.fabrication.options.spliceClearanceMm, 300.0);
  EXPECT_DOUBLE_EQ(*s.fabrication.options.labelHeightMm, 12.0);
  EXPECT_DOUBLE_EQ(s.fabrication.options.stickerMarginMm, 3.0);
  EXPECT_DOUBLE_EQ((*s.fabrication.options.stickerSheetMm)[0], 600.0);
  EXPECT_DOUBLE_EQ(*s.fabrication.options.groundHeightM, -0.5);
  EXPECT_DOUBLE_EQ(*s.fabrication.options.supportBlockMm, 200.0);
  EXPECT_TRUE(s.fabrication.options.supportsAtBoundaryConnections);
  EXPECT_FALSE(s.wants("cut_files"));
  // And it survives a round trip through the report echo.
  const Scene back = parseScene(
      [&] {
        json j = sceneToJson(s);
        j.erase("path");
        return j;
      }(),
      "/scenes/test.json");
  EXPECT_EQ(back.design().alphaBar.givenAlphaBar, 1.2);
  EXPECT_DOUBLE_EQ(back.design().maps.toleranceRelative, 0.002);
  EXPECT_EQ(back.design().maps.proxyVertices, 450);
  EXPECT_DOUBLE_EQ(back.design().members.spacingFactor, 11.0);
  EXPECT_DOUBLE_EQ(back.simulation.rods.solver.tolerance, 1e-6);
  EXPECT_DOUBLE_EQ(back.simulation.rods.solver.timeLimitS, 30.0);
  EXPECT_EQ(back.simulation.rods.solver.maxIterations, 40);
  EXPECT_FALSE(back.simulation.joinPatches);
  EXPECT_TRUE(back.simulation.rods.compareWithoutNotches);
  EXPECT_FALSE(back.simulation.holdSharedSides);
  EXPECT_EQ(back.patching.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(*back.fabrication.options.endOverhangMm, 40.0);
  EXPECT_DOUBLE_EQ(back.fabrication.options.stockLengthMm, 5000.0);
  EXPECT_FALSE(
      parse(R"({"surface": {"sample": "bump"}})").fabrication.options.endOverhangMm.has_value());
}

TEST(Scene, UnknownKeysAreErrorsNamingTheField) {
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "grid": {"aplha_bar": "min"}})")
                .find("grid.aplha_bar"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "colour": 1})").find("colour"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump", "edge": 1}})").find("surface.edge"),
            std::string::npos);
}

TEST(Scene, BadValuesAreErrorsNamingTheFieldAndFile) {
  const std::string e1 = errorOf(R"({"surface": {"sample": "bump"}, "lamella": {"width_m": -1}})");
  EXPECT_NE(e1.find("lamella.width_m"), std::string::npos) << e1;
  EXPECT_NE(e1.find("test.json"), std::string::npos) << e1;
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "grid": {"alpha_bar": "smallest"}})")
                .find("grid.alpha_bar"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "grid": {"alpha_bar": 4.0}})")
                .find("grid.alpha_bar"),
            std::string::npos);
  EXPECT_NE(
      errorOf(R"({"surface": {"sample": "bump"}, "grid": {"map_tolerance_relative": -0.001}})")
          .find("grid.map_tolerance_relative"),
      std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "simulation": {"newton_tolerance": 0}})")
                .find("simulation.newton_tolerance"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "grid": {"member_spacing_factor": 1}})")
                .find("grid.member_spacing_factor"),
            std::string::npos);
  // 0 (no proxy) or at least 8 vertices (corners plus a vertex per side); integers only.
  for (const char* bad : {"5", "-1", "300.5", "\"auto\""}) {
    const std::string e =
        errorOf(std::string(R"({"surface": {"sample": "bump"}, "grid": {"map_proxy_vertices": )") +
                bad + "}}");
    EXPECT_NE(e.find("grid.map_proxy_vertices"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_EQ(parse(R"({"surface": {"sample": "bump"}, "grid": {"map_proxy_vertices": 0}})")
                .design()
                .maps.proxyVertices,
            0);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "patching": {"eta_max": 0.9}})")
                .find("patching.eta_max"),
            std::string::npos);
  // Issue 40: a label taller than the lamella was engraved off the part.
  const std::string label =
      errorOf(R"({"surface": {"sample": "bump"}, "lamella": {"width_m": 0.05}, )"
              R"("fabrication": {"label_height_mm": 60}})");
  EXPECT_NE(label.find("fabrication.label_height_mm: 60 mm is taller than the lamella (50 mm"),
            std::string::npos)
      << label;
  EXPECT_NO_THROW(parse(R"({"surface": {"sample": "bump"}, "lamella": {"width_m": 0.05}, )"
                        R"("fabrication": {"label_height_mm": 50}})"));
  // Issue 40: a patch given twice (in another corner order) or with a corner twice was accepted.
  const std::string twice =
      errorOf(R"({"surface": {"sample": "bump"}, "patching": {"workflow": 1, "patches": [)"
              R"([[0,0,0],[1,0,0],[1,1,0],[0,1,0]], [[1,0,0],[1,1,0],[0,1,0],[0,0,0]]]}})");
  EXPECT_NE(twice.find("patching.patches[1]: has the corners of patches[0]"), std::string::npos)
      << twice;
  const std::string corner =
      errorOf(R"({"surface": {"sample": "bump"}, "patching": {"workflow": 1, "corners": )"
              R"([[0,0,0],[1,0,0],[1,1,0]], "patches": [[0, 1, 2, 1]]}})");
  EXPECT_NE(corner.find("names one corner twice"), std::string::npos) << corner;
  // Issue 40: 4294967297 and -4294967295 were read as 1 (truncated to int).
  for (const char* bad : {"[4]", "[0, 2]", "[2, 17]", "[2.5, 2]", "\"4x4\"", "[4294967297, 1]",
                          "[-4294967295, 1]", "[18446744073709551615, 1]"}) {
    const std::string e = errorOf(
        std::string(R"({"surface": {"sample": "bump"}, "patching": {"block_grid": )") + bad + "}}");
    EXPECT_NE(e.find("patching.block_grid"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_EQ(parse(R"({"surface": {"sample": "bump"}, "patching": {"block_grid": [4, 3]}})")
                .patching.workflow2.blockGrid,
            (std::array<int, 2>{4, 3}));
  EXPECT_NE(
      errorOf(
          R"({"surface": {"sample": "bump"}, "patching": {"block_grid": [2, 2], "patches": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}})")
          .find("patching.block_grid"),
      std::string::npos);
  for (const char* bad :
       {R"("kerf_mm": -1)", R"("stock_length_mm": 0)", R"("margin_mm": 900)",
        R"("min_notch_mm": "1")", R"("sticker_sheet_mm": [10])", R"("end_overhang_mm": -2)"}) {
    const std::string e =
        errorOf(std::string(R"({"surface": {"sample": "bump"}, "fabrication": {)") + bad + "}}");
    EXPECT_NE(e.find("fabrication."), std::string::npos) << bad << ": " << e;
  }
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "patching": {"slope_bounds": [2, 10]}})")
                .find("slope_bounds"),
            std::string::npos);
  EXPECT_NE(
      errorOf(
          R"({"surface": {"sample": "bump"}, "patching": {"patches": [[[0,0,0],[1,0,0],[1,1,0]]]}})")
          .find("patches[0]"),
      std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "lamella": {"material": "balsa"}})")
                .find("lamella.material"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "outputs": ["report", "pdf"]})").find("pdf"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump"}, "simulation": {"gravity": "yes"}})")
                .find("simulation.gravity"),
            std::string::npos);
}

TEST(Scene, NameMustNotEscapeTheOutputFolder) {
  for (const char* name : {"..", ".", "", "../x", "a/b", ".hidden", "a\\\\b"}) {
    const std::string text =
        std::string(R"({"surface": {"sample": "bump"}, "name": ")") + name + "\"}";
    EXPECT_NE(errorOf(text).find("name"), std::string::npos) << name;
  }
  EXPECT_EQ(parse(R"({"surface": {"sample": "bump"}, "name": "court_v2"})").name, "court_v2");
}

TEST(Scene, SurfaceNeedsExactlyOneSource) {
  EXPECT_NE(errorOf(R"({"grid": {}})").find("surface"), std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {}})").find("surface"), std::string::npos);
  EXPECT_NE(errorOf(R"({"surface": {"sample": "bump", "file": "x.obj"}})").find("exactly one"),
            std::string::npos);
}

TEST(Scene, RelativeMeshFilesResolveAgainstTheSceneFolder) {
  const Scene s = parse(R"({"surface": {"file": "meshes/roof.obj", "scale_to_m": 0.001}})");
  EXPECT_EQ(s.surface.file, std::filesystem::path("/scenes/meshes/roof.obj"));
  EXPECT_DOUBLE_EQ(s.surface.scaleToM, 0.001);
}

TEST(Scene, BrokenJsonAndMissingFilesAreReported) {
  const auto dir = std::filesystem::temp_directory_path() / "egg_scene_test";
  std::filesystem::create_directories(dir);
  const auto broken = dir / "broken.json";
  std::ofstream(broken) << "{\"surface\": {\"sample\": \"bump\",}";
  try {
    loadScene(broken);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
  }
  EXPECT_THROW(loadScene(dir / "missing.json"), IoError);
  std::filesystem::remove_all(dir);
}

TEST(Scene, ShippedScenesParse) {
  const auto dir = std::filesystem::path(EGG_SOURCE_DIR) / "samples";
  int parsed = 0;
  for (const auto& path :
       {dir / "great_court.json", dir / "lilium.json", dir / "yas.json",
        dir / "scenes" / "bump_small.json", dir / "scenes" / "cylinder_small.json",
        dir / "scenes" / "sphere_small.json", dir / "scenes" / "bump_patch.json"}) {
    EXPECT_NO_THROW(loadScene(path)) << path;
    ++parsed;
  }
  EXPECT_EQ(loadScene(dir / "great_court.json").surface.sample, "great_court");
  EXPECT_DOUBLE_EQ(loadScene(dir / "great_court.json").lamella.widthM,
                   0.40);  // 40 x 8 cm: 25 x 4 cm collapses (docs/samples.md)
  EXPECT_DOUBLE_EQ(loadScene(dir / "lilium.json").lamella.widthM, 0.50);  // 50 x 5 cm
  EXPECT_DOUBLE_EQ(loadScene(dir / "yas.json").lamella.widthM, 0.40);     // 40 x 5 cm
  EXPECT_EQ(parsed, 7);
  EXPECT_EQ(loadScene(dir / "scenes" / "bump_patch.json").patching.patches.size(), 1u);
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Issue 17: a name starting with NUL emptied ./out; control characters and long names are refused
// as the scene's error, naming the field.
TEST(SceneSafety, NamesMustBePortableFolderNames) {
  const std::string surface = R"("surface": {"sample": "bump"})";
  for (const std::string name : {"\\u0000", "\\u0000abc", "a\\nb", "a\\u001bb", "..", "a/b"}) {
    const std::string m =
        messageOf([&] { parse("{\"name\": \"" + name + "\", " + surface + "}"); });
    EXPECT_NE(m.find("name"), std::string::npos) << name << ": " << m;
    EXPECT_EQ(m.find('\0'), std::string::npos);
  }
  // 238-255 characters failed at the staging folder; now: too long, at parse time.
  const std::string m =
      messageOf([&] { parse("{\"name\": \"" + std::string(240, 'n') + "\", " + surface + "}"); });
  EXPECT_NE(m.find("too long"), std::string::npos) << m;
  EXPECT_NO_THROW(parse("{\"name\": \"" + std::string(200, 'n') + "\", " + surface + "}"));
}

// Issue 17: messages echoed the whole offending value (200 MB of stderr for a 200 MB name).
TEST(SceneSafety, MessagesShowAtMostAShortPieceOfTheValue) {
  const std::string huge(5000000, 'x');
  const std::string m = messageOf(
      [&] { parse(R"({"surface": {"sample": "bump"}, "grid": {"alpha_bar": ")" + huge + "\"}}"); });
  EXPECT_NE(m.find("grid.alpha_bar"), std::string::npos) << m.substr(0, 300);
  EXPECT_LT(m.size(), 600u);
  const std::string m2 =
      messageOf([&] { parse(R"({"surface": {"sample": "bump"}, ")" + huge + "\": 1}"); });
  EXPECT_LT(m2.size(), 1000u);
}

// A truncated scene file was blamed on the last complete key ("surface: not valid JSON").
TEST(SceneSafety, ASyntaxErrorAfterACompleteValueNamesNoKey) {
  const std::string m = messageOf(
      [&] { parseSceneText(R"({"name": "x", "surface": {"sample": "bump"}, )", "cut.json"); });
  EXPECT_EQ(m.find("surface"), std::string::npos) << m;
  EXPECT_NE(m.find("cut.json: not valid JSON"), std::string::npos) << m;
  // Inside a value, the error still names where it is.
  const std::string m2 = messageOf([&] {
    parseSceneText(R"({"surface": {"sample": "bump"}, "grid": {"alpha_bar": 1e999}})", "n.json");
  });
  EXPECT_NE(m2.find("grid.alpha_bar"), std::string::npos) << m2;
  const std::string m3 = messageOf(
      [&] { parseSceneText(R"({"surface": {"sample": "bump"}, "grid": [1, 2, }})", "a.json"); });
  EXPECT_NE(m3.find("grid[2]"), std::string::npos) << m3;
}

// Issue 17: a deeply nested value in a typed field crashed (SIGSEGV) in the message's dump.
TEST(SceneSafety, DeeplyNestedValuesNeitherCrashNorFlood) {
  const int depth = 70000;
  const std::string deep = std::string(depth, '[') + std::string(depth, ']');
  const std::string m = messageOf([&] {
    parseSceneText(R"({"surface": {"sample": "bump"}, "lamella": {"width_m": )" + deep + "}}",
                   "deep.json");
  });
  EXPECT_NE(m.find("deeper than"), std::string::npos) << m.substr(0, 300);
  EXPECT_NE(m.find("lamella.width_m"), std::string::npos) << m.substr(0, 300);
  // A parsed document handed over directly: the message renders a few levels only.
  json value = json::array();
  for (int i = 0; i < 2000; ++i) value = json::array({value});
  const std::string m2 = messageOf([&] {
    parseScene(json{{"surface", {{"sample", "bump"}}}, {"lamella", {{"width_m", value}}}},
               "x.json");
  });
  EXPECT_NE(m2.find("lamella.width_m: must be a number"), std::string::npos) << m2.substr(0, 300);
  EXPECT_LT(m2.size(), 400u);
}

// Issue 17: 1e400 (nlohmann refuses the overflow) was an "internal error", exit 1, naming no field.
TEST(SceneSafety, ANumberThatOverflowsADoubleNamesTheField) {
  try {
    parseSceneText(R"({"surface": {"sample": "bump"}, "patching": {"slope_bounds": [0.1, 1e400]}})",
                   "big.json");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("big.json: patching.slope_bounds[1]"), std::string::npos) << m;
    EXPECT_NE(m.find("1e400"), std::string::npos) << m;
  }
  const std::string m = messageOf([] {
    parseSceneText(R"({"surface": {"sample": "bump"}, "lamella": {"width_m": -1e999}})", "s.json");
  });
  EXPECT_NE(m.find("lamella.width_m"), std::string::npos) << m;
}

// Issue 17: 18446744073709551615 was reported as "got -1".
TEST(SceneSafety, HugeUnsignedIntegersAreReportedAsWritten) {
  const std::string m = messageOf([] {
    parse(R"({"surface": {"sample": "bump"}, "grid": {"map_resolution": 18446744073709551615}})");
  });
  EXPECT_NE(m.find("18446744073709551615"), std::string::npos) << m;
  EXPECT_EQ(m.find("-1"), std::string::npos) << m;
}

// Issue 17: a layout of 10,000 patches ran for minutes with no limit.
TEST(SceneSafety, TooManyPatchesIsAnErrorBeforeTheWork) {
  json patches = json::array();
  for (int i = 0; i < 1001; ++i)
    patches.push_back({{i, 0, 0}, {i + 1, 0, 0}, {i + 1, 1, 0}, {i, 1, 0}});
  const std::string m = messageOf([&] {
    parseScene(json{{"surface", {{"sample", "bump"}}}, {"patching", {{"patches", patches}}}},
               "p.json");
  });
  EXPECT_NE(m.find("patching.patches: has 1001 patches; at most 1000"), std::string::npos) << m;
}

// Issue 17: a directory as the scene was an internal error (exit 1); a FIFO blocked forever.
TEST(SceneSafety, AFolderOrFifoAsSceneIsAnIoError) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("egg_scene_safety_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "scene.json");
  EXPECT_THROW(loadScene(dir / "scene.json"), IoError);
  const auto fifo = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string m = messageOf([&] { loadScene(fifo); });
  EXPECT_NE(m.find("FIFO"), std::string::npos) << m;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace egg::pipeline

namespace egg::pipeline {
namespace {

// The field lists are the one declaration of every key: no key twice in a section, the echo of a
// scene reads back to the same scene, and the committed reference is the generated one.
TEST(SceneFields, EveryKeyIsDeclaredOnceAndTheEchoReadsBackToTheSameScene) {
  for (const SceneSection& section : sceneSections()) {
    std::set<std::string> keys;
    for (const SceneField& f : section.fields)
      EXPECT_TRUE(keys.insert(f.key).second) << section.key << "." << f.key;
  }
  for (
      const char* text :
      {R"({"surface": {"sample": "bump"}})",
       R"({"surface": {"file": "m.obj", "scale_to_m": 0.001}, "patching": {"patches": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]},
                               "grid": {"alpha_bar": 1.1, "members_per_family": 9}, "simulation": {"supports": "anchors"},
                               "fabrication": {"splice_joint": "plate_or_scarf", "end_overhang_mm": 30, "sticker_sheet_mm": [500, 300]}})"}) {
    const json echo = sceneToJson(parseScene(json::parse(text), "/scenes/test.json"));
    json again = echo;
    again.erase("path");
    EXPECT_EQ(sceneToJson(parseScene(again, "/scenes/test.json")), echo) << text;
    for (const SceneSection& section : sceneSections()) {
      if (section.key.empty()) continue;
      for (auto it = echo.at(section.key).begin(); it != echo.at(section.key).end(); ++it) {
        const bool declared = std::any_of(section.fields.begin(), section.fields.end(),
                                          [&](const SceneField& f) { return f.key == it.key(); });
        EXPECT_TRUE(declared) << section.key << "." << it.key();
      }
    }
  }
  const json echo = sceneToJson(
      parse(R"({"surface": {"sample": "bump"}, "simulation": {"supports": "design_boundary"},
                                          "fabrication": {"splice_joint": "scarf"}})"));
  EXPECT_EQ(echo["simulation"]["supports"], "design_boundary");
  EXPECT_EQ(echo["fabrication"]["splice_joint"], "scarf");
  EXPECT_EQ(echo["grid"]["members_per_family"], "auto");
  EXPECT_FALSE(
      echo["fabrication"].contains("end_overhang_mm"));  // derived from the lamella when unset
}

TEST(SceneFields, AChoiceNamesItsAlternatives) {
  const std::string e =
      errorOf(R"({"surface": {"sample": "bump"}, "simulation": {"supports": "walls"}})");
  EXPECT_NE(e.find("simulation.supports: must be \"auto\", \"anchors\" or \"design_boundary\", got "
                   "\"walls\""),
            std::string::npos)
      << e;
}

TEST(SceneFields, TheCommittedSceneReferenceIsTheGeneratedOne) {
  std::ifstream in(std::filesystem::path(EGG_SOURCE_DIR) / "docs" / "scene-reference.md");
  ASSERT_TRUE(in)
      << "docs/scene-reference.md is missing: egg scene-reference --out docs/scene-reference.md";
  const std::string committed((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
  EXPECT_EQ(committed, sceneReferenceMarkdown())
      << "regenerate it: egg scene-reference --out docs/scene-reference.md";
  for (const SceneSection& section : sceneSections())
    for (const SceneField& f : section.fields)
      EXPECT_NE(committed.find("| `" + f.key + "` |"), std::string::npos) << f.key;
}

}  // namespace
}  // namespace egg::pipeline
