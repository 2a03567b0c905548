#include "render/sky_panorama.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace radkit {

Vec3 panoramaDirection(const SkyModel& sky, double u, double v) {
  const double bearing = 2 * M_PI * u, elevation = (0.5 - v) * M_PI;
  const double horizontal = std::cos(elevation);
  return sky.toScene(
      {horizontal * std::sin(bearing), horizontal * std::cos(bearing), std::sin(elevation)});
}

RadianceImage skyPanorama(const SkyModel& sky, int width) {
  RadianceImage image;
  image.width = width;
  image.height = width / 2;
  image.radiance.resize(std::size_t(image.width) * image.height);
  image.patch.assign(image.radiance.size(), -1);
  const double cosSun = sky.sunCosRadius();
  const bool sun = sky.hasSun() && maxComponent(sky.sunIrradiance()) > 0;
  std::vector<char> inSun(image.radiance.size(), 0);
  tbb::parallel_for(0, image.height, [&](int y) {
    for (int x = 0; x < image.width; ++x) {
      const Vec3 d = panoramaDirection(sky, (x + 0.5) / image.width, (y + 0.5) / image.height);
      const std::size_t i = std::size_t(y) * image.width + x;
      image.radiance[i] = sky.radiance(d);
      if (sun && dot(d, sky.sunDirection()) >= cosSun) inSun[i] = 1;
    }
  });
  if (!sun) return image;
  // The disc's irradiance E over the pixels it covers: each gets E / (their solid angle), so
  // a disc smaller than a pixel is not lost and one larger keeps its radiance.
  const double pixelAngle = 2 * M_PI / image.width;
  auto solidAngle = [&](int y) {  // of a pixel in row y: Δφ (sin e_top − sin e_bottom)
    const double top = (0.5 - double(y) / image.height) * M_PI;
    const double bottom = (0.5 - double(y + 1) / image.height) * M_PI;
    return pixelAngle * (std::sin(top) - std::sin(bottom));
  };
  double covered = 0;
  for (std::size_t i = 0; i < inSun.size(); ++i)
    if (inSun[i]) covered += solidAngle(int(i / image.width));
  if (covered == 0) {  // no pixel centre in the disc: the pixel holding its centre takes it
    const Vec3 local = sky.toLocal(sky.sunDirection());
    double bearing = std::atan2(local.x, local.y);
    if (bearing < 0) bearing += 2 * M_PI;
    const double elevation = std::asin(std::clamp(local.z, -1.0, 1.0));
    const int x = std::clamp(int(bearing / (2 * M_PI) * image.width), 0, image.width - 1);
    const int y = std::clamp(int((0.5 - elevation / M_PI) * image.height), 0, image.height - 1);
    inSun[std::size_t(y) * image.width + x] = 1;
    covered = solidAngle(y);
  }
  for (std::size_t i = 0; i < inSun.size(); ++i)
    if (inSun[i]) image.radiance[i] += sky.sunIrradiance() / covered;
  return image;
}

}  // namespace radkit
