#pragma once
// Reading one object of a JSON input file (the scene) key by key: typed values with ranges, the
// dotted path of every key for messages ("scene.json: grid.alpha_bar: ..."), and every key left
// unread reported as unknown, so that a typo never passes silently.
#include "core/errors.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <set>
#include <string>

namespace egg::pipeline {

// A JSON value for a message: at most ~`limit` characters, never recursing deeper than a few
// levels, so that a huge or deeply nested value neither floods stderr nor overflows the stack.
std::string brief(const nlohmann::json& value, std::size_t limit = 200);

class JsonSection {
 public:
  // Throws InvalidInput when `node` is not an object.
  JsonSection(const nlohmann::json& node, std::string path, std::string origin);

  // Throws InvalidInput "origin: path.key: what".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  std::string dotted(const std::string& key) const;

  // Whether the key is present (and marks it as known).
  bool has(const std::string& key);
  const nlohmann::json& raw(const std::string& key);

  // Each returns `fallback` when the key is absent and throws InvalidInput naming the key when the
  // value has another type or lies outside the range.
  double number(const std::string& key, double fallback, double lo, double hi);
  double positive(const std::string& key, double fallback, double hi = 1e9);  // in (0, hi]
  int integer(const std::string& key, int fallback, int lo, int hi);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  std::array<double, 2> pair(const std::string& key, std::array<double, 2> fallback, double lo,
                             double hi);
  // The object under `key` (an empty one when absent).
  JsonSection child(const std::string& key);

  // Call after reading: every key present must have been asked for.
  void rejectUnknownKeys() const;

 private:
  const nlohmann::json& node_;
  std::string path_;
  std::string origin_;
  std::set<std::string> known_;
};

}  // namespace egg::pipeline
