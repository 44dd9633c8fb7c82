#include "core/io/mesh_io.hpp"

#include "core/errors.hpp"

#include "core/io/atomic_file.hpp"
#include "core/io/json_check.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <unordered_map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>
#include <system_error>
#include <utility>
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

// Appends the triangles of every mesh under `root`, with the accumulated node transform applied.
// A mesh referenced by several nodes (instancing) is appended once per reference. An explicit
// stack, not recursion: a file may nest its nodes as deep as it likes.
void collectNodes(const aiScene& scene, const aiNode& root, double scale, TriangleSoup& soup, long& ignoredPrimitives) {
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack{{&root, Eigen::Matrix4d::Identity()}};
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
        soup.triangles.push_back({offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                                  offset + static_cast<int>(face.mIndices[2])});
      }
    }
    // Children pushed in reverse so that they are visited in file order (as the recursion did).
    for (unsigned c = node.mNumChildren; c-- > 0;) stack.emplace_back(node.mChildren[c], transform);
  }
}

// --- Checks before assimp sees a file (issue 17): what assimp accepts silently or crashes on. ---

// Largest mesh file read (assimp holds all of it in memory, several times over).
constexpr std::size_t kMaxMeshFileBytes = std::size_t(2) << 30;
// Deepest glTF node hierarchy accepted (assimp walks it recursively; real files nest a few levels).
constexpr int kMaxGltfNodeDepth = 256;
constexpr int kMaxGltfJsonDepth = 256;

// OFF: every face index must name a vertex of the file; assimp accepts negative and out-of-range
// ones silently (a face 3 1 7 -2 in a 4-vertex file became a valid-looking mesh).
void checkOffFile(const fs::path& path, const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  long lineNumber = 0;
  auto nextContentLine = [&](std::string& out) {
    while (std::getline(lines, out)) {
      ++lineNumber;
      const size_t hash = out.find('#');
      if (hash != std::string::npos) out.erase(hash);
      if (out.find_first_not_of(" \t\r") != std::string::npos) return true;
    }
    return false;
  };
  if (!nextContentLine(line)) return;  // empty: assimp reports it
  std::istringstream header(line);
  std::string magic;
  header >> magic;
  // The counts: on the OFF line (OFF, COFF, NOFF, ...), on the next one, or, without the
  // keyword, on the first line. Assimp parses them with a wrapping strtoul: a count of 10^25
  // became a 61 GB allocation (or 16 GB without the keyword). Not two plain numbers below 2^31:
  // refused here.
  std::string first, second;
  const bool keyword = magic.size() >= 3 && magic.compare(magic.size() - 3, 3, "OFF") == 0;
  if (!keyword) {
    std::istringstream counts(line);
    counts >> first >> second;
  } else if (!(header >> first)) {
    if (!nextContentLine(line)) return;
    std::istringstream counts(line);
    counts >> first >> second;
  } else {
    header >> second;
  }
  auto count = [&](const std::string& text) -> long long {
    if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos)
      throw IoError("cannot read mesh " + quoted(path) + ": the OFF header's vertex and face counts must be numbers below 2^31, got " +
                    abbreviate(first, 40) + " " + abbreviate(second, 40));
    const long long value = std::stoll(text);
    if (value > 0x7fffffffLL)
      throw IoError("cannot read mesh " + quoted(path) + ": the OFF header's count " + text + " is too large");
    return value;
  };
  const long long vertices = count(first), faces = count(second);
  if (vertices < 0 || faces < 0) throw IoError("cannot read mesh " + quoted(path) + ": negative vertex or face count in the OFF header");
  // Assimp reserves by these counts; every vertex and face takes at least two bytes of the file.
  if (static_cast<unsigned long long>(vertices) + static_cast<unsigned long long>(faces) > text.size() / 2 + 1)
    throw IoError("cannot read mesh " + quoted(path) + ": the header declares " + std::to_string(vertices) + " vertices and " +
                  std::to_string(faces) + " faces, more than the file's " + std::to_string(text.size()) + " bytes can hold");
  for (long long v = 0; v < vertices; ++v)
    if (!nextContentLine(line)) return;  // truncated: assimp reports it
  for (long long f = 0; f < faces; ++f) {
    if (!nextContentLine(line)) return;
    std::istringstream face(line);
    long long count = 0;
    if (!(face >> count)) continue;
    for (long long k = 0; k < count; ++k) {
      long long index = 0;
      if (!(face >> index)) {
        throw IoError("cannot read mesh " + quoted(path) + ": line " + std::to_string(lineNumber) + ": face " + std::to_string(f) +
                      " lists " + std::to_string(count) + " vertices but gives fewer indices");
      }
      if (index < 0 || index >= vertices) {
        throw IoError("cannot read mesh " + quoted(path) + ": line " + std::to_string(lineNumber) + ": face " + std::to_string(f) +
                      " refers to vertex " + std::to_string(index) + ", but the file has vertices 0 .. " +
                      std::to_string(vertices - 1));
      }
    }
  }
}

