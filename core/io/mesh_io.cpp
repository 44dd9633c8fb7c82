#include "core/io/mesh_io.hpp"

#include "core/errors.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <system_error>
#include <unistd.h>

namespace egg {
namespace fs = std::filesystem;
namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) e(r, c) = m[r][c];
  return e;
}

// Appends the triangles of every mesh under `node`, with the accumulated node transform applied.
// A mesh referenced by several nodes (instancing) is appended once per reference.
void collectNode(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, double scale,
                 TriangleSoup& soup, long& ignoredPrimitives) {
  const Eigen::Matrix4d transform = parent * toEigen(node.mTransformation);
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
      soup.triangles.push_back({offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collectNode(scene, *node.mChildren[c], transform, scale, soup, ignoredPrimitives);
}

struct ExportFormat {
  const char* extension;
  const char* assimpId;  // binary variant
  const char* assimpIdText;
};

// Assimp exporter ids by extension. OBJ without a material library: a design surface has none.
constexpr ExportFormat kExportFormats[] = {
    {".obj", "objnomtl", "objnomtl"}, {".ply", "plyb", "ply"},   {".stl", "stlb", "stl"},
    {".gltf", "gltf2", "gltf2"},      {".glb", "glb2", "glb2"},
};

// Builds the one-mesh scene assimp's exporters expect (a root node, one material, normals).
std::unique_ptr<aiScene> sceneFromSoup(const TriangleSoup& soup, double scale) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("eggshell_surface");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  auto* mesh = new aiMesh();
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{mesh};
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
    const Eigen::Vector3d areaNormal =
        (soup.vertices[tri[1]] - soup.vertices[tri[0]]).cross(soup.vertices[tri[2]] - soup.vertices[tri[0]]);
    for (int v : tri) normals[v] += areaNormal;
  }
  for (unsigned v = 0; v < n; ++v) {
    const Eigen::Vector3d p = scale * soup.vertices[v];
    mesh->mVertices[v] = aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
    const double length = normals[v].norm();
    const Eigen::Vector3d unit = length > 0.0 ? Eigen::Vector3d(normals[v] / length) : Eigen::Vector3d::UnitZ();
    mesh->mNormals[v] = aiVector3D(static_cast<ai_real>(unit.x()), static_cast<ai_real>(unit.y()), static_cast<ai_real>(unit.z()));
  }
  const unsigned m = static_cast<unsigned>(soup.triangles.size());
  mesh->mNumFaces = m;
  mesh->mFaces = new aiFace[m];
  for (unsigned f = 0; f < m; ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) mesh->mFaces[f].mIndices[k] = static_cast<unsigned>(soup.triangles[f][k]);
  }
  return scene;
}

}  // namespace

void MeshImportOptions::validate() const {
  if (!(std::isfinite(scale_to_m) && scale_to_m > 0.0)) {
    std::ostringstream s;
    s << "MeshImportOptions.scale_to_m must be a positive number, got " << scale_to_m;
    throw InvalidInput(s.str());
  }
}

void MeshExportOptions::validate() const {
  if (!(std::isfinite(scale_from_m) && scale_from_m > 0.0)) {
    std::ostringstream s;
    s << "MeshExportOptions.scale_from_m must be a positive number, got " << scale_from_m;
    throw InvalidInput(s.str());
  }
}

TriangleSoup readMeshFile(const fs::path& path, const MeshImportOptions& options) {
  options.validate();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError("cannot read mesh " + quoted(path) + ": the file does not exist");
  if (fs::is_directory(path, ec)) throw IoError("cannot read mesh " + quoted(path) + ": it is a directory");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw IoError("cannot read mesh " + quoted(path) + ": the file cannot be opened");
  }
  Assimp::Importer importer;
  // Triangulate polygons; validation makes assimp refuse inconsistent data instead of crashing later.
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    std::string reason = importer.GetErrorString();
    if (reason.empty()) reason = "unknown format or corrupt file";
    throw IoError("cannot read mesh " + quoted(path) + ": " + reason);
  }
  TriangleSoup soup;
  long ignoredPrimitives = 0;
  if (scene->mRootNode != nullptr)
    collectNode(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), options.scale_to_m, soup, ignoredPrimitives);
  if (soup.triangles.empty()) {
    std::string detail = std::to_string(scene->mNumMeshes) + " mesh(es)";
    if (ignoredPrimitives > 0) detail += ", " + std::to_string(ignoredPrimitives) + " points/lines";
    throw IoError("cannot use mesh " + quoted(path) + ": it holds no triangles (" + detail + ")");
  }
  return soup;
}

