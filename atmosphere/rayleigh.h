// The air's Rayleigh scattering as named models: its coefficient at the ground for the channels'
// wavelengths (kWavelengths) and its scale height. "bruneton" is Bruneton and Neyret 2008's Earth
// (radkit's default, which the atmosphere was validated with); "bodhaine" derives both from the
// physics of dry air as Bodhaine, Wood, Dutton and Slusser (1999) do: Peck and Reeder's
// refractive index with its dispersion and CO2 correction, King factors of N2, O2, Ar and CO2,
// and the column of a standard atmosphere, so its optical depth is theirs (docs/atmosphere.md).
#pragma once

#include <string>

#include "atmosphere/atmosphere.h"
#include "util/registry.h"
#include "util/vec3.h"

namespace radkit::atmosphere {

struct RayleighAir {
  Vec3 scattering;     ///< 1/m at the ground and standard density, per channel
  double scaleHeight;  ///< m
};

/// The Rayleigh models by name: bruneton (the default), bodhaine (parameter co2 in ppm, 360).
const Registry<RayleighAir>& rayleighRegistry();
/// \brief The model called `choice`, "name" or "name:key=value;...". \throws ParamError.
RayleighAir rayleighAir(const std::string& choice);

/// Bodhaine et al. (1999) for dry air with `co2` CO2 (fraction by volume) at wavelength λ (m):
struct BodhaineAir {
  double refractiveIndexMinusOne;  ///< n − 1 at 288.15 K and 1013.25 hPa (their eqs. 18, 19)
  double kingFactor;               ///< F(air), the gases' volume-weighted mean (eq. 23)
  double crossSection;             ///< σ per molecule (m², eq. 22)
  double opticalDepth;             ///< τ of the column at sea level, 1013.25 hPa, 45° (eq. 25)
};
BodhaineAir bodhaineAir(double wavelength, double co2 = 360e-6);

/// \brief Puts the model's coefficients and scale height into `parameters`.
inline void useRayleigh(AtmosphereParameters& parameters, const RayleighAir& air) {
  parameters.rayleighScattering = air.scattering;
  parameters.rayleighScaleHeight = air.scaleHeight;
}

/// \brief The vertical optical depth of Rayleigh scattering through the atmosphere's shell
/// (ground to top) for a coefficient that falls exponentially with its scale height.
Vec3 rayleighOpticalDepth(const Vec3& groundScattering, double scaleHeight, double shellHeight);

}  // namespace radkit::atmosphere