// PLY: element counts the file cannot hold. Assimp reserves memory by the header's counts: a
// 169-byte file declaring 2,000,000,000 vertices was killed for lack of memory. Every element
// takes at least a few bytes in the body (ASCII: a digit and a separator per property; binary:
// the sizes of its properties), so the counts are bounded by the file's size.
void checkPlyFile(const fs::path& path, const std::string& text) {
  // The header must follow the PLY grammar exactly: assimp's parser looped forever on fuzzed
  // headers (no end_header line, or misspelt keywords), so anything else is refused here.
  auto fail = [&](long line, const std::string& why) {
    throw IoError("cannot read mesh " + quoted(path) + ": PLY header line " + std::to_string(line) + ": " + why);
  };
  static const std::set<std::string> types{"char",  "uchar", "short", "ushort",  "int",     "uint",    "float",  "double",
                                           "int8",  "uint8", "int16", "uint16",  "int32",   "uint32",  "float32", "float64"};
  auto typeSize = [](const std::string& t) -> unsigned long long {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "double" || t == "float64") return 8;
    return 4;
  };
  struct Element {
    std::string name;
    unsigned long long count = 0;
    unsigned long long minBytes = 0;
  };
  std::vector<Element> elements;
  std::string format;
  size_t pos = 0;
  long lineNumber = 0;
  bool ended = false;
  while (pos < text.size() && !ended) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // Assimp splits header words at spaces and tabs only ("end_header\v0 0 0" hung it).
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') fail(lineNumber, "a control character in the header");
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (lineNumber == 1) {
      if (word != "ply") fail(1, "the file must start with a line \"ply\"");
      continue;
    }
    if (word == "end_header") {
      ended = true;
    } else if (word == "comment" || word == "obj_info") {
    } else if (word == "format") {
      std::string version;
      words >> format >> version;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail(lineNumber, "unknown format " + abbreviate(format, 40));
    } else if (word == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      if (e.name.empty() || count.empty() || count.size() > 19 || count.find_first_not_of("0123456789") != std::string::npos)
        fail(lineNumber, "an element needs a name and a count");
      e.count = std::stoull(count);
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) fail(lineNumber, "a property before any element");
      std::string type, name;
      words >> type;
      unsigned long long bytes = 2;  // ASCII: at least one digit and one separator
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType >> name;
        if (!types.count(countType) || !types.count(itemType)) fail(lineNumber, "unknown list type");
        if (format != "ascii") bytes = typeSize(countType);
      } else {
        words >> name;
        if (!types.count(type)) fail(lineNumber, "unknown property type " + abbreviate(type, 40));
        if (format != "ascii") bytes = typeSize(type);
      }
      if (name.empty()) fail(lineNumber, "a property needs a name");
      elements.back().minBytes += bytes;
    } else {
      fail(lineNumber, "unknown keyword " + abbreviate(word, 40) + " (expected element, property, comment or end_header)");
    }
  }
  if (!ended) throw IoError("cannot read mesh " + quoted(path) + ": the PLY header has no end_header line");
  if (format.empty()) throw IoError("cannot read mesh " + quoted(path) + ": the PLY header has no format line");
  // Every element takes at least a few bytes in the body (ASCII: a digit and a separator per
  // property; binary: the sizes of its properties), so the counts are bounded by the file's size.
  const unsigned long long body = text.size() - std::min(pos, text.size());
  for (const Element& e : elements) {
    const unsigned long long perElement = std::max<unsigned long long>(e.minBytes, 1);
    if (e.count > body / perElement + 1) {
      throw IoError("cannot read mesh " + quoted(path) + ": the header declares " + std::to_string(e.count) + " " +
                    abbreviate(e.name, 40) + " elements, more than the file's " + std::to_string(body) +
                    " bytes after the header can hold");
    }
  }
}

