// The real-time cloud model (Schneider 2015; Hillaire 2016): ray marching a cloud medium with a
// fixed number of primary and light steps, Beer-Lambert transmittance, the multiple-scattering
// octaves of Wrenninge et al. (2017, "Oz: The Great and Volumetric", SIGGRAPH talk):
// L = Σ_i b^i σ_s L_sun p(θ, c^i g) exp(−a^i τ), an ambient term from sky and ground under
// homogeneous, isotropic assumptions, and blue-noise jitter of the ray starts. It is measured
// against media/volume_tracer.h's path tracer (`radkit clouds`, docs/clouds.md).
#pragma once

#include <cstdint>
#include <vector>

#include "media/volume_tracer.h"

namespace radkit::media {

struct MarchSettings {
  int primarySteps = 64;             ///< along the view ray's segment inside the medium's box
  int lightSteps = 6;                ///< towards the sun, to the box's boundary
  int octaves = 3;                   ///< multiple-scattering octaves; 1 is single scattering
  double a = 0.5, b = 0.5, c = 0.5;  ///< extinction, energy and anisotropy factors per octave
  bool ambient = true;               ///< the sky's and ground's light, isotropic and homogeneous
  bool jitter = true;                ///< offset each pixel's first step by a blue-noise value
  Vec3 ambientTop{0, 0, 0};          ///< mean radiance arriving from above (the sky)
  Vec3 ambientBottom{0, 0, 0};       ///< mean radiance arriving from below (the ground)
};

/// \brief The phase function with its asymmetry scaled by `scale` (an octave's c^i): each phase
/// function's evalAnisotropyScaled (HG and double HG scale their g; isotropic and Rayleigh
/// stay; a table becomes HG with the scaled mean cosine).
double scaledPhase(const PhaseFunction& phase, double cosTheta, double scale);

/// \brief Radiance arriving at o along −d (d the camera ray) by the real-time model; `offset`
/// in [0, 1) shifts the march's sample points by that fraction of a step.
Vec3 marchCloud(const Medium& medium, const Lighting& light, const Vec3& o, const Vec3& d,
                const MarchSettings& settings, double offset);

/// \brief A 64 × 64 tileable blue-noise dither by void-and-cluster (Ulichney 1993): ranks
/// 0..4095 divided by 4096, row-major. Deterministic per seed.
std::vector<double> blueNoiseTile(std::uint64_t seed);

/// \brief The whole image by marchCloud, parallel over rows; offsets from the blue-noise tile
/// (jitter) or ½ (no jitter).
VolumeImage renderMarched(const Medium& medium, const Lighting& light, const Vec3& eye,
                          const CameraRay& camera, int width, int height,
                          const MarchSettings& settings, std::uint64_t seed);

}  // namespace radkit::media
