#include "experiments/photon_comparison.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "util/output_folder.h"

namespace radkit {

namespace {

double ratioOrZero(double a, double b) { return b != 0 ? a / b : 0.0; }

Rgb8 diverging(double z) {
  // White at 0, toward blue (−) or red (+), saturating at |z| = 4.
  const double t = std::clamp(std::fabs(z) / 4, 0.0, 1.0);
  const auto fade = [&](double to) { return std::uint8_t(std::lround(255 + (to - 255) * t)); };
  return z < 0 ? Rgb8{fade(33), fade(102), fade(172)} : Rgb8{fade(178), fade(24), fade(43)};
}

}  // namespace

std::vector<SurfaceComparison> compareSurfaces(const std::vector<SurfaceEstimate>& photon,
                                               const std::vector<SurfaceRadiosity>& radiosity) {
  std::map<std::string, const SurfaceRadiosity*> byName;
  for (const SurfaceRadiosity& r : radiosity) byName[r.name] = &r;
  std::vector<SurfaceComparison> rows;
  for (const SurfaceEstimate& p : photon) {
    auto it = byName.find(p.name);
    if (it == byName.end())
      throw std::invalid_argument("the radiosity solution has no surface \"" + p.name +
                                  "\". Fix: compare with a run of the same scene");
    SurfaceComparison c;
    c.name = p.name;
    c.area = p.area;
    c.photon = p.radiosity;
    c.photonError = p.radiosityError;
    c.radiosity = it->second->radiosity;
    for (int k = 0; k < 3; ++k) {
      c.relativeDifference[k] = ratioOrZero(c.photon[k] - c.radiosity[k], c.radiosity[k]);
      c.zScore[k] = ratioOrZero(c.photon[k] - c.radiosity[k], c.photonError[k]);
    }
    rows.push_back(c);
  }
  return rows;
}

Canvas differenceImage(const RadianceImage& seen, const std::vector<Vec3>& photon,
                       const std::vector<Vec3>& photonError, const std::vector<Vec3>& radiosity,
                       const std::string& title) {
  const int legend = 40;
  Canvas c(seen.width, seen.height + legend, Rgb8{0, 0, 0});
  for (int y = 0; y < seen.height; ++y)
    for (int x = 0; x < seen.width; ++x) {
      const int p = seen.patch[std::size_t(y) * seen.width + x];
      if (p < 0) continue;
      // σ of the luminance: the channels' errors are fully correlated (one photon carries
      // all three), so σ_Y = Y(σ) bounds it from above.
      const double z =
          ratioOrZero(luminance(photon[p]) - luminance(radiosity[p]), luminance(photonError[p]));
      c.set(x, y, diverging(z));
    }
  const int y0 = seen.height + 4, barWidth = std::max(16, seen.width - 20);
  for (int x = 0; x < barWidth; ++x)
    c.fill(10 + x, y0, 11 + x, y0 + 10, diverging(-4 + 8.0 * x / (barWidth - 1)));
  const int scale = seen.width >= 400 ? 2 : 1;
  c.text(10, y0 + 13, "-4", scale, {255, 255, 255});
  c.text(10 + barWidth - Canvas::textWidth("+4", scale), y0 + 13, "+4", scale, {255, 255, 255});
  c.text(10 + barWidth / 2 - Canvas::textWidth(title, scale) / 2, y0 + 13, title, scale,
         {255, 255, 255});
  return c;
}

}  // namespace radkit