// OBJ: a coordinate that is not a finite number (assimp turns "inf" into NaN, and the message
// then said "-nan"): named by the file's line and vertex number (1-based, as OBJ counts).
// Also returns the vertex positions as floats, in file order.
std::vector<aiVector3D> checkObjFile(const fs::path& path, const std::string& text) {
  std::vector<aiVector3D> positions;
  size_t pos = 0;
  long lineNumber = 0, vertex = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++lineNumber;
    const size_t start = text.find_first_not_of(" \t", pos);
    if (start < end && text[start] == 'v' && start + 1 < end && (text[start + 1] == ' ' || text[start + 1] == '\t')) {
      ++vertex;
      const std::string rest = text.substr(start + 2, end - start - 2);
      std::istringstream coords(rest);
      aiVector3D p;
      for (int k = 0; k < 3; ++k) {
        std::string item;
        if (!(coords >> item)) break;
        char* stop = nullptr;
        const double x = std::strtod(item.c_str(), &stop);
        if (stop != item.c_str() && !std::isfinite(x)) {
          throw InvalidInput("mesh " + quoted(path) + ": line " + std::to_string(lineNumber) + ": vertex " + std::to_string(vertex) +
                             " has a coordinate that is not a finite number (" + abbreviate(item, 40) + ")");
        }
        // Correctly rounded to float, as assimp's parser rounds the usual short decimals; where
        // it rounds otherwise, the positions do not match and assimp's own soup is kept.
        p[k] = std::strtof(item.c_str(), nullptr);
      }
      positions.push_back(p);
    }
    pos = end + 1;
  }
  return positions;
}

// OBJ shares vertices between faces, but assimp's importer gives every face corner a vertex of
// its own: every clean OBJ then "merged N duplicate vertices", and messages named vertices by
// assimp's numbers (an edge (752, 758) in a 626-vertex file). This rebuilds the soup in the
// file's numbering (0-based: vertex k is the file's (k+1)-th "v" line) by matching assimp's
// positions with the file's (parsed as floats, as assimp stores them). False (and `soup` untouched) when a
// position does not match or a node carries a transform: the caller keeps assimp's soup.
bool objSoupInFileOrder(const aiScene& scene, const std::vector<aiVector3D>& filePositions, double scale, TriangleSoup& soup) {
  struct KeyHash {
    size_t operator()(const std::array<uint32_t, 3>& k) const {
      return (static_cast<size_t>(k[0]) * 0x9E3779B97F4A7C15ull) ^ (static_cast<size_t>(k[1]) * 0xC2B2AE3D27D4EB4Full) ^ k[2];
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
  for (size_t i = 0; i < filePositions.size(); ++i) index.emplace(key(filePositions[i]), static_cast<int>(i));
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
          out.triangles.push_back({fileIndex[face.mIndices[0]], fileIndex[face.mIndices[1]], fileIndex[face.mIndices[2]]});
      }
    }
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back(node->mChildren[c]);
  }
  out.vertices.reserve(filePositions.size());
  for (const auto& p : filePositions) out.vertices.push_back(scale * Eigen::Vector3d(p.x, p.y, p.z));
  soup = std::move(out);
  return true;
}

