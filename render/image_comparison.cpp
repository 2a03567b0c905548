#include "render/image_comparison.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace radkit {

std::vector<RegionError> compareToReference(const RadianceImage& image,
                                            const std::vector<RadianceImage>& refs,
                                            const std::vector<int>& region,
                                            const std::vector<std::string>& names) {
  const std::size_t n = image.radiance.size();
  if (refs.empty()) throw std::invalid_argument("compareToReference: no reference image");
  for (const RadianceImage& r : refs)
    if (r.width != image.width || r.height != image.height)
      throw std::invalid_argument("reference is " + std::to_string(r.width) + "x" +
                                  std::to_string(r.height) + ", the image " +
                                  std::to_string(image.width) + "x" + std::to_string(image.height));
  if (region.size() != n)
    throw std::invalid_argument("compareToReference: one region per pixel needed");
  struct Sums {
    double sq = 0, var = 0, ref = 0;
    int pixels = 0;
  };
  std::vector<Sums> sums(names.size() + 1);
  const double K = double(refs.size());
  for (std::size_t k = 0; k < n; ++k) {
    Sums pixel;
    for (int c = 0; c < 3; ++c) {
      double mean = 0, spread = 0;
      for (const RadianceImage& r : refs) mean += r.radiance[k][c];
      mean /= K;
      for (const RadianceImage& r : refs)
        spread += (r.radiance[k][c] - mean) * (r.radiance[k][c] - mean);
      // Unbiased variance of the K-render mean: Σ(r − r̄)² / (K(K − 1)).
      if (K > 1) pixel.var += spread / (K * (K - 1));
      const double e = image.radiance[k][c] - mean;
      pixel.sq += e * e;
      pixel.ref += mean;
    }
    auto add = [&](Sums& s) {
      s.sq += pixel.sq, s.var += pixel.var, s.ref += pixel.ref, ++s.pixels;
    };
    add(sums[0]);
    if (region[k] >= 0) add(sums[std::size_t(region[k]) + 1]);
  }
  std::vector<RegionError> out;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const Sums& s = sums[i];
    RegionError e;
    e.name = i == 0 ? "all" : names[i - 1];
    e.pixels = s.pixels;
    if (s.pixels > 0) {
      const double values = 3.0 * s.pixels;
      e.referenceMean = s.ref / values;
      e.rawRmse = std::sqrt(s.sq / values);
      e.referenceNoise = std::sqrt(s.var / values);
      e.rmse = std::sqrt(std::max(0.0, (s.sq - s.var) / values));
    }
    out.push_back(e);
  }
  return out;
}

std::vector<int> surfaceRegions(const std::vector<int>& surface, int width, int height,
                                int edgeRegion) {
  std::vector<int> out(surface.size(), -1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int s = surface[std::size_t(y) * width + x];
      if (s < 0) continue;
      bool alone = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && yy >= 0 && xx < width && yy < height &&
              surface[std::size_t(yy) * width + xx] != s)
            alone = false;
        }
      out[std::size_t(y) * width + x] = alone ? s : edgeRegion;
    }
  return out;
}

}  // namespace radkit
