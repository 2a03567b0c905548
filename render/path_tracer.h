// Unbiased path tracing (Kajiya 1986) with next-event estimation, BSDF sampling, multiple
// importance sampling (power heuristic) and Russian roulette: the reference image every
// other mode (radiosity, two-pass shading, photon mapping) is measured against.
#pragma once

#include <cstdint>

#include "geometry/scene.h"
#include "render/shading_context.h"

namespace radkit {

struct PathTraceSettings {
  int width = 256;
  int height = 256;
  int samplesPerPixel = 16;  ///< camera paths per pixel, jittered over the pixel
  std::uint64_t seed = 1;    ///< keys every pixel's numbers (stream 0)
  SamplerType sampler = SamplerType::Sobol;
  int rouletteDepth = 3;  ///< bounces before Russian roulette may end a path
  int maxDepth = 1000;    ///< hard stop (a safety net; roulette ends paths long before)
};

/// \brief Radiance along one camera ray (W/m²/sr per channel): emission seen directly or
/// through delta lobes at full weight; at every other vertex, light sampling and BSDF
/// sampling combined by the power heuristic (Veach 1997, §9.2).
/// \param rays incremented by the rays cast (closest-hit and shadow)
Vec3 pathRadiance(const ShadingScene& scene, const Vec3& origin, const Vec3& dir, Sampler& sampler,
                  const PathTraceSettings& settings, long long& rays);

/// \brief Renders the camera view, rows in parallel (TBB). Deterministic for a seed,
/// whatever the thread count: each pixel's numbers depend on (seed, pixel, sample) only.
MonteCarloImage renderPathTraced(const ShadingScene& scene, const Camera& camera,
                                 const PathTraceSettings& settings);

}  // namespace radkit
