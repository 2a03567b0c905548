// Typed reading of one JSON object with messages "FILE: WHERE what. Fix: ...", shared by the
// scene loader and media/medium_json.cpp so every input file reports errors the same way.
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <utility>

#include "geometry/mesh_structure.h"  // requireRegularFile
#include "util/errors.h"
#include "util/vec3.h"

namespace radkit {

/// Reads typed fields of one JSON object and rejects keys nobody asked for. Every failure
/// throws InputError naming the file and `where` (e.g. "surfaces[2]"). Holds references: the
/// object and the file name must outlive it.
class ObjectReader {
 public:
  using json = nlohmann::json;

  ObjectReader(const json& object, std::string where, const std::string& file)
      : m_object(object), m_where(std::move(where)), m_file(file) {
    if (!m_object.is_object()) fail("must be a JSON object");
  }

  /// Rejects every key not in `known`; called first, so a misspelt key is what the user
  /// hears about rather than the missing key it was meant to be.
  void allowOnly(std::initializer_list<const char*> known) const {
    for (auto it = m_object.begin(); it != m_object.end(); ++it)
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return it.key() == k; })) {
        std::string list;
        for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
        fail("has an unknown key \"" + it.key() + "\". Fix: use one of: " + list);
      }
  }
  bool has(const std::string& key) const { return m_object.contains(key); }
  const json& get(const std::string& key) {
    if (!has(key))
      fail("is missing the required key \"" + key + "\". Fix: add \"" + key +
           "\" (docs/formats.md lists every key)");
    return m_object.at(key);
  }
  std::string string(const std::string& key, const std::string& fallback) {
    if (!has(key)) return fallback;
    if (!m_object.at(key).is_string()) fail("\"" + key + "\" must be a string");
    return m_object.at(key).get<std::string>();
  }
  double number(const std::string& key, double fallback) {
    if (!has(key)) return fallback;
    return toNumber(m_object.at(key), key);
  }
  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    if (!m_object.at(key).is_boolean()) fail("\"" + key + "\" must be true or false");
    return m_object.at(key).get<bool>();
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback) {
    if (!has(key)) return fallback;
    return toVec3(m_object.at(key), key);
  }
  Vec3 toVec3(const json& j, const std::string& what) {
    if (!j.is_array() || j.size() != 3) fail("\"" + what + "\" must be an array of 3 numbers");
    return {toNumber(j[0], what), toNumber(j[1], what), toNumber(j[2], what)};
  }
  double toNumber(const json& j, const std::string& what) {
    // JSON has no NaN or infinity literals; a number too large for a double parses to inf.
    if (!j.is_number()) fail("\"" + what + "\" must be a number");
    double v = j.get<double>();
    if (!std::isfinite(v)) fail("\"" + what + "\" is not a finite number");
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const {
    const bool stop = !what.empty() && what.back() == '.';  // a nested message ends in its own
    throw InputError(m_file + ": " + m_where + " " + what + (stop ? "" : "."));
  }
  const std::string& where() const { return m_where; }

 private:
  const json& m_object;
  std::string m_where;
  const std::string& m_file;
};

/// The JSON document in `path`; `what` names it in errors ("scene file"). A missing file,
/// malformed JSON (nlohmann's message carries the line and column) and numbers that do not fit
/// a double throw InputError naming the file.
inline nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
  requireRegularFile(path, what);  // a FIFO would block the read forever
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the " + what + ". Fix: check the path.");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    // No parse callback here: nlohmann's callback parser rescans the parent object at every
    // object's end, quadratic in a scene of 80 000 materials.
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path + ": malformed JSON: " + e.what());
  } catch (const nlohmann::json::exception& e) {
    // Parsed again only to name the value nlohmann refuses (a number too large for a double):
    // the last key read before the failure.
    std::string key;
    const auto lastKey = [&key](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
      if (event == nlohmann::json::parse_event_t::key) key = parsed.get<std::string>();
      return true;
    };
    try {
      const nlohmann::json ignored = nlohmann::json::parse(text, lastKey);
    } catch (const nlohmann::json::exception&) {
    }
    throw InputError(path + ": unreadable JSON (" + e.what() + ")" +
                     (key.empty() ? "" : " in \"" + key + "\"") +
                     ". Fix: numbers must fit a double.");
  }
}

}  // namespace radkit
