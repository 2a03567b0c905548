// Images of the sky from an observer on the ground: an all-sky fisheye, an equirectangular
// panorama and a pinhole camera, each pixel one view ray of Atmosphere::skyRadiance.
//
// Directions are in the observer's local frame: x east, y north, z up (sunDirection's).
//  - Fisheye: equidistant (distance from the centre proportional to the zenith angle), the
//    whole upper hemisphere in the inscribed circle, zenith at the centre, horizon on the
//    circle. Seen from below, as an all-sky camera pointing up sees it: north at the top,
//    east on the LEFT, south at the bottom, west on the right. Outside the circle: black.
//  - Panorama: equirectangular, azimuth 0° (north) at the left edge increasing to the right
//    (east at a quarter of the width, south at the middle), elevation +90° at the top row to
//    −90° at the bottom row, so the horizon is the middle row. Use width = 2·height for square
//    pixels.
//  - Camera: a pinhole looking along `cameraDirection` with `fovDeg` the horizontal field of
//    view, the image's up as close to the zenith as the view allows (north when looking
//    straight up or down); east is on the right when looking north.
// Below the horizon a view ray ends on the ground: the pixel shows skyRadiance along that ray,
// the airlight between the observer and the ground (nearly black from a few metres up). The
// ground's own reflected light is not drawn.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "atmosphere/atmosphere.h"

namespace radkit::atmosphere {

enum class SkyProjection { Fisheye, Panorama, Camera };

/// "fisheye", "panorama", "camera".
const char* projectionName(SkyProjection projection);

struct SkyImageSettings {
  SkyProjection projection = SkyProjection::Fisheye;
  int width = 512, height = 512;
  double altitude = 1;               ///< the observer's height above the ground (m)
  Vec3 cameraDirection{0, 1, 0.25};  ///< Camera: view direction (local frame, any length)
  double fovDeg = 90;                ///< Camera: horizontal field of view
  SkySettings sky;                   ///< the ray march's sample counts
};

/// \brief The unit view direction (local frame) through the centre of pixel (column, row),
/// row 0 at the top; nullopt outside the fisheye's circle.
std::optional<Vec3> pixelDirection(const SkyImageSettings& settings, int column, int row);

/// \brief Radiance (W m⁻² sr⁻¹ per channel) row-major, top row first; black where
/// pixelDirection has no direction. `sunLocal` is the sun's direction in the local frame.
/// TBB-parallel over rows; deterministic (no randomness).
std::vector<Vec3> renderSky(const Atmosphere& atmosphere, const Vec3& sunLocal,
                            const SkyImageSettings& settings);

/// Timing of one renderSky call (one view ray per pixel inside the image's field of view).
struct SkyBenchmark {
  double seconds = 0;
  long long viewRays = 0;          ///< pixels with a direction
  long long viewSamplePoints = 0;  ///< viewRays × viewSamples
  double viewRaysPerSecond = 0, samplePointsPerSecond = 0;
};
SkyBenchmark benchmarkSky(const Atmosphere& atmosphere, const Vec3& sunLocal,
                          const SkyImageSettings& settings, std::vector<Vec3>* image = nullptr);

}  // namespace radkit::atmosphere
