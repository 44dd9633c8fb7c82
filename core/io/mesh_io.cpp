#include "core/io/mesh_io.hpp"

#include "core/errors.hpp"

#include "core/io/atomic_file.hpp"
#include "core/io/json_check.hpp"
#include "core/io/mesh_precheck.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <unordered_map>

#include <unistd.h>
#include <nlohmann/json.hpp>
#include <system_error>
#include <utility>

namespace egg {
namespace fs = std::filesystem;
namespace {

using mesh_precheck::lowerExtension;
using mesh_precheck::quoted;

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) e(r, c) = m[r][c];
  return e;
}

// Appends the triangles of every mesh under `root`, with the accumulated node transform applied.
// A mesh referenced by several nodes (instancing) is appended once per reference. An explicit
// stack, not recursion: a file may nest its nodes as deep as it likes.
void collectNodes(const aiScene& scene, const aiNode& root, double scale, TriangleSoup& soup,
                  long& ignoredPrimitives) {
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack{
      {&root, Eigen::Matrix4d::Identity()}};
  while (!stack.empty()) {
    const aiNode& node = *stack.back().first;
    const Eigen::Matrix4d transform = stack.back().second * toEigen(node.mTransformation);
    stack.pop_back();
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
      const int offset = static_cast<int>(soup.vertices.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& p = mesh.mVertices[v];
        const Eigen::Vector4d q = transform * Eigen::Vector4d(p.x, p.y, p.z, 1.0);
        soup.vertices.push_back(scale * q.head<3>() / q.w());
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) {  // points and lines (polygons were triangulated on import)
          ++ignoredPrimitives;
          continue;
        }
        soup.triangles.push_back({offset + static_cast<int>(face.mIndices[0]),
                                  offset + static_cast<int>(face.mIndices[1]),
                                  offset + static_cast<int>(face.mIndices[2])});
      }
    }
    // Children pushed in reverse so that they are visited in file order (as the recursion did).
    for (unsigned c = node.mNumChildren; c-- > 0;) stack.emplace_back(node.mChildren[c], transform);
  }
}

// OBJ shares vertices between faces, but assimp's importer gives every face corner a vertex of
// its own: every clean OBJ then "merged N duplicate vertices", and messages named vertices by
// assimp's numbers (an edge (752, 758) in a 626-vertex file). This rebuilds the soup in the
// file's numbering (0-based: vertex k is the file's (k+1)-th "v" line) by matching assimp's
// positions with the file's (parsed as floats, as assimp stores them). False (and `soup` untouched)
// when a position does not match or a node carries a transform: the caller keeps assimp's soup.
bool objSoupInFileOrder(const aiScene& scene, const std::vector<aiVector3D>& filePositions,
                        double scale, TriangleSoup& soup) {
  struct KeyHash {
    size_t operator()(const std::array<uint32_t, 3>& k) const {
      return (static_cast<size_t>(k[0]) * 0x9E3779B97F4A7C15ull) ^
             (static_cast<size_t>(k[1]) * 0xC2B2AE3D27D4EB4Full) ^ k[2];
    }
  };
  auto key = [](const aiVector3D& p) {
    std::array<uint32_t, 3> k{};
    static_assert(sizeof(ai_real) == sizeof(uint32_t));
    std::memcpy(&k[0], &p.x, 4), std::memcpy(&k[1], &p.y, 4), std::memcpy(&k[2], &p.z, 4);
    return k;
  };
  std::unordered_map<std::array<uint32_t, 3>, int, KeyHash> index;
  index.reserve(filePositions.size());
  for (size_t i = 0; i < filePositions.size(); ++i)
    index.emplace(key(filePositions[i]), static_cast<int>(i));
  TriangleSoup out;
  std::vector<const aiNode*> stack{scene.mRootNode};
  while (!stack.empty()) {
    const aiNode* node = stack.back();
    stack.pop_back();
    if (!node->mTransformation.IsIdentity()) return false;
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[k]];
      std::vector<int> fileIndex(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const auto it = index.find(key(mesh.mVertices[v]));
        if (it == index.end()) return false;
        fileIndex[v] = it->second;
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices == 3)
          out.triangles.push_back({fileIndex[face.mIndices[0]], fileIndex[face.mIndices[1]],
                                   fileIndex[face.mIndices[2]]});
      }
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back(node->mChildren[c]);
  }
  out.vertices.reserve(filePositions.size());
  for (const auto& p : filePositions)
    out.vertices.push_back(scale * Eigen::Vector3d(p.x, p.y, p.z));
  soup = std::move(out);
  return true;
}

