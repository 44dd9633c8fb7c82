#include "core/io/mesh_io.hpp"

#include "core/errors.hpp"
#include "core/mesh/validate.hpp"
#include "samples/generators/samples.hpp"

#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <unistd.h>
#include <cmath>
#include <fstream>
#include <random>

namespace egg {
namespace {
namespace fs = std::filesystem;

// A curved open surface z = 0.3 sin(x) cos(y) on a jittered grid: no coordinate is a "round"
// number.
TriangleSoup wavySurface(int n = 6) {
  TriangleSoup soup;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = 2.0 * i / n + ((i > 0 && i < n) ? jitter(rng) / n : 0.0);
      const double y = 1.5 * j / n + ((j > 0 && j < n) ? jitter(rng) / n : 0.0);
      soup.vertices.push_back({x + 10.0, y - 3.0, 0.3 * std::sin(x) * std::cos(y) + 1.0});
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return soup;
}

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("egg_test_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
  static inline int counter_ = 0;
};

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

Eigen::Vector3d areaVector(const TriangleSoup& soup) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& t : soup.triangles)
    sum += 0.5 * (soup.vertices[t[1]] - soup.vertices[t[0]])
                     .cross(soup.vertices[t[2]] - soup.vertices[t[0]]);
  return sum;
}

// Every original vertex is found again (float precision: files store 32-bit floats), counts equal
// after merging duplicates, and the orientation (area vector) survives.
void expectSameSurface(const TriangleSoup& original, const TriangleSoup& readBack,
                       const std::string& label) {
  MeshRepairDiagnostics diagnostics;
  const TriangleSoup merged = soupFromMesh(prepareMesh(readBack, {}, diagnostics));
  EXPECT_EQ(merged.vertices.size(), original.vertices.size()) << label;
  EXPECT_EQ(merged.triangles.size(), original.triangles.size()) << label;
  double worst = 0.0;
  for (const auto& p : original.vertices) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& q : merged.vertices) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, 2e-6) << label;  // |p| ~ 10 m, float spacing ~1e-6 m
  EXPECT_LT((areaVector(merged) - areaVector(original)).norm(), 1e-5) << label;
}

TEST(MeshIo, RoundTripThroughEveryExportFormat) {
  const TriangleSoup original = wavySurface();
  for (const std::string ext : {".obj", ".ply", ".stl", ".gltf", ".glb"})
    for (bool binary : {true, false}) {
      TempDir dir;
      const fs::path file = dir / ("surface" + ext);
      MeshExportOptions options;
      options.binary = binary;
      writeMeshFile(file, original, options);
      const TriangleSoup back = readMeshFile(file);
      expectSameSurface(original, back, ext + (binary ? " binary" : " ascii"));
      // Nothing but the file (and the glTF buffer) is left: no temporary, no material library.
      const std::vector<std::string> expected =
          ext == ".gltf" ? std::vector<std::string>{"surface.bin", "surface.gltf"}
                         : std::vector<std::string>{"surface" + ext};
      EXPECT_EQ(dir.files(), expected) << ext;
    }
}

TEST(MeshIo, StlComesBackWithDuplicatesThatRepairMerges) {
  const TriangleSoup original = wavySurface(4);
  TempDir dir;
  writeMeshFile(dir / "s.stl", original);
  const TriangleSoup raw = readMeshFile(dir / "s.stl");
  EXPECT_EQ(raw.vertices.size(), 3 * original.triangles.size());  // STL has no shared vertices
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = prepareMesh(raw, {}, diagnostics);
  EXPECT_EQ(mesh.n_vertices(), original.vertices.size());
  EXPECT_EQ(diagnostics.mergedVertices,
            static_cast<int>(raw.vertices.size() - original.vertices.size()));
}

TEST(MeshIo, ScaleToMetresAndExportScale) {
  const TriangleSoup original = wavySurface(3);
  TempDir dir;
  MeshExportOptions millimetres;
  millimetres.scaleFromM = 1000.0;
  writeMeshFile(dir / "mm.obj", original, millimetres);
  const TriangleSoup inFileUnits = readMeshFile(dir / "mm.obj");
  EXPECT_NEAR(inFileUnits.vertices[0].x(), 1000.0 * original.vertices[0].x(), 1e-3);
  MeshImportOptions toMetres;
  toMetres.scaleToM = 0.001;
  expectSameSurface(original, readMeshFile(dir / "mm.obj", toMetres), "mm");
}

TEST(MeshIo, OffQuadIsTriangulated) {
  TempDir dir;
  writeText(dir / "quad.off", "OFF\n4 1 0\n0 0 0\n2 0 0\n2 1 0\n0 1 0\n4 0 1 2 3\n");
  const TriangleSoup soup = readMeshFile(dir / "quad.off");
  EXPECT_EQ(soup.triangles.size(), 2u);
  EXPECT_NEAR(areaVector(soup).z(), 2.0, 1e-12);
}