// glTF / GLB: the JSON nested at most kMaxGltfJsonDepth levels, and the node hierarchy (children
// indices) at most kMaxGltfNodeDepth deep and without cycles; a file of 200,000 nested nodes
// overflowed the stack inside assimp.
void checkGltfJson(const fs::path& path, const std::string& jsonText) {
  const JsonCheck check = checkJsonText(jsonText, kMaxGltfJsonDepth);
  if (!check.ok) {
    if (check.problem.rfind("nested deeper", 0) == 0)
      throw IoError("cannot read mesh " + quoted(path) + ": its JSON is " + check.problem + " (at " + check.path + ")");
    return;  // not valid JSON: assimp reports it
  }
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(jsonText);
  } catch (const nlohmann::json::exception&) {
    return;
  }
  if (!document.is_object()) return;
  // Accessors: assimp sizes its buffers by componentType and count before checking them against
  // the data (a GLB accessor without a componentType asked for gigabytes).
  if (document.contains("accessors") && document["accessors"].is_array()) {
    size_t k = 0;
    for (const auto& accessor : document["accessors"]) {
      const std::string name = "accessor " + std::to_string(k++);
      if (!accessor.is_object()) throw IoError("cannot read mesh " + quoted(path) + ": " + name + " is not an object");
      const auto& type = accessor.contains("componentType") ? accessor["componentType"] : nlohmann::json();
      const bool knownType = type.is_number_integer() && std::set<long long>{5120, 5121, 5122, 5123, 5125, 5126}.count(type.get<long long>());
      if (!knownType) throw IoError("cannot read mesh " + quoted(path) + ": " + name + " has no valid componentType");
      const auto& count = accessor.contains("count") ? accessor["count"] : nlohmann::json();
      if (!count.is_number_integer() || count.get<long long>() < 0 || count.get<long long>() > 100000000LL)
        throw IoError("cannot read mesh " + quoted(path) + ": " + name + " needs a count between 0 and 100000000");
    }
  }
  if (!document.contains("nodes") || !document["nodes"].is_array()) return;
  const nlohmann::json& nodes = document["nodes"];
  const long long n = static_cast<long long>(nodes.size());
  std::vector<int> depth(static_cast<size_t>(n), 0);  // 0 = not reached yet
  std::vector<long long> stack;
  auto children = [&](long long i) -> std::vector<long long> {
    std::vector<long long> out;
    const auto& node = nodes[static_cast<size_t>(i)];
    if (!node.is_object() || !node.contains("children") || !node["children"].is_array()) return out;
    for (const auto& c : node["children"])
      if (c.is_number_integer() && c.get<long long>() >= 0 && c.get<long long>() < n) out.push_back(c.get<long long>());
    return out;
  };
  // Depth of every node from each node no one refers to; a node reached twice on one path is a cycle.
  std::vector<char> isChild(static_cast<size_t>(n), 0);
  for (long long i = 0; i < n; ++i)
    for (long long c : children(i)) isChild[static_cast<size_t>(c)] = 1;
  long long visits = 0;
  for (long long r = 0; r < n; ++r) {
    if (isChild[static_cast<size_t>(r)]) continue;
    depth[static_cast<size_t>(r)] = 1;
    stack.assign(1, r);
    while (!stack.empty()) {
      const long long i = stack.back();
      stack.pop_back();
      if (++visits > 4 * n + 16)
        throw IoError("cannot read mesh " + quoted(path) + ": its node hierarchy has a cycle or shared subtrees");
      for (long long c : children(i)) {
        const int d = depth[static_cast<size_t>(i)] + 1;
        if (d > kMaxGltfNodeDepth)
          throw IoError("cannot read mesh " + quoted(path) + ": its nodes nest deeper than " + std::to_string(kMaxGltfNodeDepth) +
                        " levels (node " + std::to_string(c) + ")");
        depth[static_cast<size_t>(c)] = d;
        stack.push_back(c);
      }
    }
  }
  for (long long i = 0; i < n; ++i)
    if (isChild[static_cast<size_t>(i)] && depth[static_cast<size_t>(i)] == 0)
      throw IoError("cannot read mesh " + quoted(path) + ": its node hierarchy has a cycle (node " + std::to_string(i) + ")");
}