// --- Export through memory: assimp's exporters do not check their writes (a full disk gave a
// truncated file and success); they write into buffers here, and every buffer goes to disk
// through writeFileAtomically, which checks write, fsync and close and leaves nothing behind. ---

class MemoryStream : public Assimp::IOStream {
 public:
  explicit MemoryStream(std::string& buffer) : buffer_(buffer) {}
  size_t Read(void*, size_t, size_t) override { return 0; }
  size_t Write(const void* data, size_t size, size_t count) override {
    const size_t bytes = size * count;
    if (position_ + bytes > buffer_.size()) buffer_.resize(position_ + bytes);
    std::memcpy(buffer_.data() + position_, data, bytes);
    position_ += bytes;
    return count;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET   ? 0
                        : origin == aiOrigin_CUR ? position_
                                                 : buffer_.size();
    // Past the end is allowed, as with a file (the GLB writer seeks over its header first).
    position_ = base + offset;
    if (position_ > buffer_.size()) buffer_.resize(position_);
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return position_; }
  size_t FileSize() const override { return buffer_.size(); }
  void Flush() override {}

 private:
  std::string& buffer_;
  size_t position_ = 0;
};

class MemoryIOSystem : public Assimp::IOSystem {
 public:
  bool Exists(const char* file) const override { return files_.count(file) > 0; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (mode == nullptr || (std::strchr(mode, 'w') == nullptr && std::strchr(mode, 'a') == nullptr))
      return nullptr;
    auto& entry = files_[file];
    if (entry.second == 0) entry.second = ++order_;
    entry.first.clear();
    return new MemoryStream(entry.first);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
  // Files in the order they were first opened.
  std::vector<std::pair<std::string, const std::string*>> files() const {
    std::vector<std::pair<int, std::pair<std::string, const std::string*>>> ordered;
    for (const auto& [name, entry] : files_)
      ordered.push_back({entry.second, {name, &entry.first}});
    std::sort(ordered.begin(), ordered.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::pair<std::string, const std::string*>> out;
    for (auto& o : ordered) out.push_back(o.second);
    return out;
  }

 private:
  std::map<std::string, std::pair<std::string, int>> files_;
  int order_ = 0;
};

struct ExportFormat {
  const char* extension;
  const char* assimpId;  // binary variant
  const char* assimpIdText;
};

// Assimp exporter ids by extension. OBJ without a material library: a design surface has none.
constexpr ExportFormat kExportFormats[] = {
    {".obj", "objnomtl", "objnomtl"}, {".ply", "plyb", "ply"},  {".stl", "stlb", "stl"},
    {".gltf", "gltf2", "gltf2"},      {".glb", "glb2", "glb2"},
};

// Builds the one-mesh scene assimp's exporters expect (a root node, one material, normals).
std::unique_ptr<aiScene> sceneFromSoup(const TriangleSoup& soup, double scale) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("eggshell_surface");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  auto* mesh = new aiMesh();
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { mesh };
  mesh->mName = "surface";
  mesh->mMaterialIndex = 0;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const unsigned n = static_cast<unsigned>(soup.vertices.size());
  mesh->mNumVertices = n;
  mesh->mVertices = new aiVector3D[n];
  mesh->mNormals = new aiVector3D[n];
  std::vector<Eigen::Vector3d> normals(n, Eigen::Vector3d::Zero());
  for (const auto& tri : soup.triangles) {
    // Area-weighted vertex normals (viewers shade with them; glTF requires unit normals).
    const Eigen::Vector3d areaNormal = (soup.vertices[tri[1]] - soup.vertices[tri[0]])
                                           .cross(soup.vertices[tri[2]] - soup.vertices[tri[0]]);
    for (int v : tri) normals[v] += areaNormal;
  }
  for (unsigned v = 0; v < n; ++v) {
    const Eigen::Vector3d p = scale * soup.vertices[v];
    mesh->mVertices[v] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()),
                                    static_cast<ai_real>(p.z()));
    const double length = normals[v].norm();
    const Eigen::Vector3d unit =
        length > 0.0 ? Eigen::Vector3d(normals[v] / length) : Eigen::Vector3d::UnitZ();
    mesh->mNormals[v] = aiVector3D(static_cast<ai_real>(unit.x()), static_cast<ai_real>(unit.y()),
                                   static_cast<ai_real>(unit.z()));
  }
  const unsigned m = static_cast<unsigned>(soup.triangles.size());
  mesh->mNumFaces = m;
  mesh->mFaces = new aiFace[m];
  for (unsigned f = 0; f < m; ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k)
      mesh->mFaces[f].mIndices[k] = static_cast<unsigned>(soup.triangles[f][k]);
  }
  return scene;
}

}  // namespace

