#include "bsdf/params.h"

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

BsdfParams BsdfParams::parse(const std::string& text) {
  BsdfParams p;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    item = trim(item);
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw BsdfParamError("parameter \"" + item + "\" is not key=value");
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
    if (v.isText && !v.numbers.empty())
      throw BsdfParamError("parameter \"" + key + "\" mixes numbers and names");
    p.m_values[key] = v;
  }
  return p;
}

const BsdfParams::Value* BsdfParams::find(const std::string& key) {
  m_read.insert(key);
  auto it = m_values.find(key);
  return it == m_values.end() ? nullptr : &it->second;
}

double BsdfParams::number(const std::string& key, double defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  if (v->isText || v->numbers.size() != 1 || !std::isfinite(v->numbers[0]))
    throw BsdfParamError("\"" + key +
                         "\" must be one finite number. Fix: write it as a plain number");
  return v->numbers[0];
}

double BsdfParams::number(const std::string& key, double defaultValue, double lo, double hi,
                          bool openLo, bool openHi, const std::string& fix) {
  const double x = number(key, defaultValue);
  const bool ok = (openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi);
  if (!ok)
    throw BsdfParamError("\"" + key + "\" " + formatNumber(x) + " is outside " +
                         (openLo ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
                         (openHi ? ")" : "]") +
                         ". Fix: " + (fix.empty() ? "use a value in that range" : fix));
  return x;
}

Vec3 BsdfParams::rgb(const std::string& key, const Vec3& defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  const bool shape = !v->isText && (v->numbers.size() == 1 || v->numbers.size() == 3);
  bool finite = shape;
  for (double d : v->numbers) finite = finite && std::isfinite(d);
  if (!finite)
    throw BsdfParamError("\"" + key +
                         "\" must be an RGB triple [r, g, b] of finite numbers. Fix: write [r, g, "
                         "b], or one number for grey");
  if (v->numbers.size() == 1) return Vec3{1, 1, 1} * v->numbers[0];
  return {v->numbers[0], v->numbers[1], v->numbers[2]};
}

Vec3 BsdfParams::rgb(std::initializer_list<const char*> keys, const Vec3& defaultValue) {
  const char* given = nullptr;
  for (const char* key : keys) {
    m_read.insert(key);
    if (!has(key)) continue;
    if (given)
      throw BsdfParamError("gives both \"" + std::string(given) + "\" and \"" + key +
                           "\": they are the same. Fix: keep one");
    given = key;
  }
  return given ? rgb(given, defaultValue) : defaultValue;
}

std::string BsdfParams::text(const std::string& key, const std::string& defaultValue) {
  const Value* v = find(key);
  if (!v) return defaultValue;
  if (!v->isText) throw BsdfParamError("\"" + key + "\" must be a name. Fix: write it as a string");
  return v->text;
}

void BsdfParams::checkAlbedo(const std::string& key, const Vec3& value) {
  for (int c = 0; c < 3; ++c)
    if (!(value[c] >= 0 && value[c] < 1))
      throw BsdfParamError(
          "\"" + key + "\" " + formatNumber(value[c]) + " (" + kChannel[c] +
          ") is outside [0, 1). Fix: use a value below 1; a reflectance of 1 makes the "
          "radiosity system singular.");
}

void BsdfParams::checkUnit(const std::string& key, const Vec3& value) {
  for (int c = 0; c < 3; ++c)
    if (!(value[c] >= 0 && value[c] <= 1))
      throw BsdfParamError("\"" + key + "\" " + formatNumber(value[c]) + " (" + kChannel[c] +
                           ") is outside [0, 1]. Fix: use a value between 0 and 1");
}

void BsdfParams::rejectUnused(const std::string& bsdfName) const {
  std::string unknown, known;
  for (const auto& [key, value] : m_values)
    if (!m_read.count(key)) unknown += (unknown.empty() ? "\"" : ", \"") + key + "\"";
  if (unknown.empty()) return;
  for (const std::string& key : m_read) known += (known.empty() ? "" : ", ") + key;
  throw BsdfParamError("gives " + unknown + ", which " + bsdfName + " does not use. Fix: " +
                       bsdfName + (known.empty() ? " has no parameters" : " reads " + known));
}

}  // namespace radkit
