#pragma once
// Reading the SVG the figures write, in tests: elements by id, their attributes and text. Plain
// finds, no std::regex: libstdc++'s regex recurses per character and would overflow the stack on
// the long paths of a K map or a member layer.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace egg::test::svg {

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Occurrences of `needle`.
inline int count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

// The start tag of the element with id `id` ("" if none).
inline std::string element(const std::string& svg, const std::string& id) {
  const size_t at = svg.find(" id=\"" + id + "\"");
  if (at == std::string::npos) return "";
  const size_t open = svg.rfind('<', at), close = svg.find('>', at);
  return svg.substr(open, close - open + 1);
}

// Attribute `name` of the element with id `id`.
inline std::string attribute(const std::string& svg, const std::string& id,
                             const std::string& name) {
  const std::string tag = element(svg, id);
  const std::string key = " " + name + "=\"";
  const size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const size_t start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

// The text content of the element with id `id`.
inline std::string textOf(const std::string& svg, const std::string& id) {
  const std::string tag = element(svg, id);
  if (tag.empty()) return "";
  const size_t start = svg.find(tag) + tag.size();
  return svg.substr(start, svg.find('<', start) - start);
}

}  // namespace egg::test::svg