void MeshImportOptions::validate() const {
  if (!(std::isfinite(scaleToM) && scaleToM > 0.0)) {
    std::ostringstream s;
    s << "MeshImportOptions.scale_to_m must be a positive number, got " << scaleToM;
    throw InvalidInput(s.str());
  }
}

void MeshExportOptions::validate() const {
  if (!(std::isfinite(scaleFromM) && scaleFromM > 0.0)) {
    std::ostringstream s;
    s << "MeshExportOptions.scale_from_m must be a positive number, got " << scaleFromM;
    throw InvalidInput(s.str());
  }
}

TriangleSoup readMeshFile(const fs::path& path, const MeshImportOptions& options) {
  options.validate();
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw IoError("cannot read mesh " + quoted(path) + ": the file does not exist");
  if (fs::is_directory(path, ec))
    throw IoError("cannot read mesh " + quoted(path) + ": it is a directory");
  // Not a regular file (a FIFO would block assimp forever), too large, or what assimp takes
  // wrongly.
  const std::vector<aiVector3D> objPositions = precheckMeshFile(path);
  Assimp::Importer importer;
  // Validation makes assimp refuse inconsistent data instead of crashing later. Triangulation is
  // a second step: assimp's validation lets a face without vertices through, and its triangulation
  // then aborts the process on an assertion (a fuzzed binary PLY), so such faces are refused first.
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  auto failed = [&] {
    std::string reason = importer.GetErrorString();
    if (reason.empty()) reason = "unknown format or corrupt file";
    throw IoError("cannot read mesh " + quoted(path) + ": " + reason);
  };
  if (scene == nullptr) failed();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned f = 0; mesh != nullptr && f < mesh->mNumFaces; ++f) {
      if (mesh->mFaces[f].mNumIndices == 0 || mesh->mFaces[f].mIndices == nullptr)
        throw IoError("cannot read mesh " + quoted(path) + ": face " + std::to_string(f) +
                      (scene->mNumMeshes > 1 ? " of mesh " + std::to_string(m) : std::string()) +
                      " has no vertices");
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
  if (scene == nullptr) failed();
  TriangleSoup soup;
  long ignoredPrimitives = 0;
  if (scene->mRootNode != nullptr)
    collectNodes(*scene, *scene->mRootNode, options.scaleToM, soup, ignoredPrimitives);
  if (!objPositions.empty() && scene->mRootNode != nullptr && !soup.triangles.empty())
    objSoupInFileOrder(*scene, objPositions, options.scaleToM, soup);
  if (soup.triangles.empty()) {
    std::string detail = std::to_string(scene->mNumMeshes) + " mesh(es)";
    if (ignoredPrimitives > 0) detail += ", " + std::to_string(ignoredPrimitives) + " points/lines";
    throw IoError("cannot use mesh " + quoted(path) + ": it holds no triangles (" + detail + ")");
  }
  return soup;
}

TriMesh loadMeshFile(const fs::path& path, const MeshImportOptions& importOptions,
                     const MeshCheckOptions& checkOptions, MeshRepairDiagnostics& diagnostics) {
  checkOptions.validate();
  TriangleSoup soup = readMeshFile(path, importOptions);
  try {
    return prepareMesh(std::move(soup), checkOptions, diagnostics);
  } catch (const InvalidInput& e) {
    throw InvalidInput("mesh " + quoted(path) + ": " + e.what());
  }
}

