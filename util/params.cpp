#include "util/params.h"

#include "util/format.h"

#include <cmath>
#include <sstream>

namespace radkit {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

const char* kChannel[] = {"red", "green", "blue"};

}  // namespace

Params::Params(const std::map<std::string, double>& numbers) {
  for (const auto& [key, v] : numbers) set(key, v);
}

Params Params::parse(const std::string& text) {
  Params p;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    item = trim(item);
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw ParamError("parameter \"" + item + "\" is not key=value");
    const std::string key = trim(item.substr(0, eq));
    std::istringstream in(item.substr(eq + 1));
    Value v;
    std::string word;
    while (in >> word) {
      char* end = nullptr;
      const double d = std::strtod(word.c_str(), &end);
      if (end && *end == '\0')
        v.numbers.push_back(d);
      else
        v.text = word, v.isText = true;
    }
    if (key.empty())
      throw ParamError("parameter \"" + item + "\" has no key. Fix: write key=value");
    if (!v.isText && v.numbers.empty())
      throw ParamError("parameter \"" + key + "\" has no value. Fix: write key=value");
    if (v.isText && !v.numbers.empty())
      throw ParamError("parameter \"" + key + "\" mixes numbers and names");
    if (!p.m_values.emplace(key, v).second)
      throw ParamError("\"" + key + "\" is given twice. Fix: keep one");
  }
  return p;
}

const Params::Value* Params::find(const std::string& key) {
  m_read.insert(key);
  auto it = m_values.find(key);
  return it == m_values.end() ? nullptr : &it->second;
}

double Params::number(const std::string& key, double defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  if (v->isText || v->numbers.size() != 1 || !std::isfinite(v->numbers[0]))
    throw ParamError("\"" + key + "\" must be one finite number. Fix: write it as a plain number");
  return v->numbers[0];
}

double Params::number(const std::string& key, double defaultValue, double lo, double hi,
                      bool openLo, bool openHi, const std::string& fix) {
  const double x = number(key, defaultValue);
  const bool ok = (openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi);
  if (!ok)
    throw ParamError("\"" + key + "\" " + formatNumber(x) + " is outside " + (openLo ? "(" : "[") +
                     formatNumber(lo) + ", " + formatNumber(hi) + (openHi ? ")" : "]") +
                     ". Fix: " + (fix.empty() ? "use a value in that range" : fix));
  return x;
}

long Params::integer(const std::string& key, long defaultValue, long lo, long hi) {
  const double x = number(key, static_cast<double>(defaultValue));
  if (!(x >= static_cast<double>(lo) && x <= static_cast<double>(hi)) || x != std::floor(x))
    throw ParamError("\"" + key + "\" " + formatNumber(x) + " is not a whole number in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) +
                     "]. Fix: use a whole number in that range");
  return static_cast<long>(x);
}

Vec3 Params::rgb(const std::string& key, const Vec3& defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  const bool shape = !v->isText && (v->numbers.size() == 1 || v->numbers.size() == 3);
  bool finite = shape;
  for (double d : v->numbers) finite = finite && std::isfinite(d);
  if (!finite)
    throw ParamError("\"" + key +
                     "\" must be an RGB triple [r, g, b] of finite numbers. Fix: write [r, g, "
                     "b], or one number for grey");
  if (v->numbers.size() == 1) return Vec3{1, 1, 1} * v->numbers[0];
  return {v->numbers[0], v->numbers[1], v->numbers[2]};
}

Vec3 Params::rgb(std::initializer_list<const char*> keys, const Vec3& defaultValue) {
  const char* given = nullptr;
  for (const char* key : keys) {
    m_read.insert(key);
    if (!has(key)) continue;
    if (given)
      throw ParamError("gives both \"" + std::string(given) + "\" and \"" + key +
                       "\": they are the same. Fix: keep one");
    given = key;
  }
  return given ? rgb(given, defaultValue) : defaultValue;
}

std::string Params::text(const std::string& key, const std::string& defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  if (!v->isText) throw ParamError("\"" + key + "\" must be a name. Fix: write it as a string");
  return v->text;
}

void Params::checkAlbedo(const std::string& key, const Vec3& value) {
  for (int c = 0; c < 3; ++c)
    if (!(value[c] >= 0 && value[c] < 1))
      throw ParamError(
          "\"" + key + "\" " + formatNumber(value[c]) + " (" + kChannel[c] +
          ") is outside [0, 1). Fix: use a value below 1; a reflectance of 1 makes the "
          "radiosity system singular.");
}

void Params::checkUnit(const std::string& key, const Vec3& value) {
  for (int c = 0; c < 3; ++c)
    if (!(value[c] >= 0 && value[c] <= 1))
      throw ParamError("\"" + key + "\" " + formatNumber(value[c]) + " (" + kChannel[c] +
                       ") is outside [0, 1]. Fix: use a value between 0 and 1");
}

void Params::rejectUnused(const std::string& owner) const {
  std::string unknown, known;
  for (const auto& [key, value] : m_values)
    if (!m_read.count(key)) unknown += (unknown.empty() ? "\"" : ", \"") + key + "\"";
  if (unknown.empty()) return;
  for (const std::string& key : m_read) known += (known.empty() ? "" : ", ") + key;
  throw ParamError("gives " + unknown + ", which " + owner + " does not use. Fix: " + owner +
                   (known.empty() ? " has no parameters" : " reads " + known));
}

PluginChoice splitPluginChoice(const std::string& text) {
  const std::size_t colon = text.find(':');
  PluginChoice choice{text.substr(0, colon), ""};
  if (colon != std::string::npos) choice.parameters = text.substr(colon + 1);
  for (char& c : choice.parameters)
    if (c == ';') c = ',';
  return choice;
}

}  // namespace radkit