TEST(MeshIo, GltfNodeTransformsAndInstancesAreApplied) {
  // One triangle (0,0,0) (1,0,0) (0,1,0), instanced by two nodes: the second translated by
  // (5, 0, 0) and scaled by 2, under a root node translated by (0, 0, 3).
  TempDir dir;
  writeText(dir / "nodes.gltf", R"({
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"translation": [0, 0, 3], "children": [1, 2]},
              {"mesh": 0},
              {"mesh": 0, "translation": [5, 0, 0], "scale": [2, 2, 2]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}]
  })");
  const TriangleSoup soup = readMeshFile(dir / "nodes.gltf");
  ASSERT_EQ(soup.triangles.size(), 2u);
  std::vector<Eigen::Vector3d> expected = {{0, 0, 3}, {1, 0, 3}, {0, 1, 3},
                                           {5, 0, 3}, {7, 0, 3}, {5, 2, 3}};
  for (const auto& e : expected) {
    double best = 1e9;
    for (const auto& p : soup.vertices) best = std::min(best, (p - e).norm());
    EXPECT_LT(best, 1e-6) << e.transpose();
  }
}

TEST(MeshIo, FbxWrittenByAssimpIsRead) {
  // eggshell does not write FBX, so let assimp's own exporter make one from our scene.
  TempDir dir;
  const TriangleSoup original = wavySurface(3);
  writeMeshFile(dir / "s.glb", original);
  const fs::path fbx = dir / "s.fbx";
  {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile((dir / "s.glb").string(), 0);
    ASSERT_NE(scene, nullptr);
    Assimp::Exporter exporter;
    ASSERT_EQ(exporter.Export(scene, "fbxa", fbx.string()), aiReturn_SUCCESS)
        << exporter.GetErrorString();
  }
  const TriangleSoup back = readMeshFile(fbx);
  EXPECT_EQ(back.triangles.size(), original.triangles.size());
  expectSameSurface(original, back, "fbx");
}

TEST(MeshIo, SamplesWithHolesSurviveStlAndGlbRoundTrips) {
  // great_court has the Reading Room hole and coordinates up to ~50 m: float storage costs
  // ~4e-6 m, and prepareMesh must rebuild exactly the same surface from the STL soup.
  const TriMesh mesh = samples::generateSample("great_court", {}, 4.0);
  const TriangleSoup original = soupFromMesh(mesh);
  TempDir dir;
  for (const std::string name : {"court.stl", "court.glb", "court.obj"}) {
    writeMeshFile(dir / name, mesh);
    const TriangleSoup back = readMeshFile(dir / name);
    MeshRepairDiagnostics diagnostics;
    const TriMesh rebuilt = prepareMesh(back, {}, diagnostics);
    EXPECT_EQ(rebuilt.n_vertices(), mesh.n_vertices()) << name;
    EXPECT_EQ(rebuilt.n_faces(), mesh.n_faces()) << name;
    EXPECT_NEAR(surfaceArea(rebuilt), surfaceArea(mesh), 1e-6 * surfaceArea(mesh)) << name;
    // Same boundary structure: the outer rectangle and the hole.
    int boundaryEdges = 0, originalBoundaryEdges = 0;
    for (auto eh : rebuilt.edges()) boundaryEdges += rebuilt.is_boundary(eh);
    for (auto eh : mesh.edges()) originalBoundaryEdges += mesh.is_boundary(eh);
    EXPECT_EQ(boundaryEdges, originalBoundaryEdges) << name;
  }
  EXPECT_GT(original.triangles.size(), 100u);
}

