#pragma once
// The field lists of the scene file: one entry per key (its name, where it lives in Scene, its
// range and one line of doc). The parser, sceneToJson, the error messages and the generated scene
// reference all read these lists, so adding a knob is one line in scene_fields.cpp.
#include "pipeline/json_section.hpp"
#include "pipeline/scene.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace egg::pipeline {

struct SceneField {
  std::string key;   // the JSON key, snake_case with its unit ("friction_mu", "kerf_mm")
  std::string type;  // for the reference: "number in [0, 2]", "true or false", ...
  std::string doc;   // one line: what it does, with the thesis section
  // Reads the key (absent: leaves the default) or throws InvalidInput naming it.
  std::function<void(JsonSection&, Scene&)> read;
  // Its value in the echo; std::nullopt leaves the key out (an unset optional, a key that does not
  // apply: a sample's edge length for a mesh file).
  std::function<std::optional<nlohmann::json>(const Scene&)> write;
  // What the key accepts, as a JSON Schema (draft 2020-12) fragment: the scene's schema
  // (`egg scene-schema`, docs/scene.schema.json) is generated from these, like the reference.
  nlohmann::json schema;
};

struct SceneSection {
  std::string key;  // "surface", ...; "" for the top-level keys
  std::string doc;
  std::vector<SceneField> fields;
  // Checks across keys once all are read (the margin against the sheet, ...); may be empty.
  std::function<void(JsonSection&, Scene&)> check;
};

// Every section in the order the parser reads them; the first is the top level (name, outputs).
const std::vector<SceneSection>& sceneSections();
// Appends lamella, simulation, fabrication, acceptance and loads (scene_fields_structure.cpp).
void addStructureSections(std::vector<SceneSection>& sections);

// Builders of the common kinds. `member` is a captureless lambda naming where the value lives,
// EGG_AT(simulation.rods.model.frictionMu) for short. The default is whatever Scene{} holds there.
#define EGG_AT(path) \
  [](::egg::pipeline::Scene & s) -> auto& { return s.path; }
namespace field {

template <class Member>
using ValueOf = std::remove_reference_t<std::invoke_result_t<Member, Scene&>>;

// A field's value for the echo.
template <class T>
std::optional<nlohmann::json> some(const T& value) {
  return nlohmann::json(value);
}

template <class Member>
auto writer(Member member) {
  return [member](const Scene& s) -> std::optional<nlohmann::json> {
    return nlohmann::json(member(const_cast<Scene&>(s)));
  };
}

// "[lo, hi]" and a number as the reference writes them.
std::string range(double lo, double hi);
std::string numberText(double x);
// "\"a\", \"b\" or \"c\"".
std::string alternatives(const std::vector<std::string>& names);

// Schema fragments of the common kinds.
nlohmann::json numberSchema(double lo, double hi);
nlohmann::json positiveSchema(double hi);
nlohmann::json integerSchema(long long lo, long long hi);
nlohmann::json pairSchema(double lo, double hi);
nlohmann::json stringSchema();

template <class Member>
SceneField number(std::string key, Member member, double lo, double hi, std::string doc) {
  const std::string k = key;
  return {
      std::move(key), "number in " + range(lo, hi),
      std::move(doc), [=](JsonSection& j, Scene& s) { member(s) = j.number(k, member(s), lo, hi); },
      writer(member), numberSchema(lo, hi)};
}

// A number in (0, hi].
template <class Member>
SceneField positive(std::string key, Member member, double hi, std::string doc) {
  const std::string k = key;
  return {
      std::move(key), "number in (0, " + numberText(hi) + "]",
      std::move(doc), [=](JsonSection& j, Scene& s) { member(s) = j.positive(k, member(s), hi); },
      writer(member), positiveSchema(hi)};
}

template <class Member>
SceneField integer(std::string key, Member member, int lo, int hi, std::string doc) {
  const std::string k = key;
  return {std::move(key),
          "integer in " + range(lo, hi),
          std::move(doc),
          [=](JsonSection& j, Scene& s) { member(s) = j.integer(k, member(s), lo, hi); },
          writer(member),
          integerSchema(lo, hi)};
}

template <class Member>
SceneField boolean(std::string key, Member member, std::string doc) {
  const std::string k = key;
  return {std::move(key), "true or false",
          std::move(doc), [=](JsonSection& j, Scene& s) { member(s) = j.boolean(k, member(s)); },
          writer(member), {{"type", "boolean"}}};
}

template <class Member>
SceneField pair(std::string key, Member member, double lo, double hi, std::string doc) {
  const std::string k = key;
  return {
      std::move(key), "two numbers in " + range(lo, hi),
      std::move(doc), [=](JsonSection& j, Scene& s) { member(s) = j.pair(k, member(s), lo, hi); },
      writer(member), pairSchema(lo, hi)};
}

// A std::optional<double>: absent keeps the derived default, named in `doc`.
template <class Member>
SceneField optionalNumber(std::string key, Member member, double lo, double hi, std::string doc) {
  const std::string k = key;
  return {std::move(key),
          "number in " + range(lo, hi) + ", optional",
          std::move(doc),
          [=](JsonSection& j, Scene& s) {
            if (j.has(k)) member(s) = j.number(k, 0.0, lo, hi);
          },
          [=](const Scene& s) -> std::optional<nlohmann::json> {
            const auto& value = member(const_cast<Scene&>(s));
            return value ? std::optional<nlohmann::json>(*value) : std::nullopt;
          },
          numberSchema(lo, hi)};
}

// An enum spelled by name: `names` lists every value with its spelling.
template <class Member>
SceneField choice(std::string key, Member member,
                  std::vector<std::pair<ValueOf<Member>, std::string>> names, std::string doc) {
  std::vector<std::string> spellings;
  for (const auto& entry : names) spellings.push_back(entry.second);
  const std::string spelled = alternatives(spellings);
  const std::string k = key;
  return {std::move(key),
          "one of " + spelled,
          std::move(doc),
          [=](JsonSection& j, Scene& s) {
            if (!j.has(k)) return;
            const std::string text = j.text(k, "");
            for (const auto& [value, name] : names)
              if (name == text) {
                member(s) = value;
                return;
              }
            j.fail(k, "must be " + spelled + ", got \"" + text + "\"");
          },
          [=](const Scene& s) -> std::optional<nlohmann::json> {
            const auto value = member(const_cast<Scene&>(s));
            for (const auto& [v, name] : names)
              if (v == value) return nlohmann::json(name);
            return std::nullopt;
          },
          {{"enum", spellings}}};
}

}  // namespace field
}  // namespace egg::pipeline