TriMesh loadMeshFile(const fs::path& path, const MeshImportOptions& importOptions, const MeshCheckOptions& checkOptions,
                     MeshRepairDiagnostics& diagnostics) {
  checkOptions.validate();
  TriangleSoup soup = readMeshFile(path, importOptions);
  try {
    return prepareMesh(std::move(soup), checkOptions, diagnostics);
  } catch (const InvalidInput& e) {
    throw InvalidInput("mesh " + quoted(path) + ": " + e.what());
  }
}

void writeMeshFile(const fs::path& path, const TriangleSoup& soup, const MeshExportOptions& options) {
  options.validate();
  const std::string ext = lowerExtension(path);
  const ExportFormat* format = nullptr;
  for (const auto& f : kExportFormats)
    if (ext == f.extension) format = &f;
  if (format == nullptr) {
    std::string known;
    for (const auto& f : kExportFormats) known += std::string(known.empty() ? "" : ", ") + f.extension;
    throw IoError("cannot write mesh " + quoted(path) + ": unknown extension '" + ext + "' (use " + known + ")");
  }
  if (soup.triangles.empty()) throw InvalidInput("cannot write mesh " + quoted(path) + ": the mesh has no triangles");
  const int n = static_cast<int>(soup.vertices.size());
  for (const auto& tri : soup.triangles)
    for (int v : tri)
      if (v < 0 || v >= n) throw InvalidInput("cannot write mesh " + quoted(path) + ": a triangle index is out of range");

  const fs::path target = fs::absolute(path);
  const fs::path directory = target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw WriteError("cannot write mesh " + quoted(path) + ": the directory " + quoted(directory) +
                     (ec ? " cannot be read: " + ec.message() : " does not exist"));
  }

  // Export into a private directory next to the target, then rename every produced file into
  // place (same file system, so each rename is atomic). glTF's .bin keeps the name the .gltf
  // refers to because the file names do not change, only their directory.
  static std::atomic<int> counter{0};
  const fs::path staging = directory / (".egg-write-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  if (!fs::create_directory(staging, ec))
    throw WriteError("cannot write mesh " + quoted(path) + ": cannot create a temporary directory in " + quoted(directory) +
                  " (" + ec.message() + ")");
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } cleanup{staging};

  const auto scene = sceneFromSoup(soup, options.scale_from_m);
  Assimp::Exporter exporter;
  const char* id = options.binary ? format->assimpId : format->assimpIdText;
  if (exporter.Export(scene.get(), id, (staging / target.filename()).string()) != aiReturn_SUCCESS) {
    std::string reason = exporter.GetErrorString();
    throw WriteError("cannot write mesh " + quoted(path) + ": " + (reason.empty() ? "the exporter failed" : reason));
  }
  std::vector<fs::path> produced;
  for (const auto& entry : fs::directory_iterator(staging)) produced.push_back(entry.path());
  // The main file last, so it never refers to a companion file that is not there yet.
  std::stable_partition(produced.begin(), produced.end(), [&](const fs::path& p) { return p.filename() != target.filename(); });
  for (const auto& file : produced) {
    fs::rename(file, directory / file.filename(), ec);
    if (ec) throw WriteError("cannot write mesh " + quoted(path) + ": cannot move " + quoted(file.filename()) +
                          " into place (" + ec.message() + ")");
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
    std::transform(item.begin(), item.end(), item.begin(), [](unsigned char c) { return std::tolower(c); });
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
