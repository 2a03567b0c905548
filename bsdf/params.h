// BsdfParams: a material's own parameters (pbrt-v4's ParameterDictionary). A BSDF reads each
// key once with its default beside it; the registry rejects the keys no BSDF read, so a typo
// in a scene file is an error that names the keys the BSDF knows.
#pragma once

#include <initializer_list>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vec3.h"

namespace radkit {

/// A parameter that is missing its key's type or range; the scene loader prefixes the file
/// and the material.
class BsdfParamError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class BsdfParams {
 public:
  /// A value: one number, an RGB triple, or a name.
  struct Value {
    std::vector<double> numbers;
    std::string text;
    bool isText = false;
  };

  BsdfParams() = default;
  /// \brief Parses "key=v, key=r g b, key=name" (the registry's examples, tests).
  static BsdfParams parse(const std::string& text);

  void set(const std::string& key, double v) { m_values[key] = Value{{v}, {}, false}; }
  void set(const std::string& key, const Vec3& v) {
    m_values[key] = Value{{v.x, v.y, v.z}, {}, false};
  }
  void setText(const std::string& key, const std::string& v) { m_values[key] = Value{{}, v, true}; }

  bool has(const std::string& key) const { return m_values.count(key) > 0; }
  bool empty() const { return m_values.empty(); }
  const std::map<std::string, Value>& values() const { return m_values; }

  /// \brief A finite number, or defaultValue when absent; throws BsdfParamError otherwise.
  double number(const std::string& key, double defaultValue);
  /// \brief A number in [lo, hi] (an open end when its flag is set), or defaultValue.
  double number(const std::string& key, double defaultValue, double lo, double hi,
                bool openLo = false, bool openHi = false, const std::string& fix = "");
  /// \brief An RGB triple of finite numbers (a single number is grey), or defaultValue.
  Vec3 rgb(const std::string& key, const Vec3& defaultValue);
  /// \brief The first of several synonyms given ("kd" or "reflectance"); giving two is an error.
  Vec3 rgb(std::initializer_list<const char*> keys, const Vec3& defaultValue);
  /// \brief A name, or defaultValue when absent.
  std::string text(const std::string& key, const std::string& defaultValue);

  /// \brief Each channel of an albedo read as `key` must lie in [0, 1): 1 makes the radiosity
  ///        system singular.
  static void checkAlbedo(const std::string& key, const Vec3& value);
  /// \brief Each channel in [0, 1].
  static void checkUnit(const std::string& key, const Vec3& value);

  /// \brief Throws BsdfParamError naming every key that was never read, and the keys that were.
  void rejectUnused(const std::string& bsdfName) const;

 private:
  const Value* find(const std::string& key);
  std::map<std::string, Value> m_values;
  std::set<std::string> m_read;
};

}  // namespace radkit
