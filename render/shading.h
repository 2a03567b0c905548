// Two-pass shading (Wallace, Cohen & Greenberg 1987, in its simplest form): the first pass
// is the radiosity solution; the second, per pixel, adds what a BRDF model sees that
// radiosity cannot: direct light from the area lights through Phong or Cook-Torrance
// (Embree shadow rays, light and BRDF sampling combined by MIS), mirror and glass chains,
// and glossy reflections of the radiosity solution. Indirect diffuse light comes from the
// solution: ρ_d/π · H_indirect per patch, H_indirect = F·B − F·E.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/radiosity_pipeline.h"
#include "render/shading_context.h"

namespace radkit {

struct TwoPassSettings {
  int width = 256;
  int height = 256;
  int samplesPerPixel = 16;  ///< camera samples per pixel, each with one light and one BSDF sample
  std::uint64_t seed = 1;    ///< keys every pixel's numbers (stream 1)
  SamplerType sampler = SamplerType::Sobol;
  int maxSpecularDepth = 8;  ///< mirror/glass bounces followed before a path is dropped
};

/// What the second pass reads from the first, per patch of the mesh it was solved on.
struct RadiosityLighting {
  std::vector<Vec3> radiosity;           ///< B, W/m²
  std::vector<Vec3> emission;            ///< E, W/m²
  std::vector<Vec3> indirectIrradiance;  ///< F·B − F·E, W/m²
};

/// \brief B, E and F·B − F·E of a pipeline run (one extra pass over F for F·E).
RadiosityLighting radiosityLighting(const PipelineResult& result);

/// \brief The two-pass image. `scene` must be built on the mesh the lighting was solved on.
MonteCarloImage renderTwoPass(const ShadingScene& scene, const Camera& camera,
                              const RadiosityLighting& lighting, const TwoPassSettings& settings);

}  // namespace radkit
