// The brute-force reference for media: a volumetric path tracer (delta tracking for free paths,
// ratio tracking for transmittance, next-event estimation to the sun and, with a SkySampler, to
// the sky, combined with phase sampling by multiple importance sampling; an optional Lambertian
// ground at z = 0). Unbiased; grey media, RGB light.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "media/medium.h"
#include "util/sampling.h"

namespace radkit::media {

using SkyRadiance = std::function<Vec3(const Vec3& direction)>;

/// Light from outside the medium.
struct Lighting {
  Vec3 sunDirection{0, 0, 1};   ///< unit, towards the sun
  Vec3 sunIrradiance{0, 0, 0};  ///< W/m² on a plane facing the sun, outside the medium
  /// Radiance arriving from a direction (the sky; below the horizon the ground's glow or 0).
  SkyRadiance sky;
  /// Next-event estimation to the sky at every scattering event when set (built from `sky`);
  /// without it the sky is seen only where paths escape.
  std::shared_ptr<const SkySampler> skySampler;
  double groundAlbedo = 0;  ///< Lambertian ground at z = 0 (0: none, rays pass)
};

/// \brief Free-flight distance by delta tracking (Woodcock et al. 1965): the first real
/// collision along o + t·d in (0, tMax), or +∞ when the path leaves [0, tMax) unscattered.
double deltaTrack(const Medium& medium, const Vec3& o, const Vec3& d, double tMax, Rng& rng);
/// \brief Transmittance of [0, tMax) along the ray by ratio tracking (Novák et al. 2014):
/// unbiased, in [0, 1].
double ratioTrack(const Medium& medium, const Vec3& o, const Vec3& d, double tMax, Rng& rng);

/// \brief One path's radiance estimate arriving at o from direction −d (d the direction of the
/// camera ray). Russian roulette after `rouletteDepth` scattering events.
Vec3 traceVolumePath(const Medium& medium, const Lighting& light, const Vec3& o, const Vec3& d,
                     Rng& rng, int rouletteDepth = 8);

struct VolumeImage {
  int width = 0, height = 0;
  std::vector<Vec3> radiance;       ///< row-major, top row first
  std::vector<Vec3> standardError;  ///< per pixel, from the spread of its samples
  double seconds = 0;
  long long paths = 0;
};

/// Camera rays: the unit direction through pixel (x, y), (0, 0) the top-left corner.
using CameraRay = std::function<Vec3(double x, double y)>;

/// \brief `samples` paths per pixel (jittered in the pixel), parallel over rows, per-pixel
/// streams Rng(seed, pixel, 0): the same seed gives the same image on any number of threads.
VolumeImage renderVolume(const Medium& medium, const Lighting& light, const Vec3& eye,
                         const CameraRay& camera, int width, int height, int samples,
                         std::uint64_t seed);

}  // namespace radkit::media
