// Checks of a mesh file before assimp reads it (see mesh_precheck.hpp).
#include "core/io/mesh_precheck.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/json_check.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

namespace egg {
namespace fs = std::filesystem;
namespace {

using mesh_precheck::lowerExtension;
using mesh_precheck::quoted;

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
    if (text.empty() || text.size() > 10 ||
        text.find_first_not_of("0123456789") != std::string::npos)
      throw IoError("cannot read mesh " + quoted(path) +
                    ": the OFF header's vertex and face counts must be numbers below 2^31, got " +
                    abbreviate(first, 40) + " " + abbreviate(second, 40));
    const long long value = std::stoll(text);
    if (value > 0x7fffffffLL)
      throw IoError("cannot read mesh " + quoted(path) + ": the OFF header's count " + text +
                    " is too large");
    return value;
  };
  const long long vertices = count(first), faces = count(second);
  if (vertices < 0 || faces < 0)
    throw IoError("cannot read mesh " + quoted(path) +
                  ": negative vertex or face count in the OFF header");
  // Assimp reserves by these counts; every vertex and face takes at least two bytes of the file.
  if (static_cast<unsigned long long>(vertices) + static_cast<unsigned long long>(faces) >
      text.size() / 2 + 1)
    throw IoError("cannot read mesh " + quoted(path) + ": the header declares " +
                  std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                  " faces, more than the file's " + std::to_string(text.size()) +
                  " bytes can hold");
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
        throw IoError("cannot read mesh " + quoted(path) + ": line " + std::to_string(lineNumber) +
                      ": face " + std::to_string(f) + " lists " + std::to_string(count) +
                      " vertices but gives fewer indices");
      }
      if (index < 0 || index >= vertices) {
        throw IoError("cannot read mesh " + quoted(path) + ": line " + std::to_string(lineNumber) +
                      ": face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                      ", but the file has vertices 0 .. " + std::to_string(vertices - 1));
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
    throw IoError("cannot read mesh " + quoted(path) + ": PLY header line " + std::to_string(line) +
                  ": " + why);
  };
  static const std::set<std::string> types{
      "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
      "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
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
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
        fail(lineNumber, "a control character in the header");
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
      if (e.name.empty() || count.empty() || count.size() > 19 ||
          count.find_first_not_of("0123456789") != std::string::npos)
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
        if (!types.count(countType) || !types.count(itemType))
          fail(lineNumber, "unknown list type");
        if (format != "ascii") bytes = typeSize(countType);
      } else {
        words >> name;
        if (!types.count(type)) fail(lineNumber, "unknown property type " + abbreviate(type, 40));
        if (format != "ascii") bytes = typeSize(type);
      }
      if (name.empty()) fail(lineNumber, "a property needs a name");
      elements.back().minBytes += bytes;
    } else {
      fail(lineNumber, "unknown keyword " + abbreviate(word, 40) +
                           " (expected element, property, comment or end_header)");
    }
  }
  if (!ended)
    throw IoError("cannot read mesh " + quoted(path) + ": the PLY header has no end_header line");
  if (format.empty())
    throw IoError("cannot read mesh " + quoted(path) + ": the PLY header has no format line");
  // Every element takes at least a few bytes in the body (ASCII: a digit and a separator per
  // property; binary: the sizes of its properties), so the counts are bounded by the file's size.
  const unsigned long long body = text.size() - std::min(pos, text.size());
  for (const Element& e : elements) {
    const unsigned long long perElement = std::max<unsigned long long>(e.minBytes, 1);
    if (e.count > body / perElement + 1) {
      throw IoError("cannot read mesh " + quoted(path) + ": the header declares " +
                    std::to_string(e.count) + " " + abbreviate(e.name, 40) +
                    " elements, more than the file's " + std::to_string(body) +
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
    if (start < end && text[start] == 'v' && start + 1 < end &&
        (text[start + 1] == ' ' || text[start + 1] == '\t')) {
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
          throw InvalidInput("mesh " + quoted(path) + ": line " + std::to_string(lineNumber) +
                             ": vertex " + std::to_string(vertex) +
                             " has a coordinate that is not a finite number (" +
                             abbreviate(item, 40) + ")");
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

// glTF / GLB: the JSON nested at most kMaxGltfJsonDepth levels, and the node hierarchy (children
// indices) at most kMaxGltfNodeDepth deep and without cycles; a file of 200,000 nested nodes
// overflowed the stack inside assimp.
void checkGltfJson(const fs::path& path, const std::string& jsonText) {
  const JsonCheck check = checkJsonText(jsonText, kMaxGltfJsonDepth);
  if (!check.ok) {
    if (check.problem.rfind("nested deeper", 0) == 0)
      throw IoError("cannot read mesh " + quoted(path) + ": its JSON is " + check.problem +
                    " (at " + check.path + ")");
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
      if (!accessor.is_object())
        throw IoError("cannot read mesh " + quoted(path) + ": " + name + " is not an object");
      const auto& type =
          accessor.contains("componentType") ? accessor["componentType"] : nlohmann::json();
      const bool knownType =
          type.is_number_integer() &&
          std::set<long long>{5120, 5121, 5122, 5123, 5125, 5126}.count(type.get<long long>());
      if (!knownType)
        throw IoError("cannot read mesh " + quoted(path) + ": " + name +
                      " has no valid componentType");
      const auto& count = accessor.contains("count") ? accessor["count"] : nlohmann::json();
      if (!count.is_number_integer() || count.get<long long>() < 0 ||
          count.get<long long>() > 100000000LL)
        throw IoError("cannot read mesh " + quoted(path) + ": " + name +
                      " needs a count between 0 and 100000000");
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
      if (c.is_number_integer() && c.get<long long>() >= 0 && c.get<long long>() < n)
        out.push_back(c.get<long long>());
    return out;
  };
  // Depth of every node from each node no one refers to; a node reached twice on one path is a
  // cycle.
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
        throw IoError("cannot read mesh " + quoted(path) +
                      ": its node hierarchy has a cycle or shared subtrees");
      for (long long c : children(i)) {
        const int d = depth[static_cast<size_t>(i)] + 1;
        if (d > kMaxGltfNodeDepth)
          throw IoError("cannot read mesh " + quoted(path) + ": its nodes nest deeper than " +
                        std::to_string(kMaxGltfNodeDepth) + " levels (node " + std::to_string(c) +
                        ")");
        depth[static_cast<size_t>(c)] = d;
        stack.push_back(c);
      }
    }
  }
  for (long long i = 0; i < n; ++i)
    if (isChild[static_cast<size_t>(i)] && depth[static_cast<size_t>(i)] == 0)
      throw IoError("cannot read mesh " + quoted(path) + ": its node hierarchy has a cycle (node " +
                    std::to_string(i) + ")");
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
    throw IoError("cannot read mesh " + quoted(path) +
                  ": its GLB header declares more bytes than the file's " +
                  std::to_string(data.size()));
  if (data.compare(16, 4, "JSON") != 0) return;
  checkGltfJson(path, data.substr(20, chunkLength));
}

// The checks above, by extension; the whole file is read once (the size is bounded). Returns
// the vertex positions of an OBJ file (empty for other formats).
}  // namespace

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

}  // namespace egg
