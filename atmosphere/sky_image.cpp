// Sky images (sky_image.h).
#include "atmosphere/sky_image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace radkit::atmosphere {

const char* projectionName(SkyProjection projection) {
  switch (projection) {
    case SkyProjection::Fisheye:
      return "fisheye";
    case SkyProjection::Panorama:
      return "panorama";
    case SkyProjection::Camera:
      return "camera";
  }
  return "?";
}

std::optional<Vec3> pixelDirection(const SkyImageSettings& s, int column, int row) {
  const double u = 2 * (column + 0.5) / s.width - 1;  // −1 left .. 1 right
  const double v = 1 - 2 * (row + 0.5) / s.height;    // 1 top .. −1 bottom
  switch (s.projection) {
    case SkyProjection::Fisheye: {
      const double r = std::sqrt(u * u + v * v);
      if (r > 1) return std::nullopt;
      // Seen from below: north up, east left, so azimuth (clockwise from north, seen from
      // above) runs counter-clockwise in the image.
      const double zenith = r * kPi / 2, azimuth = std::atan2(-u, v);
      const double s0 = std::sin(zenith);
      return Vec3{s0 * std::sin(azimuth), s0 * std::cos(azimuth), std::cos(zenith)};
    }
    case SkyProjection::Panorama: {
      const double azimuth = (u + 1) * kPi, elevation = v * kPi / 2;
      return sunDirection(elevation * 180 / kPi, azimuth * 180 / kPi);
    }
    case SkyProjection::Camera: {
      const Vec3 forward = normalize(s.cameraDirection);
      const Vec3 up0 = std::fabs(forward.z) > 0.999999 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
      const Vec3 right = normalize(cross(forward, up0)), up = cross(right, forward);
      const double halfWidth = std::tan(s.fovDeg * kPi / 360);
      const double halfHeight = halfWidth * s.height / s.width;
      return normalize(forward + right * (u * halfWidth) + up * (v * halfHeight));
    }
  }
  return std::nullopt;
}

std::vector<Vec3> renderSky(const Atmosphere& atmosphere, const Vec3& sunLocal,
                            const SkyImageSettings& settings) {
  // The observer stands on the local frame's north pole, where local and planet axes agree.
  const Vec3 eye = atmosphere.pointAtAltitude(settings.altitude);
  const Vec3 sun = normalize(sunLocal);
  std::vector<Vec3> image(std::size_t(settings.width) * std::size_t(settings.height));
  tbb::parallel_for(tbb::blocked_range<int>(0, settings.height),
                    [&](const tbb::blocked_range<int>& rows) {
                      for (int row = rows.begin(); row < rows.end(); ++row)
                        for (int column = 0; column < settings.width; ++column)
                          if (const std::optional<Vec3> d = pixelDirection(settings, column, row))
                            image[std::size_t(row) * settings.width + column] =
                                atmosphere.skyRadiance(eye, *d, sun, settings.sky);
                    });
  return image;
}

SkyBenchmark benchmarkSky(const Atmosphere& atmosphere, const Vec3& sunLocal,
                          const SkyImageSettings& settings, std::vector<Vec3>* image) {
  SkyBenchmark b;
  for (int row = 0; row < settings.height; ++row)
    for (int column = 0; column < settings.width; ++column)
      b.viewRays += pixelDirection(settings, column, row).has_value();
  const Vec3 eye = atmosphere.pointAtAltitude(settings.altitude);
  if (settings.sky.multipleScattering)  // its tables are built once per atmosphere, not timed
    atmosphere.skyRadiance(eye, {0, 0, 1}, normalize(sunLocal), settings.sky);
  const auto start = std::chrono::steady_clock::now();
  std::vector<Vec3> pixels = renderSky(atmosphere, sunLocal, settings);
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  b.viewSamplePoints = b.viewRays * std::max(1, settings.sky.viewSamples);
  if (b.seconds > 0) {
    b.viewRaysPerSecond = b.viewRays / b.seconds;
    b.samplePointsPerSecond = b.viewSamplePoints / b.seconds;
  }
  if (image) *image = std::move(pixels);
  return b;
}

}  // namespace radkit::atmosphere
