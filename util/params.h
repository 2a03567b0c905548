// Params: the parameters of one plugin (a BSDF, a solver, a phase function), as pbrt-v4's
// ParameterDictionary. The plugin reads each key once with its default and range beside it;
// its registry (util/registry.h) then rejects the keys nobody read, so a typo in a scene file
// or on the command line is an error that names the keys the plugin knows.
#pragma once

#include <initializer_list>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/vec3.h"

namespace radkit {

/// A parameter of the wrong type or outside its range, or a key nobody read. The message names
/// the key and the fix; the caller prefixes where it was given (the file and the material, the
/// solver's name).
class ParamError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Params {
 public:
  /// A value: one number, an RGB triple, or a name.
  struct Value {
    std::vector<double> numbers;
    std::string text;
    bool isText = false;
  };

  Params() = default;
  /// Numbers by key (tests, the Python module): Params({{"omega", 1.2}}).
  Params(const std::map<std::string, double>& numbers);
  /// \brief Parses "key=v, key=r g b, key=name": items separated by ',' (the command line's
  ///        "sor:omega=1.2;power_iterations=40" arrives with ';' turned into ','). A key given
  ///        twice is an error.
  static Params parse(const std::string& text);

  void set(const std::string& key, double v) { m_values[key] = Value{{v}, {}, false}; }
  void set(const std::string& key, const Vec3& v) {
    m_values[key] = Value{{v.x, v.y, v.z}, {}, false};
  }
  void setText(const std::string& key, const std::string& v) { m_values[key] = Value{{}, v, true}; }
  void set(const std::string& key, const Value& v) { m_values[key] = v; }

  bool has(const std::string& key) const { return m_values.count(key) > 0; }
  bool empty() const { return m_values.empty(); }
  const std::map<std::string, Value>& values() const { return m_values; }

  /// \brief A finite number, or defaultValue when absent; throws ParamError otherwise.
  double number(const std::string& key, double defaultValue);
  /// \brief A number in [lo, hi] (an open end when its flag is set), or defaultValue.
  double number(const std::string& key, double defaultValue, double lo, double hi,
                bool openLo = false, bool openHi = false, const std::string& fix = "");
  /// \brief A whole number in [lo, hi], or defaultValue (counts: iterations, samples).
  long integer(const std::string& key, long defaultValue, long lo, long hi);
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

  /// \brief Throws ParamError naming every key that was never read, and the keys that were;
  ///        owner is the plugin's name as the message should say it ("sor", "lambert").
  void rejectUnused(const std::string& owner) const;

 private:
  const Value* find(const std::string& key);
  std::map<std::string, Value> m_values;
  std::set<std::string> m_read;
};

/// A plugin as a command line names it, "name:key=value;key=value": ';' separates its
/// parameters because ',' separates the items of a list (--solvers jacobi,sor:omega=1.2).
struct PluginChoice {
  std::string name;
  std::string parameters;  ///< Params::parse's text, ';' turned into ','; empty for a name alone
};
/// \brief Splits a plugin choice at its first ':'.
PluginChoice splitPluginChoice(const std::string& text);

}  // namespace radkit
