// A spherical planet with a Rayleigh and Mie atmosphere (Nishita et al. 1993; Bruneton and
// Neyret 2008's Earth defaults): phase functions, optical depth, sun transmittance and the sky's
// radiance by single scattering with an optional multiple-scattering term (Hillaire 2020).
// Three channels, the wavelengths of kWavelengths. Lengths in metres; positions planet-centred.
#pragma once

#include <cstdint>
#include <memory>

#include "phase/closed_form.h"
#include "util/vec3.h"

namespace radkit::atmosphere {

/// The channels' wavelengths in metres (R, G, B).
constexpr double kWavelengths[3] = {680e-9, 550e-9, 440e-9};

/// \brief Rayleigh volume scattering coefficient (1/m) of air whose refractive index at standard
/// density is `refractiveIndex` and whose number density is `numberDensity` (1/m³) times
/// `relativeDensity`: 8π³(n²−1)²/(3Nλ⁴)·King factor, with n − 1 proportional to the density
/// (Lorentz-Lorenz), so the coefficient grows linearly with pressure.
double rayleighCoefficient(double wavelength, double refractiveIndex, double numberDensity,
                           double relativeDensity = 1);

struct AtmosphereParameters {
  double groundRadius = 6360e3;
  double topRadius = 6420e3;
  /// Air density at the ground over the standard one (pressure at fixed temperature); scales
  /// Rayleigh and Mie coefficients alike.
  double relativeDensity = 1;
  Vec3 rayleighScattering{5.8e-6, 13.5e-6, 33.1e-6};  ///< at the ground, standard density
  double rayleighScaleHeight = 8000;
  double mieScattering = 21e-6;  ///< at the ground, the same in every channel
  double mieExtinction = 21e-6 / 0.9;
  double mieScaleHeight = 1200;
  double mieG = 0.76;
  /// Sun irradiance at the top of the atmosphere (W/m² per channel) and its disc. The
  /// channels follow the solar spectrum at kWavelengths (1.50, 1.86, 1.76 W m⁻² nm⁻¹, ASTM
  /// E-490), scaled so that 683·Y = 133.8 klx, the luminous solar constant (Darula, Kittler and
  /// Gueymard 2005), with radkit's photometry (docs/formats.md, Units).
  Vec3 solarIrradiance{165.4, 205.1, 194.1};
  double sunAngularRadius = 0.004675;
  double groundAlbedo = 0.3;  ///< Lambertian ground (multiple scattering and the reference)
};

/// Sample counts of the sky's ray march.
struct SkySettings {
  int viewSamples = 32;  ///< along the view ray
  int lightSamples = 8;  ///< along each sample's ray to the sun
  bool multipleScattering = true;
};

class MultipleScatteringLut;

class Atmosphere {
 public:
  explicit Atmosphere(const AtmosphereParameters& parameters = {});
  ~Atmosphere();
  Atmosphere(Atmosphere&&) noexcept;
  Atmosphere& operator=(Atmosphere&&) noexcept;

  const AtmosphereParameters& parameters() const { return m_p; }

  /// Coefficients (1/m) at altitude h above the ground.
  Vec3 rayleighScatteringAt(double h) const;
  double mieScatteringAt(double h) const;
  Vec3 extinctionAt(double h) const;

  /// Optical depth of the segment a→b, per channel, by numerical integration.
  Vec3 opticalDepth(const Vec3& a, const Vec3& b) const;
  /// Transmittance from p along unit d to the top of the atmosphere; zero when the ray meets
  /// the ground (the planet's shadow).
  Vec3 transmittanceToTop(const Vec3& p, const Vec3& d) const;
  /// Irradiance on a plane facing the sun at p (W/m² per channel): solarIrradiance times
  /// transmittanceToTop(p, sunDir).
  Vec3 sunIrradiance(const Vec3& p, const Vec3& sunDir) const;
  /// Sky radiance (W m⁻² sr⁻¹ per channel) seen from p along unit `dir`, sun's disc excluded.
  Vec3 skyRadiance(const Vec3& p, const Vec3& dir, const Vec3& sunDir,
                   const SkySettings& settings = {}) const;

  /// A point at altitude h above the ground's north pole (the frame of localToPlanet).
  Vec3 pointAtAltitude(double h) const { return {0, 0, m_p.groundRadius + h}; }

 private:
  /// The transmittance and multiple-scattering tables, built once on first use under a
  /// std::once_flag: skyRadiance may be called from many threads at once.
  struct Tables;
  const MultipleScatteringLut& multipleScattering() const;

  AtmosphereParameters m_p;
  std::unique_ptr<Tables> m_tables;
};

/// Sun direction in the local frame (x east, y north, z up) from elevation and azimuth in
/// degrees (azimuth clockwise from north, so 90° is east).
Vec3 sunDirection(double elevationDeg, double azimuthDeg);

/// A brute-force estimate of the sky's radiance: a volumetric path tracer through the same
/// spherical atmosphere (delta tracking, next-event estimation to the sun, Lambertian ground).
struct ReferenceEstimate {
  Vec3 mean, standardError;
  long long paths = 0;
};
ReferenceEstimate referenceSkyRadiance(const Atmosphere& atmosphere, const Vec3& p, const Vec3& dir,
                                       const Vec3& sunDir, long long paths, std::uint64_t seed);

}  // namespace radkit::atmosphere
