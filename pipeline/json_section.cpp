#include "pipeline/json_section.hpp"

#include <algorithm>

#include "core/io/atomic_file.hpp"

#include <cmath>
#include <sstream>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// A JSON value for a message: at most ~200 characters, never recursing deeper than a few levels,
// so that a huge or deeply nested value neither floods stderr nor overflows the stack.
void renderBrief(const json& v, int depth, std::string& out, std::size_t limit) {
  if (out.size() > limit) return;
  if (v.is_string()) {
    const std::string& text = v.get_ref<const std::string&>();
    out += json(text.substr(0, limit)).dump(-1, ' ', false, json::error_handler_t::replace);
  } else if (v.is_array() || v.is_object()) {
    const bool array = v.is_array();
    out += array ? "[" : "{";
    if (depth >= 4 && !v.empty()) {
      out += "...";
    } else {
      bool first = true;
      for (auto it = v.begin(); it != v.end() && out.size() <= limit; ++it) {
        if (!first) out += ", ";
        first = false;
        if (!array)
          out +=
              json(it.key().substr(0, limit)).dump(-1, ' ', false, json::error_handler_t::replace) +
              ": ";
        renderBrief(it.value(), depth + 1, out, limit);
      }
    }
    out += array ? "]" : "}";
  } else {
    out += v.dump();
  }
}

}  // namespace

std::string brief(const json& v, std::size_t limit) {
  std::string out;
  renderBrief(v, 0, out, limit);
  if (out.size() > limit) out = out.substr(0, limit) + "...";
  return out;
}

JsonSection::JsonSection(const json& node, std::string path, std::string origin)
    : node_(node), path_(std::move(path)), origin_(std::move(origin)) {
  if (!node_.is_object()) fail("", "must be an object");
}

void JsonSection::fail(const std::string& key, const std::string& what) const {
  const std::string field = abbreviate(dotted(key));
  throw InvalidInput(abbreviate(origin_) + ": " + field + (field.empty() ? "" : ": ") + what,
                     origin_, dotted(key));
}

std::string JsonSection::dotted(const std::string& key) const {
  if (path_.empty()) return key;
  return key.empty() ? path_ : path_ + "." + key;
}

bool JsonSection::has(const std::string& key) {
  known_.insert(key);
  return node_.contains(key);
}

const json& JsonSection::raw(const std::string& key) {
  known_.insert(key);
  return node_.at(key);
}

double JsonSection::number(const std::string& key, double fallback, double lo, double hi) {
  if (!has(key)) return fallback;
  const json& v = node_.at(key);
  if (!v.is_number()) fail(key, "must be a number, got " + brief(v));
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    std::ostringstream msg;
    msg << "must lie in [" << lo << ", " << hi << "], got " << x;
    fail(key, msg.str());
  }
  return x;
}

double JsonSection::positive(const std::string& key, double fallback, double hi) {
  const double x = number(key, fallback, 0.0, hi);
  if (x <= 0.0) fail(key, "must be positive");
  return x;
}

int JsonSection::integer(const std::string& key, int fallback, int lo, int hi) {
  if (!has(key)) return fallback;
  const json& v = node_.at(key);
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + brief(v));
  // An unsigned above LLONG_MAX would wrap to a negative long long: compare it as unsigned.
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi))
    fail(key,
         "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + brief(v));
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                  std::to_string(x));
  return static_cast<int>(x);
}

bool JsonSection::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const json& v = node_.at(key);
  if (!v.is_boolean()) fail(key, "must be true or false, got " + brief(v));
  return v.get<bool>();
}

std::string JsonSection::text(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  const json& v = node_.at(key);
  if (!v.is_string()) fail(key, "must be a string, got " + brief(v));
  return v.get<std::string>();
}

std::array<double, 2> JsonSection::pair(const std::string& key, std::array<double, 2> fallback,
                                        double lo, double hi) {
  if (!has(key)) return fallback;
  const json& v = node_.at(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    fail(key, "must be an array of two numbers, got " + brief(v));
  }
  std::array<double, 2> out{v[0].get<double>(), v[1].get<double>()};
  for (double x : out) {
    if (!std::isfinite(x) || x < lo || x > hi)
      fail(key, "values must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return out;
}

JsonSection JsonSection::child(const std::string& key) {
  known_.insert(key);
  static const json empty = json::object();
  return JsonSection(node_.contains(key) ? node_.at(key) : empty, dotted(key), origin_);
}

void JsonSection::rejectUnknownKeys() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    // "$comment" (JSON Schema's spelling of a comment, which `egg init` writes) is a note to the
    // reader in any section: a string or an array of strings, never read.
    if (it.key() == "$comment") {
      const json& v = it.value();
      const bool text = v.is_string() ||
                        (v.is_array() && std::all_of(v.begin(), v.end(),
                                                     [](const json& x) { return x.is_string(); }));
      if (!text) fail(it.key(), "a comment must be a string or an array of strings");
      continue;
    }
    if (!known_.count(it.key())) {
      std::string allowed;
      for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      fail(it.key(), "unknown key (allowed here: " + allowed + ")");
    }
  }
}

}  // namespace egg::pipeline
