// The real-time cloud model against the volumetric path tracer (`radkit clouds`,
// docs/clouds.md): a medium under the physical sky and sun, rendered by the reference and by
// the model with its features switched on one by one, then with fewer and more steps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "media/cloud_marcher.h"
#include "media/medium.h"
#include "media/volume_tracer.h"
#include "render/camera.h"

namespace radkit {

struct CloudComparisonSettings {
  int width = 128, height = 72;
  int samples = 32;  ///< the reference's paths per pixel
  std::uint64_t seed = 1;
  double sunElevationDeg = 40, sunAzimuthDeg = 150;
  double groundAlbedo = 0;  ///< Lambertian ground at z = 0 (0: none)
  /// Next-event estimation to the sky in the reference: on cumulus, stratus and haze it cost
  /// 30-80 % more time for no less noise (docs/clouds.md); it pays where a small bright part
  /// of the sky dominates.
  bool skyNee = false;
  media::MarchSettings march;  ///< the model's defaults; the ambient terms are set from the sky
  Camera camera;
};

/// One configuration of the real-time model and its error against the reference.
struct CloudVariant {
  std::string name;
  media::MarchSettings settings;
  media::VolumeImage image;
  double relativeRmse = 0;  ///< over pixels and channels, relative to the reference's mean
  double relativeBias = 0;  ///< (Σ model − Σ reference)/Σ reference
};

struct CloudComparison {
  media::Lighting light;  ///< the sun and sky both renderers saw
  media::VolumeImage reference;
  double referenceMean = 0;  ///< mean radiance over pixels and channels
  /// The RMSE an exact image would show against the reference (its own noise), relative to
  /// its mean.
  double referenceNoise = 0;
  std::vector<CloudVariant> variants;  ///< single scattering, + ambient, + octaves, + jitter, ...
  int defaults = 0;                    ///< the variant with the model's default settings
};

/// \brief Renders `medium` both ways. Deterministic for a fixed seed.
CloudComparison compareCloudModels(const media::Medium& medium,
                                   const CloudComparisonSettings& settings);

}  // namespace radkit
