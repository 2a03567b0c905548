// Final gather of a radiosity solution (the classic two-pass method's second pass): per
// camera sample, one BSDF-sampled bounce from the first non-delta surface that looks up the
// radiosity the solution reflects where it lands, and direct light by next-event estimation
// (both combined with the bounce's own hits on emitters by MIS). The patches' discretisation
// error is thereby averaged over the gathered hemisphere instead of being seen directly.
#pragma once

#include "render/shading.h"
#include "render/smooth_radiosity.h"

namespace radkit {

struct FinalGatherSettings {
  int width = 256;
  int height = 256;
  int samplesPerPixel = 16;  ///< camera samples per pixel, each one light and one gather ray
  std::uint64_t seed = 1;    ///< keys every pixel's numbers (stream 2)
  SamplerType sampler = SamplerType::Sobol;
  int maxSpecularDepth = 8;  ///< mirror/glass bounces followed before the gathering vertex
  bool smooth = true;        ///< look up the crease-aware smooth reconstruction, not flat B
  SmoothSettings smoothing;
};

/// \brief The final-gather image. `scene` must be built on the mesh the lighting was solved on.
MonteCarloImage renderFinalGather(const ShadingScene& scene, const Camera& camera, const RadiosityLighting& lighting,
                                  const FinalGatherSettings& settings);

}  // namespace radkit