void expectIoErrorNaming(const fs::path& path, const std::string& reason) {
  try {
    readMeshFile(path);
    ADD_FAILURE() << "no IoError for " << path;
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
}

TEST(MeshIo, BadFilesAreIoErrorsNamingTheFile) {
  TempDir dir;
  expectIoErrorNaming(dir / "missing.obj", "does not exist");
  expectIoErrorNaming(dir / "", "directory");
  std::string garbage(4096, '\0');
  std::mt19937 rng(1);
  for (auto& c : garbage) c = static_cast<char>(rng() & 0xff);
  for (const std::string ext : {".obj", ".stl", ".ply", ".glb", ".fbx", ".off", ".xyz"}) {
    writeText(dir / ("garbage" + ext), garbage);
    expectIoErrorNaming(dir / ("garbage" + ext), "");
  }
  writeText(dir / "empty.obj", "");
  expectIoErrorNaming(dir / "empty.obj", "");
  writeText(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  expectIoErrorNaming(dir / "points.obj", "");
  writeText(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n");
  expectIoErrorNaming(dir / "lines.obj", "");
}

// glTF writes a companion .bin nobody named: it never replaces a file of the user's, only the
// companion of an earlier export to the same .gltf.
TEST(MeshIo, AGltfCompanionNeverReplacesAUsersFile) {
  TempDir dir;
  const TriangleSoup soup = wavySurface(2);
  std::ofstream(dir / "x.bin") << "mine";
  EXPECT_THROW(writeMeshFile(dir / "x.gltf", soup), WriteError);
  std::ifstream mine(dir / "x.bin");
  std::string text;
  std::getline(mine, text);
  EXPECT_EQ(text, "mine");
  EXPECT_FALSE(fs::exists(dir / "x.gltf"));
  fs::remove(dir / "x.bin");
  writeMeshFile(dir / "x.gltf", soup);
  writeMeshFile(dir / "x.gltf", soup);  // the earlier export's own companion is replaced
  EXPECT_TRUE(fs::exists(dir / "x.bin"));
  EXPECT_EQ(readMeshFile(dir / "x.gltf").triangles.size(), soup.triangles.size());
}

TEST(MeshIo, WriteErrorsNameTheFileAndLeaveNothing) {
  TempDir dir;
  const TriangleSoup soup = wavySurface(2);
  // An unsupported format or an empty mesh is the caller's mistake (exit 2); a folder that is not
  // there is a failure to write (WriteError, exit 1).
  EXPECT_THROW(writeMeshFile(dir / "s.xyz", soup), IoError);
  EXPECT_THROW(writeMeshFile(dir / "no_such_dir" / "s.obj", soup), WriteError);
  EXPECT_THROW(writeMeshFile(dir / "empty.obj", TriangleSoup{}), InvalidInput);
  try {
    writeMeshFile(dir / "s.xyz", soup);
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("s.xyz"), std::string::npos);
  }
  EXPECT_TRUE(dir.files().empty());
  MeshImportOptions bad;
  bad.scaleToM = 0.0;
  EXPECT_THROW(readMeshFile(dir / "s.obj", bad), InvalidInput);
}

TEST(MeshIo, LoadMeshFileRepairsOrNamesFileAndElement) {
  TempDir dir;
  const TriangleSoup original = wavySurface(3);
  writeMeshFile(dir / "ok.stl", original);
  MeshRepairDiagnostics diagnostics;
  const TriMesh mesh = loadMeshFile(dir / "ok.stl", {}, {}, diagnostics);
  EXPECT_EQ(mesh.n_vertices(), original.vertices.size());
  EXPECT_GT(diagnostics.mergedVertices, 0);
  // A fin on an edge: three triangles share edge (1, 2) of this OBJ (1-based indices in the file).
  writeText(dir / "fin.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 1 1 1\nf 1 2 3\nf 2 4 3\nf 2 3 5\n");
  try {
    loadMeshFile(dir / "fin.obj", {}, {}, diagnostics);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "fin.obj").string()), std::string::npos) << message;
    EXPECT_NE(message.find("non-manifold edge"), std::string::npos) << message;
    EXPECT_NE(message.find("shared by 3 triangles (0, 1, 2)"), std::string::npos) << message;
  }
}

TEST(MeshIo, ExtensionListsContainTheRequiredFormats) {
  const auto in = importableExtensions();
  for (const std::string ext : {".obj", ".stl", ".ply", ".off", ".gltf", ".glb", ".fbx"})
    EXPECT_NE(std::find(in.begin(), in.end(), ext), in.end()) << ext;
  EXPECT_EQ(exportableExtensions().size(), 5u);
}

// Issue 17: mesh export onto a full disk exited 0 and left a truncated file (assimp does not check
// its writes). The file size limit stands in for the full disk: write() fails with EFBIG.
TEST(MeshIoSafety, ExportToAFullDiskFailsAndLeavesNoTruncatedFile) {
  const TriangleSoup soup = wavySurface(30);
  for (const char* name : {"s.obj", "s.stl", "s.ply", "s.glb", "s.gltf"}) {
    TempDir dir;
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    rlimit small = old;
    small.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    bool threw = false;
    try {
      writeMeshFile(dir / name, soup);
    } catch (const WriteError& e) {
      threw = true;
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    EXPECT_TRUE(threw) << name;
    // No main file; at most a whole companion (.bin written before the .gltf failed? it is larger).
    for (const auto& f : dir.files()) EXPECT_NE(f, std::string(name)) << name;
    for (const auto& f : dir.files()) EXPECT_NE(f.rfind(".egg-", 0), 0u) << f;
  }
}

TEST(MeshIoSafety, ExportOntoADeviceIsRefused) {
  TempDir dir;
  fs::create_directories(dir / "folder.obj");
  EXPECT_THROW(writeMeshFile(dir / "folder.obj", wavySurface(3)), WriteError);
  EXPECT_TRUE(fs::is_directory(dir / "folder.obj"));
  const fs::path fifo = dir / "pipe.stl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(writeMeshFile(fifo, wavySurface(3)), WriteError);
  EXPECT_TRUE(fs::is_fifo(fifo));
}

// Issue 17: leftovers of interrupted exports (.egg-write-PID-N) were never removed.
TEST(MeshIoSafety, LeftoverExportFoldersOfDeadProcessesAreRemoved) {
  TempDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  const fs::path leftover = dir / (".egg-write-" + std::to_string(child) + "-0");
  fs::create_directories(leftover);
  writeText(leftover / "s.obj", "half");
  writeMeshFile(dir / "s.obj", wavySurface(3));
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_EQ(dir.files(), std::vector<std::string>{"s.obj"});
}

// Issue 17: a FIFO as mesh file blocked forever.
TEST(MeshIoSafety, AFifoAsMeshFileIsAnErrorNotAHang) {
  TempDir dir;
  const fs::path fifo = dir / "roof.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    readMeshFile(fifo);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("FIFO"), std::string::npos) << e.what();
  }
}