void checkGlb(const fs::path& path, const std::string& data) {
  // Header: magic "glTF", version, length; first chunk: length, type "JSON", the JSON text.
  if (data.size() < 20 || data.compare(0, 4, "glTF") != 0) return;
  // Assimp allocates by these lengths before it reads: a chunk length of 4 GB in a 648-byte file
  // took seconds and gigabytes. Lengths beyond the file are refused here.
  uint32_t totalLength = 0, chunkLength = 0;
  std::memcpy(&totalLength, data.data() + 8, 4);
  std::memcpy(&chunkLength, data.data() + 12, 4);
  if (totalLength > data.size() || chunkLength > data.size() - 20)
    throw IoError("cannot read mesh " + quoted(path) + ": its GLB header declares more bytes than the file's " +
                  std::to_string(data.size()));
  if (data.compare(16, 4, "JSON") != 0) return;
  checkGltfJson(path, data.substr(20, chunkLength));
}

// The checks above, by extension; the whole file is read once (the size is bounded). Returns
// the vertex positions of an OBJ file (empty for other formats).
std::vector<aiVector3D> precheckMeshFile(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".ply") {
    checkRegularInputFile(path, kMaxMeshFileBytes, "mesh file");
    return {};
  }
  const std::string text = readRegularFile(path, kMaxMeshFileBytes, "mesh file");
  if (ext == ".off") checkOffFile(path, text);
  if (ext == ".ply") checkPlyFile(path, text);
  if (ext == ".gltf") checkGltfJson(path, text);
  if (ext == ".glb") checkGlb(path, text);
  if (ext == ".obj") return checkObjFile(path, text);
  return {};
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
    const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? position_ : buffer_.size();
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
    if (mode == nullptr || (std::strchr(mode, 'w') == nullptr && std::strchr(mode, 'a') == nullptr)) return nullptr;
    auto& entry = files_[file];
    if (entry.second == 0) entry.second = ++order_;
    entry.first.clear();
    return new MemoryStream(entry.first);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
  // Files in the order they were first opened.
  std::vector<std::pair<std::string, const std::string*>> files() const {
    std::vector<std::pair<int, std::pair<std::string, const std::string*>>> ordered;
    for (const auto& [name, entry] : files_) ordered.push_back({entry.second, {name, &entry.first}});
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
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
  // Not a regular file (a FIFO would block assimp forever), too large, or what assimp takes wrongly.
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
                      (scene->mNumMeshes > 1 ? " of mesh " + std::to_string(m) : std::string()) + " has no vertices");
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate);
  if (scene == nullptr) failed();
  TriangleSoup soup;
  long ignoredPrimitives = 0;
  if (scene->mRootNode != nullptr)
    collectNodes(*scene, *scene->mRootNode, options.scale_to_m, soup, ignoredPrimitives);
  if (!objPositions.empty() && scene->mRootNode != nullptr && !soup.triangles.empty())
    objSoupInFileOrder(*scene, objPositions, options.scale_to_m, soup);
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
  checkedOutputTarget(target);  // a device, a FIFO or a folder is refused before the work
  // Leftovers of earlier versions, which exported into .egg-write-PID-N folders.
  removeDeadLeftovers(directory, ".egg-write-", true);

  const auto scene = sceneFromSoup(soup, options.scale_from_m);
  Assimp::Exporter exporter;
  auto* memory = new MemoryIOSystem;  // owned by the exporter
  exporter.SetIOHandler(memory);
  const char* id = options.binary ? format->assimpId : format->assimpIdText;
  if (exporter.Export(scene.get(), id, target.string()) != aiReturn_SUCCESS) {
    std::string reason = exporter.GetErrorString();
    throw WriteError("cannot write mesh " + quoted(path) + ": " + (reason.empty() ? "the exporter failed" : reason));
  }
  auto produced = memory->files();
  // The main file last, so it never refers to a companion file (glTF's .bin) that is not there yet.
  std::stable_partition(produced.begin(), produced.end(), [&](const auto& f) { return fs::path(f.first) != target; });
  for (const auto& [name, bytes] : produced) {
    const fs::path file(name);
    if (file.parent_path() != directory)
      throw WriteError("cannot write mesh " + quoted(path) + ": the exporter asked for a file elsewhere (" + quoted(file) + ")");
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
