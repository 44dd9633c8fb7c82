#include "core/io/json_check.hpp"

#include "core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace egg {
namespace {

using nlohmann::json;

class ShapeScanner : public json::json_sax_t {
 public:
  explicit ShapeScanner(int maxDepth) : maxDepth_(maxDepth) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(string_t& k) override {
    if (!frames_.empty()) frames_.back().key = k.substr(0, 80);
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    result.ok = false;
    result.path = path();
    // 406: a number that overflows a double ("number overflow parsing '1e400'").
    result.problem = e.id == 406 ? "number out of range: " + abbreviate(e.what(), 120)
                                 : "not valid JSON: " + abbreviate(e.what(), 300);
    return false;
  }

  JsonCheck result;

 private:
  struct Frame {
    bool array;
    std::string key;
    std::size_t index;
  };

  // A value is complete: an array moves to its next index, an object forgets the key, so that a
  // syntax error after the value (a truncated file) is not blamed on the key before it.
  bool value() {
    if (frames_.empty()) return true;
    if (frames_.back().array)
      ++frames_.back().index;
    else
      frames_.back().key.clear();
    return true;
  }
  bool open(bool array) {
    if (static_cast<int>(frames_.size()) >= maxDepth_) {
      result.ok = false;
      result.path = path();
      result.problem =
          "nested deeper than " + std::to_string(maxDepth_) + " levels of objects and arrays";
      return false;
    }
    frames_.push_back({array, "", 0});
    return true;
  }
  bool close() {
    if (!frames_.empty()) frames_.pop_back();
    return value();
  }
  std::string path() const {
    std::string out;
    for (const auto& f : frames_) {
      if (f.array)
        out += "[" + std::to_string(f.index) + "]";
      else if (!f.key.empty())
        out += (out.empty() ? "" : ".") + abbreviate(f.key, 80);
      if (out.size() > 160) return out.substr(0, 160) + "...";
    }
    return out;
  }

  int maxDepth_;
  std::vector<Frame> frames_;
};

}  // namespace

JsonCheck checkJsonText(const std::string& text, int maxDepth) {
  ShapeScanner scanner(maxDepth);
  json::sax_parse(text, &scanner);
  return scanner.result;
}

}  // namespace egg