// Issue 17: OFF faces with negative or out-of-range indices were accepted silently.
TEST(MeshIoSafety, OffFacesWithBadIndicesNameTheFaceAndLine) {
  TempDir dir;
  writeText(dir / "bad.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 7 3\n");
  try {
    readMeshFile(dir / "bad.off");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("line 8: face 1 refers to vertex 7"), std::string::npos) << m;
  }
  writeText(dir / "neg.off",
            "OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 -2 3\n");
  EXPECT_THROW(readMeshFile(dir / "neg.off"), IoError);
  writeText(dir / "ok.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n");
  EXPECT_EQ(readMeshFile(dir / "ok.off").triangles.size(), 2u);
}

// Issue 17: every clean OBJ warned "merged N duplicate vertices", messages used assimp's vertex
// numbers (not the file's), and an inf coordinate was printed as -nan.
TEST(MeshIoSafety, ObjKeepsTheFileNumberingWarnsNothingAndNamesInf) {
  TempDir dir;
  writeText(dir / "sq.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  const TriangleSoup soup = readMeshFile(dir / "sq.obj");
  EXPECT_EQ(soup.vertices.size(), 4u);
  ASSERT_EQ(soup.triangles.size(), 2u);
  EXPECT_EQ(soup.triangles[1], (std::array<int, 3>{1, 3, 2}));
  MeshRepairDiagnostics diagnostics;
  loadMeshFile(dir / "sq.obj", {}, {}, diagnostics);
  EXPECT_TRUE(diagnostics.warnings.empty()) << diagnostics.warnings.front();
  // Elements are named by the file's numbers (0-based: vertex k is the (k+1)-th "v" line), not
  // assimp's per-corner ones: this edge was "(1, 2)" before.
  writeText(dir / "fin.obj",
            "v 0 0 1\nv 0 -1 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 5 3 4\nf 3 2 4\nf 3 4 1\n");
  try {
    loadMeshFile(dir / "fin.obj", {}, {}, diagnostics);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("edge (2, 3)"), std::string::npos) << e.what();
  }
  writeText(dir / "inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    readMeshFile(dir / "inf.obj");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("line 2: vertex 2"), std::string::npos) << m;
    EXPECT_NE(m.find("(inf)"), std::string::npos) << m;
    EXPECT_EQ(m.find("nan"), std::string::npos) << m;
  }
}

// Issue 17: a glTF of 200,000 nested nodes overflowed the stack (inside assimp).
TEST(MeshIoSafety, DeeplyNestedGltfNodesAreRefusedBeforeAssimp) {
  TempDir dir;
  const int depth = 200000;
  std::string nodes;
  nodes.reserve(depth * 20);
  for (int i = 0; i < depth; ++i)
    nodes += (i ? "," : "") +
             (i + 1 < depth ? "{\"children\":[" + std::to_string(i + 1) + "]}" : std::string("{}"));
  writeText(
      dir / "deep.gltf",
      "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[" +
          nodes + "]}");
  try {
    readMeshFile(dir / "deep.gltf");
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("nest deeper"), std::string::npos) << e.what();
  }
  // Deep JSON nesting itself.
  writeText(dir / "deepjson.gltf", std::string(100000, '[') + std::string(100000, ']'));
  EXPECT_THROW(readMeshFile(dir / "deepjson.gltf"), IoError);
  // A cycle.
  writeText(dir / "cycle.gltf",
            "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"children\":[1]},{\"children\":[0]}]}");
  EXPECT_THROW(readMeshFile(dir / "cycle.gltf"), IoError);
}

}  // namespace
}  // namespace egg
