#include "viewer/view_settings.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "render/radiosity_image.h"
#include "util/errors.h"
#include "util/setting_names.h"

namespace radkit::viewer {

ModeChoice parseMode(const std::string& text) {
  const std::string rowPrefix = "formfactors-row:";
  if (text == "radiosity") return {ViewMode::Radiosity, -1};
  if (text == "false-colour" || text == "false-color") return {ViewMode::FalseColour, -1};
  if (text == "matrix") return {ViewMode::Matrix, -1};
  if (text == "convergence") return {ViewMode::Convergence, -1};
  if (text.rfind(rowPrefix, 0) == 0) {
    const std::string id = text.substr(rowPrefix.size());
    if (!id.empty() && id.size() < 10 && std::all_of(id.begin(), id.end(), ::isdigit))
      return {ViewMode::FormFactorRow, std::stoi(id)};
    throw InputError(setting("mode") + " " + text +
                     ": the patch id after 'formfactors-row:' must be a number >= 0 "
                     "(patch ids are the id column of patches.csv)");
  }
  throw InputError(
      setting("mode") + " " + text +
      ": unknown mode; use radiosity, false-colour, formfactors-row:ID, matrix or convergence");
}

Channel parseChannel(const std::string& text) {
  if (text == "r" || text == "red") return Channel::Red;
  if (text == "g" || text == "green") return Channel::Green;
  if (text == "b" || text == "blue") return Channel::Blue;
  if (text == "l" || text == "luminance") return Channel::Luminance;
  throw InputError(setting("channel") + " " + text + ": unknown channel; use r, g, b or luminance");
}

std::string modeName(ViewMode mode) {
  switch (mode) {
    case ViewMode::Radiosity:
      return "radiosity";
    case ViewMode::FalseColour:
      return "false-colour";
    case ViewMode::FormFactorRow:
      return "formfactors-row";
    case ViewMode::Matrix:
      return "matrix";
    case ViewMode::Convergence:
      return "convergence";
  }
  return "?";
}

double autoExposure(const PatchData& patches) {
  // (luminance of L, area) of every non-emitting patch, sorted by luminance.
  std::vector<std::pair<double, double>> samples;
  double totalArea = 0;
  for (int i = 0; i < patches.size(); ++i) {
    if (patches.emits(i)) continue;
    samples.emplace_back(luminance(patches.radiosity[i]) / M_PI, patches.area[i]);
    totalArea += patches.area[i];
  }
  if (samples.empty() || totalArea <= 0) return 1;
  std::sort(samples.begin(), samples.end());
  double below = 0;
  for (const auto& [lum, area] : samples) {
    below += area;
    if (below >= 0.95 * totalArea) return lum > 0 ? 0.8 / lum : 1;
  }
  return samples.back().first > 0 ? 0.8 / samples.back().first : 1;
}

double falseColourTop(const PatchData& patches, const std::vector<double>& values) {
  std::vector<std::pair<double, double>> samples;  // (value, area) of non-emitters
  double totalArea = 0, top = 0;
  for (int i = 0; i < patches.size(); ++i)
    if (!patches.emits(i)) {
      samples.emplace_back(values[i], patches.area[i]);
      totalArea += patches.area[i];
    }
  std::sort(samples.begin(), samples.end());
  double below = 0;
  for (const auto& [value, area] : samples) {
    top = value;
    if ((below += area) >= 0.99 * totalArea) break;
  }
  if (!(top > 0))
    top = values.empty() ? 1 : std::max(1e-300, *std::max_element(values.begin(), values.end()));
  const double unit = std::pow(10.0, std::floor(std::log10(top)) - 1);  // two significant digits
  return std::ceil(top / unit - 1e-9) * unit;
}

std::array<std::uint8_t, 3> trueColour(const Vec3& radiosity, double exposure) {
  const Vec3 v = radiosity * (exposure / M_PI);  // L = B/π for a Lambertian surface
  auto byte = [](double t) { return std::uint8_t(std::lround(255 * srgbEncode(t))); };
  return {byte(v.x), byte(v.y), byte(v.z)};
}

double channelValue(const Vec3& b, Channel channel, bool photometric) {
  if (photometric) return kLumensPerWatt * luminance(b) / M_PI;  // cd/m² = lm/(m² sr)
  switch (channel) {
    case Channel::Red:
      return b.x;
    case Channel::Green:
      return b.y;
    case Channel::Blue:
      return b.z;
    case Channel::Luminance:
      return luminance(b);
  }
  return 0;
}

std::string channelLabel(Channel channel, bool photometric) {
  if (photometric) return "luminance (cd/m²)";
  switch (channel) {
    case Channel::Red:
      return "radiosity B_r (W/m²)";
    case Channel::Green:
      return "radiosity B_g (W/m²)";
    case Channel::Blue:
      return "radiosity B_b (W/m²)";
    case Channel::Luminance:
      return "radiosity Y(B) (W/m²)";
  }
  return "";
}

MatrixCells downsampleMatrix(const FormFactorRows& f, int maxCells) {
  MatrixCells m;
  m.block = std::max(1, (f.n + maxCells - 1) / maxCells);
  m.cells = (f.n + m.block - 1) / m.block;
  m.value.assign(std::size_t(m.cells) * m.cells, 0.0);
  for (int i = 0; i < f.n; ++i)
    for (long long k = f.rowStart[i]; k < f.rowStart[i + 1]; ++k)
      m.value[std::size_t(i / m.block) * m.cells + f.column[k] / m.block] += f.value[k];
  // Divide by the pairs each tile covers (the last row and column of tiles may be short).
  for (int a = 0; a < m.cells; ++a)
    for (int b = 0; b < m.cells; ++b) {
      const int rows = std::min(f.n, (a + 1) * m.block) - a * m.block;
      const int cols = std::min(f.n, (b + 1) * m.block) - b * m.block;
      m.value[std::size_t(a) * m.cells + b] /= double(rows) * cols;
    }
  return m;
}

}  // namespace radkit::viewer
