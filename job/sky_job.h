// `radkit sky` as one library call: images of the physically based sky of atmosphere/
// (fisheye, panorama and camera views as PFM and PNG, optionally OpenEXR) with their timing,
// radiance and irradiance figures, and optionally the model against the reference path tracer.
// The command line and the Python module's sky() call it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "atmosphere/atmosphere.h"

namespace radkit {

struct SkyJobSettings {
  double sunElevationDeg = 30, sunAzimuthDeg = 180;  ///< azimuth clockwise from north
  double relativeDensity = 1;  ///< air density over the standard one (Rayleigh and Mie alike)
  /// The Rayleigh model (atmosphere/rayleigh.h): "bruneton" or "bodhaine[:co2=ppm]".
  std::string rayleigh = "bruneton";
  double altitude = 1;  ///< the observer's height above the ground, m
  atmosphere::SkySettings sky;
  int size = 512;  ///< image height in pixels; the panorama is twice as wide
  /// Which images: "fisheye", "panorama", "camera" or "all".
  std::string projection = "all";
  double cameraAzimuthDeg = 180, cameraElevationDeg = 20;  ///< the camera view's direction
  double fovDeg = 90;   ///< the camera view's horizontal field of view
  double exposure = 0;  ///< radiance multiplier before tone mapping; 0: automatic per image
  bool exr = false;     ///< also each image as OpenEXR
  /// Reference paths per direction for the comparison with the path tracer; 0: none.
  long long comparePaths = 0;
  std::vector<double> compareElevationsDeg{2, 10, 30, 60, 90};
  std::uint64_t seed = 1;  ///< the reference path tracer's
  std::string out = "out/sky";
};

struct SkyJobResult {
  std::string out;
  nlohmann::json report;        ///< report.json as written
  std::string comparisonTable;  ///< comparison.md, when compared
};

/// \brief Writes the sky's images and report.json into `out` (all or nothing).
/// \throws std::invalid_argument for an unusable setting, naming it.
SkyJobResult runSkyJob(const SkyJobSettings& settings);

}  // namespace radkit
