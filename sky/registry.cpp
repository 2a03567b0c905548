// The one table of sky models (as bsdf/registry.cpp).
#include "sky/sky_radiance.h"

namespace radkit {

// Defined in each model's own .cpp.
std::unique_ptr<SkyRadiance> createUniformSky(Params& params);
std::unique_ptr<SkyRadiance> createCieOvercastSky(Params& params);
std::unique_ptr<SkyRadiance> createPhysicalSky(Params& params);

const SkyRegistry& skyRegistry() {
  static const SkyRegistry registry(
      "sky model",
      {
          {"uniform", createUniformSky,
           "the same radiance from every direction; radiance (W m⁻² sr⁻¹) or luminance (cd/m²)",
           "luminance=3183"},
          {"cie-overcast", createCieOvercastSky,
           "the CIE standard overcast sky, L = L_z (1 + 2 cos θ)/3; zenith_radiance or "
           "zenith_luminance",
           "zenith_luminance=4093"},
          {"physical", createPhysicalSky,
           "Rayleigh and Mie scattering of the atmosphere (atmosphere/) for the scene's sun, which "
           "it also makes; density (1, over the standard one), altitude (0 m), rayleigh "
           "(bruneton, or bodhaine[:co2=ppm])",
           ""},
      });
  return registry;
}

}  // namespace radkit
