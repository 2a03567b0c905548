// `radkit clouds` as one library call: a cloud layer (or a volume scene file's medium) under
// the physical sky, by the volumetric path tracer (the reference) and by the real-time model
// with each of its features switched on in turn, with error against time (docs/clouds.md).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "media/cloud_marcher.h"
#include "media/medium.h"

namespace radkit {

struct CloudsJobSettings {
  /// A volume scene file (medium, sun, camera, ground; docs/formats.md); empty: the layer.
  std::string scene;
  media::CloudLayerSettings layer;  ///< without a scene file; its seed is `seed`
  /// The layer's phase function (phase registry) and its parameters (empty: the function's own
  /// defaults). By default Henyey-Greenstein g = 0.86, the Mie cloud table's mean cosine, as a
  /// volume scene's medium without "phase" (docs/formats.md); HG, not the Mie table: the
  /// table's forward peak makes the reference's sun estimates fireflies.
  std::string phase = "henyey-greenstein", phaseParams = "g=0.86";
  int width = 128, height = 72;
  int samples = 32;  ///< reference paths per pixel
  // Unset: the scene file's value, else the default beside it.
  std::optional<double> sunElevationDeg;     ///< 40
  std::optional<double> sunAzimuthDeg;       ///< 150, clockwise from north
  std::optional<double> cameraElevationDeg;  ///< 25, looking north from the ground
  std::optional<double> fovDeg;              ///< 70, vertical
  double exposure = 0;                       ///< 0: automatic
  bool skyNee;  ///< reference: next-event estimation to the sky (CloudComparisonSettings)
  std::uint64_t seed = 1;      ///< the samples', and the layer's noise without a scene file
  media::MarchSettings march;  ///< the real-time model's steps and octaves
  std::string out = "out/clouds";
  CloudsJobSettings();
};

struct CloudsJobResult {
  std::string out;
  nlohmann::json report;  ///< report.json as written
};

/// \brief Writes the reference, real-time and difference images and report.json into `out`
/// (all or nothing). \throws InputError for a bad scene file or a medium too dense to trace.
CloudsJobResult runCloudsJob(const CloudsJobSettings& settings);

}  // namespace radkit