void writeMeshFile(const fs::path& path, const TriangleSoup& soup,
                   const MeshExportOptions& options) {
  options.validate();
  const std::string ext = lowerExtension(path);
  const ExportFormat* format = nullptr;
  for (const auto& f : kExportFormats)
    if (ext == f.extension) format = &f;
  if (format == nullptr) {
    std::string known;
    for (const auto& f : kExportFormats)
      known += std::string(known.empty() ? "" : ", ") + f.extension;
    throw IoError("cannot write mesh " + quoted(path) + ": unknown extension '" + ext + "' (use " +
                  known + ")");
  }
  if (soup.triangles.empty())
    throw InvalidInput("cannot write mesh " + quoted(path) + ": the mesh has no triangles");
  const int n = static_cast<int>(soup.vertices.size());
  for (const auto& tri : soup.triangles)
    for (int v : tri)
      if (v < 0 || v >= n)
        throw InvalidInput("cannot write mesh " + quoted(path) +
                           ": a triangle index is out of range");

  const fs::path target = fs::absolute(path);
  const fs::path directory = target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw WriteError("cannot write mesh " + quoted(path) + ": the directory " + quoted(directory) +
                     (ec ? " cannot be read: " + ec.message() : " does not exist"));
  }
  checkedOutputTarget(target);  // a device, a FIFO or a folder is refused before the work
  // Leftovers of earlier versions, which exported into .egg-write-PID-N folders.
  removeDeadLeftovers(directory, ".egg-write-", true);

  const auto scene = sceneFromSoup(soup, options.scaleFromM);
  Assimp::Exporter exporter;
  auto* memory = new MemoryIOSystem;  // owned by the exporter
  exporter.SetIOHandler(memory);
  const char* id = options.binary ? format->assimpId : format->assimpIdText;
  if (exporter.Export(scene.get(), id, target.string()) != aiReturn_SUCCESS) {
    std::string reason = exporter.GetErrorString();
    throw WriteError("cannot write mesh " + quoted(path) + ": " +
                     (reason.empty() ? "the exporter failed" : reason));
  }
  auto produced = memory->files();
  // The main file last, so it never refers to a companion file (glTF's .bin) that is not there yet.
  std::stable_partition(produced.begin(), produced.end(),
                        [&](const auto& f) { return fs::path(f.first) != target; });
  // A companion file (glTF's .bin) is a path the user did not name: it may replace only the
  // companion of an earlier export to the same target (whose text refers to it), never a file of
  // theirs that happens to share its name (issue 40).
  for (const auto& [name, bytes] : produced) {
    const fs::path file(name);
    if (file == target || !fs::exists(fs::symlink_status(file))) continue;
    std::string earlier;
    {
      std::ifstream in(target, std::ios::binary);
      std::ostringstream text;
      if (in) text << in.rdbuf();
      earlier = text.str();
    }
    if (earlier.find(file.filename().string()) == std::string::npos)
      throw WriteError("cannot write mesh " + quoted(path) + ": its companion file " +
                       quoted(file) +
                       " exists and is not an earlier export's (remove it, or export .glb, "
                       "which is one file)");
  }
  for (const auto& [name, bytes] : produced) {
    const fs::path file(name);
    if (file.parent_path() != directory)
      throw WriteError("cannot write mesh " + quoted(path) +
                       ": the exporter asked for a file elsewhere (" + quoted(file) + ")");
    try {
      writeFileAtomically(file, *bytes);
    } catch (const WriteError& e) {
      throw WriteError("cannot write mesh " + quoted(path) + ": " + e.what());
    }
  }
}

void writeMeshFile(const fs::path& path, const TriMesh& mesh, const MeshExportOptions& options) {
  writeMeshFile(path, soupFromMesh(mesh), options);
}

std::vector<std::string> importableExtensions() {
  Assimp::Importer importer;
  std::string list;
  importer.GetExtensionList(list);  // "*.3ds;*.obj;..."
  std::vector<std::string> extensions;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ';')) {
    if (item.rfind("*", 0) == 0) item = item.substr(1);
    std::transform(item.begin(), item.end(), item.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (!item.empty()) extensions.push_back(item);
  }
  return extensions;
}

std::vector<std::string> exportableExtensions() {
  std::vector<std::string> extensions;
  for (const auto& f : kExportFormats) extensions.push_back(f.extension);
  return extensions;
}

}  // namespace egg
